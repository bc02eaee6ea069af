// The model schema (model_schema.hpp) drives the view, the owning data, the
// artifact and the header generator. These tests walk the schema itself, so a
// field added there is checked here without a line of test code.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "model/artifact.hpp"
#include "model/header.hpp"
#include "model/model_data.hpp"
#include "toy/toy.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// A value of type T in [low, high] (integers and enums) or any float.
template <class T>
T random_value(std::mt19937_64& rng, long long low, long long high) {
    if constexpr (std::is_floating_point_v<T>) {
        return std::uniform_real_distribution<T>(-1e3f, 1e3f)(rng);
    } else {
        return static_cast<T>(std::uniform_int_distribution<long long>(low, high)(rng));
    }
}

template <class T>
bool same(const T& a, const T& b) {
    if constexpr (std::is_floating_point_v<T>) return std::memcmp(&a, &b, sizeof a) == 0;  // bit for bit
    else return a == b;
}

template <class T>
bool same_table(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!same(a[i], b[i])) return false;
    return true;
}

// Every field filled with random values in its range (tables of three
// elements): not a valid model, but every value one the artifact can hold.
ModelData random_fields(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    ModelData m;
#define FILL_SCALAR(T, FIELD, INITIAL, LOW, HIGH) m.FIELD = random_value<T>(rng, LOW, HIGH);
#define FILL_COUNT(T, FIELD, TABLE)
#define FILL_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    m.FIELD.clear();                          \
    for (int i = 0; i < 3; ++i) m.FIELD.push_back(random_value<T>(rng, LOW, HIGH));
#define FILL_NAMES(FIELD, COUNT)                                              \
    {                                                                         \
        const std::vector<std::string> names{"walk", "sit down", "\xc3\xbc"}; \
        m.FIELD.assign(names.begin(), names.end());                           \
    }
    ACTIONSTRING_MODEL_FIELDS(FILL_SCALAR, FILL_COUNT, FILL_TABLE, FILL_NAMES)
#undef FILL_SCALAR
#undef FILL_COUNT
#undef FILL_TABLE
#undef FILL_NAMES
    return m;
}

}  // namespace

TEST_CASE("every schema field round-trips through the artifact text, bit for bit") {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        CAPTURE(seed);
        const ModelData original = random_fields(seed);
        const std::string text = serialize_fields(original);
        const ModelData read = parse_fields("walk.model", text);
        CHECK(serialize_fields(read) == text);
#define CHECK_SCALAR(T, FIELD, INITIAL, LOW, HIGH) CHECK_MESSAGE(same(read.FIELD, original.FIELD), #FIELD);
#define CHECK_COUNT(T, FIELD, TABLE)
#define CHECK_TABLE(T, FIELD, SIZE, LOW, HIGH) CHECK_MESSAGE(same_table(read.FIELD, original.FIELD), #FIELD);
#define CHECK_NAMES(FIELD, COUNT) CHECK_MESSAGE(read.FIELD == original.FIELD, #FIELD);
        ACTIONSTRING_MODEL_FIELDS(CHECK_SCALAR, CHECK_COUNT, CHECK_TABLE, CHECK_NAMES)
#undef CHECK_SCALAR
#undef CHECK_COUNT
#undef CHECK_TABLE
#undef CHECK_NAMES
    }
}

TEST_CASE("the artifact holds one line per stored field and refuses a value out of its range") {
    const ModelData m = random_fields(7);
    const std::string text = serialize_fields(m);
    std::size_t expected_lines = 1;  // "end"
#define COUNT_SCALAR(T, FIELD, INITIAL, LOW, HIGH) ++expected_lines;
#define COUNT_COUNT(T, FIELD, TABLE)
#define COUNT_TABLE(T, FIELD, SIZE, LOW, HIGH) ++expected_lines;
#define COUNT_NAMES(FIELD, COUNT) expected_lines += 1 + m.FIELD.size();
    ACTIONSTRING_MODEL_FIELDS(COUNT_SCALAR, COUNT_COUNT, COUNT_TABLE, COUNT_NAMES)
#undef COUNT_SCALAR
#undef COUNT_COUNT
#undef COUNT_TABLE
#undef COUNT_NAMES
    CHECK(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) == expected_lines);
    // Each integer scalar one past its upper bound is refused, naming the field.
#define OVER_SCALAR(T, FIELD, INITIAL, LOW, HIGH)                                                           \
    if constexpr (!std::is_floating_point_v<T>) {                                                           \
        const std::string line = std::string(#FIELD " ") + std::to_string(static_cast<long long>(m.FIELD)); \
        std::string bad = text;                                                                             \
        const std::size_t at = ("\n" + bad).find("\n" + line + "\n"); /* a whole line */                    \
        REQUIRE(at != std::string::npos);                                                                   \
        bad.replace(at, line.size(), std::string(#FIELD " ") + std::to_string((HIGH) + 1LL));               \
        CHECK_THROWS_WITH_AS(parse_fields("over.model", bad), doctest::Contains(#FIELD), ReadError);        \
    }
#define OVER_COUNT(T, FIELD, TABLE)
#define OVER_TABLE(T, FIELD, SIZE, LOW, HIGH)
#define OVER_NAMES(FIELD, COUNT)
    ACTIONSTRING_MODEL_FIELDS(OVER_SCALAR, OVER_COUNT, OVER_TABLE, OVER_NAMES)
#undef OVER_SCALAR
#undef OVER_COUNT
#undef OVER_TABLE
#undef OVER_NAMES
}

TEST_CASE("the view points at every table and counts it") {
    ToyWorld world = make_toy_world();
    const ModelData& m = world.model;
    const ModelView v = m.view();
#define VIEW_SCALAR(T, FIELD, INITIAL, LOW, HIGH) CHECK_MESSAGE(same(v.FIELD, m.FIELD), #FIELD);
#define VIEW_COUNT(T, FIELD, TABLE) CHECK_MESSAGE(static_cast<std::size_t>(v.FIELD) == m.TABLE.size(), #FIELD);
#define VIEW_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    CHECK_MESSAGE(v.FIELD == (m.FIELD.empty() ? nullptr : m.FIELD.data()), #FIELD);
#define VIEW_NAMES(FIELD, COUNT) \
    for (std::size_t i = 0; i < m.FIELD.size(); ++i) CHECK_MESSAGE(std::string(v.FIELD[i]) == m.FIELD[i], #FIELD);
    ACTIONSTRING_MODEL_FIELDS(VIEW_SCALAR, VIEW_COUNT, VIEW_TABLE, VIEW_NAMES)
#undef VIEW_SCALAR
#undef VIEW_COUNT
#undef VIEW_TABLE
#undef VIEW_NAMES
}

TEST_CASE("a valid model's tables agree with their sizes; the loader refuses one element more in any table") {
    ToyWorld world = make_toy_world();
    CHECK(mismatched_table(world.model) == nullptr);
#define GROW_SCALAR(T, FIELD, INITIAL, LOW, HIGH)
#define GROW_COUNT(T, FIELD, TABLE)
#define GROW_TABLE(T, FIELD, SIZE, LOW, HIGH)                                                                 \
    {                                                                                                         \
        ToyWorld grown = make_toy_world();                                                                    \
        grown.model.FIELD.push_back(T{});                                                                     \
        CHECK_THROWS_AS_MESSAGE(parse_model("grown.model", serialize_model(grown.model)), ReadError, #FIELD); \
    }
#define GROW_NAMES(FIELD, COUNT)
    ACTIONSTRING_MODEL_FIELDS(GROW_SCALAR, GROW_COUNT, GROW_TABLE, GROW_NAMES)
#undef GROW_SCALAR
#undef GROW_COUNT
#undef GROW_TABLE
#undef GROW_NAMES
}

TEST_CASE("the generated header sets every field of the view") {
    ToyWorld world = make_toy_world();
    const std::string text = serialize_model(world.model);
    const std::string header = generate_header(world.model, artifact_checksum(text), "walk", "walk.model");
#define HEADER_SCALAR(T, FIELD, INITIAL, LOW, HIGH) \
    CHECK_MESSAGE(header.find("    m." #FIELD " = ") != std::string::npos, #FIELD);
#define HEADER_COUNT(T, FIELD, TABLE) CHECK_MESSAGE(header.find("    m." #FIELD " = ") != std::string::npos, #FIELD);
#define HEADER_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    CHECK_MESSAGE(header.find("    m." #FIELD " = ") != std::string::npos, #FIELD);
#define HEADER_NAMES(FIELD, COUNT) CHECK_MESSAGE(header.find("    m." #FIELD " = ") != std::string::npos, #FIELD);
    ACTIONSTRING_MODEL_FIELDS(HEADER_SCALAR, HEADER_COUNT, HEADER_TABLE, HEADER_NAMES)
#undef HEADER_SCALAR
#undef HEADER_COUNT
#undef HEADER_TABLE
#undef HEADER_NAMES
}
