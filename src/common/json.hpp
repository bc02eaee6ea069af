// actionstring host library — writing JSON: one writer for every JSON file the
// tools produce, so commas, escapes and numbers are right everywhere.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace actionstring {
namespace host {

/// A JSON string literal (quotes included) that is valid UTF-8 whatever the
/// input: control characters escaped, and every byte that is not part of a
/// well-formed UTF-8 sequence read as Latin-1 (as HDM05's files are).
std::string json_string(std::string_view text);

/// Builds one JSON document. Values and keys are added in order; the writer
/// places commas and, in objects, expects key() before each value.
/// Non-finite numbers become null (JSON has no infinity).
class JsonWriter {
public:
    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    JsonWriter& key(std::string_view name);
    JsonWriter& value(double number);
    JsonWriter& value(int number) { return value(static_cast<long long>(number)); }
    JsonWriter& value(long number) { return value(static_cast<long long>(number)); }
    JsonWriter& value(long long number);
    JsonWriter& value(unsigned long number);
    JsonWriter& value(bool flag);
    JsonWriter& value(std::string_view text);
    JsonWriter& value(const char* text) { return value(std::string_view(text)); }
    JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
    JsonWriter& null();
    /// A value already written as JSON (from another writer's str()).
    JsonWriter& raw(std::string_view json);
    /// key(name).value(v) in one call.
    template <class T>
    JsonWriter& field(std::string_view name, const T& v) {
        return key(name).value(v);
    }
    /// An array of numbers or strings.
    template <class T>
    JsonWriter& array(const std::vector<T>& values) {
        begin_array();
        for (const T& v : values) value(v);
        return end_array();
    }
    /// The document, with a final newline when it is complete.
    std::string str() const;

private:
    void before_value();
    std::string out_;
    std::vector<bool> first_;  // per open container: nothing written in it yet
    bool after_key_ = false;
};

}  // namespace host
}  // namespace actionstring
