// actionstring host library — C and C++ source text for generated files.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace actionstring {
namespace host {

/// C99 hexadecimal float (exact), or "inf" / "-inf".
std::string hex_float(float v);
/// A float literal for generated C++: hex float with an `f` suffix, or the runtime's infinity().
std::string float_literal(float v);
/// A C string literal: quotes, backslashes, control and non-ASCII bytes escaped.
std::string c_string(const std::string& text);
/// True for a C++ namespace name: identifiers joined by `::`, none a keyword.
bool is_cpp_namespace(const std::string& text);
/// A one-line comment text: control bytes (newlines among them) escaped, so
/// nothing written after `//` can end the comment.
std::string comment_text(const std::string& text);

/// Appends `inline constexpr TYPE NAME[N] = {…};`, eight values a line, each
/// through `format`; nothing for an empty array (the caller writes nullptr).
template <class T, class Format>
void put_cpp_array(std::ostringstream& out, const std::string& type, const std::string& name,
                   const std::vector<T>& values, Format format, const char* prefix = "") {
    if (values.empty()) return;
    out << prefix << "inline constexpr " << type << ' ' << name << "[" << values.size() << "] = {";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i % 8 == 0) out << "\n    ";
        out << format(values[i]) << (i + 1 < values.size() ? ", " : "");
    }
    out << "\n};\n";
}

}  // namespace host
}  // namespace actionstring
