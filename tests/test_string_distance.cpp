// Batch string distance: the paper's requirements (§4.2) and each variant's boundaries.
#include <doctest/doctest.h>

#include <limits>

#include "actionstring/string_distance.hpp"
#include "test_support.hpp"

using actionstring::LengthNormalization;
using actionstring::MatchVariant;
using actionstring::Status;
using test::batch_distance;
using test::chars;

namespace {
const std::vector<float> W = test::unit_weights(10);
float d(const std::string& a, const std::string& b, MatchVariant v, LengthNormalization n = LengthNormalization::none) {
    return batch_distance(chars(a), chars(b), W, 10, v, n);
}
}  // namespace

TEST_CASE("paper requirements hold under the variant each was written for") {
    // A window cut from inside an action: the shorter string lies inside the longer.
    CHECK(d("12345", "345", MatchVariant::subsequence) == 0.0f);
    CHECK(d("345", "12345", MatchVariant::subsequence) == 0.0f);
    // Speed changes and small edits between whole performances.
    CHECK(d("112233", "111223", MatchVariant::whole) <= 2.0f);
    CHECK(d("12345", "1345", MatchVariant::whole) <= 1.0f);
    CHECK(d("12345", "15345", MatchVariant::whole) <= 1.0f);
}

TEST_CASE("exact values of each variant on the paper's cases, worked by hand") {
    // Whole DTW must align the leading 1 and 2 of 12345 with something of 345.
    CHECK(d("12345", "345", MatchVariant::whole) == 2.0f);
    CHECK(d("112233", "111223", MatchVariant::whole) == 0.0f);
    CHECK(d("12345", "1345", MatchVariant::whole) == 1.0f);
    CHECK(d("12345", "15345", MatchVariant::whole) == 1.0f);
    // The paper's boundaries, as printed (DP tables in the design notes of this test).
    CHECK(d("12345", "345", MatchVariant::paper) == 0.0f);
    CHECK(d("112233", "111223", MatchVariant::paper) == 0.0f);
    CHECK(d("12345", "1345", MatchVariant::paper) == 1.0f);
    CHECK(d("12345", "15345", MatchVariant::paper) == 1.0f);
    CHECK(d("112233", "111223", MatchVariant::subsequence) == 0.0f);
    CHECK(d("12345", "1345", MatchVariant::subsequence) == 1.0f);
    CHECK(d("12345", "15345", MatchVariant::subsequence) == 1.0f);
}

TEST_CASE("the paper's boundaries let a short string match a suffix only") {
    // design.md §1.6: row 0 = 0 means the shorter string needs to fit only the end of
    // the longer one, so a 2-character reference matches a 5-character clip exactly.
    CHECK(d("12345", "45", MatchVariant::paper) == 0.0f);
    CHECK(d("12345", "45", MatchVariant::whole) == 3.0f);
    // Column 0 = W[A1(i)][A2(1)] lets a prefix of A1 be skipped: the path enters at
    // D[2][0] = W[1][1] = 0, so the leading 9 costs nothing; only 3↔4 at the end counts.
    CHECK(d("9123", "1234", MatchVariant::paper) == 1.0f);
    CHECK(d("9123", "1234", MatchVariant::whole) == 2.0f);
}

TEST_CASE("the shorter string indexes the rows; equal lengths put the query first") {
    // An asymmetric W shows which string is A1: W[a][b] = 1 for a = 1, b = 2 only.
    std::vector<float> w(9, 0.0f);
    w[1 * 3 + 2] = 1.0f;
    CHECK(batch_distance(chars("1"), chars("22"), w, 3, MatchVariant::whole) == 2.0f);  // A1 = "1"
    CHECK(batch_distance(chars("22"), chars("1"), w, 3, MatchVariant::whole) == 2.0f);  // A1 = "1" again
    CHECK(batch_distance(chars("2"), chars("11"), w, 3, MatchVariant::whole) == 0.0f);
    CHECK(batch_distance(chars("1"), chars("2"), w, 3, MatchVariant::whole) == 1.0f);  // query is A1
    CHECK(batch_distance(chars("2"), chars("1"), w, 3, MatchVariant::whole) == 0.0f);
}

TEST_CASE("length normalisation") {
    // 12345 vs 15345: one substitution over a 5-cell diagonal path.
    CHECK(d("12345", "15345", MatchVariant::whole, LengthNormalization::path) == doctest::Approx(0.2));
    CHECK(d("12345", "15345", MatchVariant::whole, LengthNormalization::query) == doctest::Approx(0.2));
    // 12345 vs 345 (whole): cost 2 along 1-3, 2-3, 3-3, 4-4, 5-5: five cells; the query is 12345.
    CHECK(d("12345", "345", MatchVariant::whole, LengthNormalization::path) == doctest::Approx(0.4));
    CHECK(d("345", "12345", MatchVariant::whole, LengthNormalization::query) == doctest::Approx(2.0 / 3.0));
    // A constant offset W = 1 everywhere: path normalisation gives 1 for any pair.
    std::vector<float> ones(9, 1.0f);
    CHECK(batch_distance(chars("1221"), chars("120"), ones, 3, MatchVariant::whole, LengthNormalization::path) == 1.0f);
}

TEST_CASE("bad arguments are refused, never answered with NaN") {
    Status status = Status::ok;
    batch_distance(chars(""), chars("12"), W, 10, MatchVariant::whole, LengthNormalization::none, &status);
    CHECK(status == Status::invalid_argument);
    batch_distance(chars("12"), {}, W, 10, MatchVariant::whole, LengthNormalization::none, &status);
    CHECK(status == Status::invalid_argument);
    batch_distance(chars("1:"), chars("12"), W, 10, MatchVariant::whole, LengthNormalization::none, &status);
    CHECK(status == Status::invalid_argument);  // ':' is character 10, outside W
    batch_distance(chars("19"), chars("12"), W, 10, MatchVariant::whole, LengthNormalization::none, &status);
    CHECK(status == Status::ok);
}
