// C and C++ source text for generated files.
#include "common/cpp_literals.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>

namespace actionstring {
namespace host {

std::string hex_float(float v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%a", static_cast<double>(v));
    return buffer;
}

std::string float_literal(float v) {
    if (std::isinf(v)) return v > 0 ? "::actionstring::detail::infinity()" : "-::actionstring::detail::infinity()";
    return hex_float(v) + "f";
}

std::string c_string(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += ch;
        } else if (c < 0x20 || c >= 0x7F) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\%03o", c);
            out += buffer;
        } else {
            out += ch;
        }
    }
    return out + "\"";
}

namespace {

bool is_keyword(const std::string& word) {
    static const char* const keywords[] = {
        "alignas",     "alignof",   "and",        "and_eq",    "asm",      "auto",         "bitand",
        "bitor",       "bool",      "break",      "case",      "catch",    "char",         "char8_t",
        "char16_t",    "char32_t",  "class",      "compl",     "concept",  "const",        "consteval",
        "constexpr",   "constinit", "const_cast", "continue",  "co_await", "co_return",    "co_yield",
        "decltype",    "default",   "delete",     "do",        "double",   "dynamic_cast", "else",
        "enum",        "explicit",  "export",     "extern",    "false",    "float",        "for",
        "friend",      "goto",      "if",         "inline",    "int",      "long",         "mutable",
        "namespace",   "new",       "noexcept",   "not",       "not_eq",   "nullptr",      "operator",
        "or",          "or_eq",     "private",    "protected", "public",   "register",     "reinterpret_cast",
        "requires",    "return",    "short",      "signed",    "sizeof",   "static",       "static_assert",
        "static_cast", "struct",    "switch",     "template",  "this",     "thread_local", "throw",
        "true",        "try",       "typedef",    "typeid",    "typename", "union",        "unsigned",
        "using",       "virtual",   "void",       "volatile",  "wchar_t",  "while",        "xor",
        "xor_eq"};
    for (const char* keyword : keywords)
        if (word == keyword) return true;
    return false;
}

bool is_identifier(const std::string& word) {
    if (word.empty() || std::isdigit(static_cast<unsigned char>(word[0]))) return false;
    for (const char c : word)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    return !is_keyword(word);
}

}  // namespace

bool is_cpp_namespace(const std::string& text) {
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find("::", start);
        if (!is_identifier(text.substr(start, end == std::string::npos ? std::string::npos : end - start)))
            return false;
        if (end == std::string::npos) return true;
        start = end + 2;
    }
}

std::string comment_text(const std::string& text) {
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c == 0x7F || c == '\\') {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
            out += buffer;
        } else {
            out += ch;
        }
    }
    return out;
}

}  // namespace host
}  // namespace actionstring
