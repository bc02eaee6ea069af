// The model artifact: every schema field as one text line, checksummed.
#include "model/artifact.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "actionstring/model.hpp"
#include "common/cpp_literals.hpp"
#include "io/text.hpp"
#include "model/blob.hpp"

namespace actionstring {
namespace host {
namespace {

const char kMagic[] = "actionstring-model";

// Reads the fields in the order serialize_model() writes them.
class FieldReader {
public:
    FieldReader(LineScanner& scanner) : scanner_(scanner) {}

    std::vector<std::string_view> line(const char* name) {
        std::string_view text;
        if (!scanner_.next(text))
            scanner_.fail(std::string("file ends where '") + name + "' was expected (truncated?)");
        words_ = split_words(text);
        if (words_.empty() || words_[0] != name)
            scanner_.fail(std::string("expected '") + name + "', got " +
                          quoted(words_.empty() ? std::string_view() : words_[0]));
        return words_;
    }
    long integer(const char* name, long low, long high) {
        const auto words = line(name);
        if (words.size() != 2) scanner_.fail(std::string("expected one value for '") + name + "'");
        return checked(words[1], name, low, high);
    }
    float real(const char* name) {
        const auto words = line(name);
        if (words.size() != 2) scanner_.fail(std::string("expected one value for '") + name + "'");
        return to_float(words[1], name);
    }
    template <class T>
    std::vector<T> ints(const char* name, long low, long high) {
        const auto words = count_line(name);
        std::vector<T> out;
        for (std::size_t i = 2; i < words.size(); ++i)
            out.push_back(static_cast<T>(checked(words[i], name, low, high)));
        return out;
    }
    std::vector<float> floats(const char* name) {
        const auto words = count_line(name);
        std::vector<float> out;
        for (std::size_t i = 2; i < words.size(); ++i) out.push_back(to_float(words[i], name));
        return out;
    }
    std::string rest_of_line() {
        std::string_view text;
        if (!scanner_.next(text)) scanner_.fail("file ends inside the label names (truncated?)");
        return std::string(text);
    }
    LineScanner& scanner() { return scanner_; }

private:
    std::vector<std::string_view> count_line(const char* name) {
        const auto words = line(name);
        if (words.size() < 2) scanner_.fail(std::string("expected a count for '") + name + "'");
        const long count = checked(words[1], name, 0, 100000000);
        if (static_cast<std::size_t>(count) != words.size() - 2)
            scanner_.fail(std::string("'") + name + "' declares " + std::to_string(count) + " values but has " +
                          std::to_string(words.size() - 2));
        return words;
    }
    long checked(std::string_view token, const char* name, long low, long high) {
        char* end = nullptr;
        const std::string text(token);
        const long long v = std::strtoll(text.c_str(), &end, 10);
        if (end == text.c_str() || *end != '\0' || v < low || v > high)
            scanner_.fail(std::string("expected an integer in [") + std::to_string(low) + ", " + std::to_string(high) +
                          "] for '" + name + "', got " + quoted(token));
        return static_cast<long>(v);
    }
    float to_float(std::string_view token, const char* name) {
        const std::string text(token);
        char* end = nullptr;
        const float v = std::strtof(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || std::isnan(v))
            scanner_.fail(std::string("expected a number for '") + name + "', got " + quoted(token));
        return v;
    }
    LineScanner& scanner_;
    std::vector<std::string_view> words_;
};

template <class T>
void put_scalar(std::ostringstream& out, const char* name, T value) {
    out << name << ' ';
    if constexpr (std::is_floating_point_v<T>) out << hex_float(value);
    else out << static_cast<long long>(value);
    out << '\n';
}

template <class T>
void put_table(std::ostringstream& out, const char* name, const std::vector<T>& values) {
    out << name << ' ' << values.size();
    for (const T v : values) {
        if constexpr (std::is_floating_point_v<T>) out << ' ' << hex_float(v);
        else out << ' ' << static_cast<long long>(v);
    }
    out << '\n';
}

void put_names(std::ostringstream& out, const char* name, const NameList& names) {
    out << name << ' ' << names.size() << '\n';
    for (const std::string& label : names) out << label << '\n';
}

template <class T>
T read_scalar(FieldReader& f, const char* name, long low, long high) {
    if constexpr (std::is_floating_point_v<T>) return f.real(name);
    else return static_cast<T>(f.integer(name, low, high));
}

template <class T>
std::vector<T> read_table(FieldReader& f, const char* name, long low, long high) {
    if constexpr (std::is_floating_point_v<T>) return f.floats(name);
    else return f.ints<T>(name, low, high);
}

void read_names(FieldReader& f, const char* name, NameList& names) {
    const long count = f.integer(name, 1, 65535);
    for (long l = 0; l < count; ++l) names.push_back(f.rest_of_line());
}

// Every field in schema order, then the end marker.
std::string write_fields(const ModelData& m) {
    for (const auto& name : m.label_names)
        if (name.empty() || name.find_first_of("\r\n") != std::string::npos)
            throw std::invalid_argument("label names must be non-empty single lines");
    std::ostringstream out;
#define ACTIONSTRING_PUT_SCALAR(T, FIELD, INITIAL, LOW, HIGH) put_scalar(out, #FIELD, m.FIELD);
#define ACTIONSTRING_PUT_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_PUT_TABLE(T, FIELD, SIZE, LOW, HIGH) put_table(out, #FIELD, m.FIELD);
#define ACTIONSTRING_PUT_NAMES(FIELD, COUNT) put_names(out, #FIELD, m.FIELD);
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_PUT_SCALAR, ACTIONSTRING_PUT_COUNT, ACTIONSTRING_PUT_TABLE,
                              ACTIONSTRING_PUT_NAMES)
#undef ACTIONSTRING_PUT_SCALAR
#undef ACTIONSTRING_PUT_COUNT
#undef ACTIONSTRING_PUT_TABLE
#undef ACTIONSTRING_PUT_NAMES
    out << "end\n";
    return out.str();
}

// The format version that added a field (0: every version this build reads).
// A file of an earlier version lacks the field, which keeps its initial value.
int field_since(std::string_view name) {
    if (name == "acceleration_weight") return 7;
    if (name == "min_action_us") return 8;
    if (name == "exemplar_dim") return 9;
    if (name.substr(0, 9) == "direction") return 12;
    if (name.substr(0, 10) == "descriptor") return 10;
    if (name == "label_lead_us") return 11;
    if (name == "settle_stable_us") return 13;
    if (name.substr(0, 16) == "window_direction" || name == "segment_direction_weight") return 14;
    return name.find("exemplar") != std::string_view::npos ? 6 : 0;
}

ModelData read_fields(FieldReader& f, int version = artifact_version) {
    ModelData m;
#define ACTIONSTRING_GET_SCALAR(T, FIELD, INITIAL, LOW, HIGH) \
    if (version >= field_since(#FIELD)) m.FIELD = read_scalar<T>(f, #FIELD, LOW, HIGH);
#define ACTIONSTRING_GET_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_GET_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    if (version >= field_since(#FIELD)) m.FIELD = read_table<T>(f, #FIELD, LOW, HIGH);
#define ACTIONSTRING_GET_NAMES(FIELD, COUNT) read_names(f, #FIELD, m.FIELD);
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_GET_SCALAR, ACTIONSTRING_GET_COUNT, ACTIONSTRING_GET_TABLE,
                              ACTIONSTRING_GET_NAMES)
#undef ACTIONSTRING_GET_SCALAR
#undef ACTIONSTRING_GET_COUNT
#undef ACTIONSTRING_GET_TABLE
#undef ACTIONSTRING_GET_NAMES
    f.line("end");
    return m;
}

std::string hex64(std::uint64_t v) {
    char buffer[24];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, v);
    return buffer;
}

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
    std::uint64_t hash = 14695981039346656037ull;
    for (const char c : bytes) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ull;
    }
    return hash;
}

std::string serialize_fields(const ModelData& model) { return write_fields(model); }

ModelData parse_fields(const std::string& name, std::string_view fields) {
    LineScanner scanner(name, fields);
    FieldReader f(scanner);
    return read_fields(f);
}

std::string serialize_model(const ModelData& model) {
    const std::string body = write_fields(model);
    return std::string(kMagic) + " " + std::to_string(artifact_version) + "\nchecksum fnv1a64 " + hex64(fnv1a64(body)) +
           "\n" + body;
}

std::string artifact_checksum(std::string_view text) {
    LineScanner scanner("artifact", text);
    std::string_view line;
    scanner.next(line);
    if (!scanner.next(line)) return {};
    const auto words = split_words(line);
    return words.size() == 3 ? std::string(words[2]) : std::string();
}

ModelData parse_model(const std::string& name, std::string_view text) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next(line)) scanner.fail_at(0, "empty file: expected an actionstring model");
    const auto magic = split_words(line);
    if (magic.size() != 2 || magic[0] != kMagic)
        scanner.fail("not an actionstring model (expected 'actionstring-model <version>')");
    // Version 4 differs only in the order of gmm_factors (component by
    // component); it is read and reordered, and version 5 lacks only the
    // exemplars and 6 the acceleration's weight (field_since()), so a model
    // trained before keeps working.
    int version = 0;
    for (int v = 4; v <= artifact_version; ++v)
        if (magic[1] == std::to_string(v)) version = v;
    if (version == 0)
        scanner.fail("model format version " + std::string(magic[1]) +
                     " is not supported; this build reads versions 4 to " + std::to_string(artifact_version) +
                     " (retrain or use a matching build)");
    const bool component_major_factors = version == 4;
    if (!scanner.next(line)) scanner.fail("file ends where the checksum was expected (truncated?)");
    const auto checksum = split_words(line);
    if (checksum.size() != 3 || checksum[0] != "checksum" || checksum[1] != "fnv1a64")
        scanner.fail("expected 'checksum fnv1a64 <hex>'");
    const std::size_t body_start = static_cast<std::size_t>(line.data() + line.size() - text.data()) + 1;
    const std::string_view body = body_start <= text.size() ? text.substr(body_start) : std::string_view();
    if (hex64(fnv1a64(body)) != checksum[2])
        scanner.fail("checksum mismatch: the file is corrupt or was edited (expected " + std::string(checksum[2]) +
                     ", got " + hex64(fnv1a64(body)) + ")");

    FieldReader f(scanner);
    ModelData m = read_fields(f, version);
    // A table of the wrong size is left for check_model() to report.
    if (component_major_factors && mismatched_table(m) == nullptr) interleave_gmm_factors(m);

    check_model(m, name);
    return m;
}

void save_model(const ModelData& model, const std::string& path) { write_file(path, serialize_model(model)); }

ModelData load_model(const std::string& path) {
    const std::string bytes = read_file(path);
    return looks_like_blob(bytes) ? read_blob(path, bytes) : parse_model(path, bytes);
}

}  // namespace host
}  // namespace actionstring
