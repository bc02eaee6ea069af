// kNN vote, unknown threshold and confidence.
#include <doctest/doctest.h>

#include <limits>
#include <vector>

#include "actionstring/classify.hpp"
#include "actionstring/exemplars.hpp"

using namespace actionstring;

namespace {
struct Reps {
    std::vector<LabelId> labels;
    static constexpr char names_text[] = "a\0b\0c";
    static constexpr std::uint32_t names_offsets[4] = {0, 2, 4, 6};
    ModelView view;
    Reps(std::vector<LabelId> l, std::uint16_t k, float unknown = std::numeric_limits<float>::infinity())
        : labels(std::move(l)) {
        view.representative_count = static_cast<std::uint16_t>(labels.size());
        view.representative_labels = labels.data();
        view.label_count = 3;
        view.label_names = NameTable{names_text, names_offsets};
        view.neighbours = k;
        view.unknown_distance = unknown;
    }
};
}  // namespace

TEST_CASE("1-NN picks the nearest representative") {
    Reps reps({0, 1, 2, 1}, 1);
    const float d[] = {3.0f, 2.0f, 1.0f, 5.0f};
    const Classification c = classify_distances(reps.view, d);
    CHECK(c.label == 2);
    CHECK(c.representative == 2);
    CHECK(c.distance == 1.0f);
    CHECK(c.confidence == doctest::Approx(0.5));  // 1 − 1/2
}

TEST_CASE("k-NN votes; ties go to the label of the nearer neighbour") {
    Reps reps({0, 1, 1, 0, 2}, 3);
    const float d[] = {1.0f, 1.5f, 1.6f, 9.0f, 2.0f};
    Classification c = classify_distances(reps.view, d);
    CHECK(c.label == 1);  // two of the three nearest
    CHECK(c.distance == 1.5f);
    CHECK(c.confidence == 0.0f);  // label 0 is nearer than the winner
    Reps tie({0, 1, 2}, 3);
    const float e[] = {2.0f, 1.0f, 3.0f};
    c = classify_distances(tie.view, e);
    CHECK(c.label == 1);
    CHECK(c.confidence == doctest::Approx(0.5));
}

TEST_CASE("nothing close enough is unknown") {
    Reps reps({0, 1}, 1, 2.0f);
    const float far[] = {2.5f, 3.0f};
    Classification c = classify_distances(reps.view, far);
    CHECK(c.label == unknown_label);
    CHECK(c.nearest_label == 0);
    CHECK(c.confidence == 0.0f);
    const float near[] = {2.0f, 3.0f};
    c = classify_distances(reps.view, near);
    CHECK(c.label == 0);
}

TEST_CASE("a single label has full confidence; NaN distances are ignored") {
    Reps reps({1, 1}, 2);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float d[] = {nan, 4.0f};
    const Classification c = classify_distances(reps.view, d);
    CHECK(c.label == 1);
    CHECK(c.representative == 1);
    CHECK(c.confidence == 1.0f);
    const float all_nan[] = {nan, nan};
    CHECK(classify_distances(reps.view, all_nan).label == unknown_label);
    // Nothing compared (an empty string: every distance +inf): unknown with no
    // confidence, not the first label at full confidence.
    const float inf = std::numeric_limits<float>::infinity();
    const float all_inf[] = {inf, inf};
    const Classification none = classify_distances(reps.view, all_inf);
    CHECK(none.label == unknown_label);
    CHECK(none.confidence == 0.0f);
    const float one_finite[] = {inf, 4.0f};
    CHECK(classify_distances(reps.view, one_finite).label == 1);
}

TEST_CASE("the characters' votes: penalties relative to the favoured label, and they can decide") {
    Reps reps({0, 1, 2}, 1);
    // K = 2 characters; log P(c | label) label by label (exact binary fractions).
    const float votes[] = {-0.25f, -2.0f,    // a: mostly character 0
                           -2.0f, -0.25f,    // b: mostly character 1
                           -1.0f, -1.0f};    // c: either
    reps.view.character_count = 2;
    reps.view.character_votes = votes;
    float penalties[3] = {9, 9, 9};

    // No votes in the model (weight 0): all zero.
    const Character string[] = {1, 1, 0, 1};
    vote_penalties(reps.view, string, 4, penalties);
    CHECK(penalties[0] == 0.0f);
    CHECK(penalties[2] == 0.0f);
    CHECK_FALSE(reps.view.has_votes());

    reps.view.vote_weight = 2.0f;
    REQUIRE(reps.view.has_votes());
    vote_penalties(reps.view, string, 4, penalties);
    // Means: a (−2 − 2 − 0.25 − 2) / 4 = −1.5625, b −0.6875, c −1; b is favoured.
    CHECK(penalties[1] == 0.0f);
    CHECK(penalties[0] == 2.0f * (1.5625f - 0.6875f));
    CHECK(penalties[2] == 2.0f * (1.0f - 0.6875f));

    // DTW alone says a; with the votes b wins, and the distance and confidence include them.
    const float d[] = {1.0f, 1.5f, 3.0f};
    CHECK(classify_distances(reps.view, d).label == 0);
    const Classification voted = classify_distances(reps.view, d, penalties);
    CHECK(voted.label == 1);
    CHECK(voted.distance == 1.5f);
    CHECK(voted.confidence == doctest::Approx((2.75f - 1.5f) / 2.75f));  // the nearest other label: a, 1 + 1.75

    // An empty string or a null string gives no penalty.
    vote_penalties(reps.view, string, 0, penalties);
    CHECK(penalties[0] == 0.0f);
    vote_penalties(reps.view, nullptr, 4, penalties);
    CHECK(penalties[1] == 0.0f);
}

TEST_CASE("a label's own bound makes what lies beyond it unknown") {
    Reps reps({0, 1, 2}, 1);
    const float bounds[] = {2.0f, std::numeric_limits<float>::infinity(), 0.5f};
    reps.view.has_label_bounds = 1;
    reps.view.label_bounds = bounds;
    const float within[] = {2.0f, 3.0f, 4.0f};  // label 0 at exactly its bound
    CHECK(classify_distances(reps.view, within).label == 0);
    const float beyond[] = {2.5f, 3.0f, 4.0f};
    Classification c = classify_distances(reps.view, beyond);
    CHECK(c.label == unknown_label);
    CHECK(c.nearest_label == 0);
    CHECK(c.distance == 2.5f);
    const float unbounded[] = {5.0f, 3.0f, 4.0f};  // label 1 has no bound
    CHECK(classify_distances(reps.view, unbounded).label == 1);
    const float tight[] = {5.0f, 6.0f, 1.0f};  // label 2's bound is 0.5
    CHECK(classify_distances(reps.view, tight).label == unknown_label);
    reps.view.has_label_bounds = 0;  // the same distances without bounds
    CHECK(classify_distances(reps.view, tight).label == 2);
}

TEST_CASE("exemplars: each label's nearest centre, penalties relative to the nearest label, and they can decide") {
    Reps reps({0, 1, 2}, 1);
    // Two-dimensional features; label 0 has two centres, label 1 one, label 2 none.
    const LabelId labels[] = {0, 1, 0};
    const float centres[] = {0.0f, 0.0f, 3.0f, 4.0f, 1.0f, 1.0f};
    reps.view.feature_dim = 2;
    reps.view.exemplar_count = 3;
    reps.view.exemplar_labels = labels;
    reps.view.exemplars = centres;
    reps.view.exemplar_weight = 2.0f;
    reps.view.exemplar_scale = 0.5f;
    REQUIRE(reps.view.has_exemplars());
    const float feature[] = {1.0f, 2.0f};
    float d[3];
    exemplar_distances(reps.view, feature, d);
    CHECK(d[0] == 1.0f);                                        // (1,1): 0 + 1, nearer than (0,0): 1 + 4
    CHECK(d[1] == 8.0f);                                        // (3,4): 4 + 4
    CHECK(d[2] == std::numeric_limits<float>::infinity());      // no exemplars
    // Sums over four characters: penalties weight · (mean − best mean) / scale.
    const float sums[] = {4.0f, 12.0f, std::numeric_limits<float>::infinity()};
    float p[3];
    exemplar_penalties(reps.view, sums, 4, p);
    CHECK(p[0] == 0.0f);
    CHECK(p[1] == doctest::Approx(2.0 * (3.0 - 1.0) / 0.5));
    CHECK(p[2] == std::numeric_limits<float>::infinity());
    // They decide between representatives the strings find equally near.
    const float distances[] = {1.0f, 1.0f - 1e-3f, 5.0f};
    CHECK(classify_distances(reps.view, distances).label == 1);
    CHECK(classify_distances(reps.view, distances, p).label == 0);
    // No characters, no sums, or no finite sum: no opinion.
    exemplar_penalties(reps.view, sums, 0, p);
    CHECK((p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f));
    const float none[] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::infinity()};
    exemplar_penalties(reps.view, none, 4, p);
    CHECK((p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f));
    // Centres of "no action" (unknown_label, after every label's): not a label's,
    // and reported apart when asked for.
    CHECK_FALSE(reps.view.has_no_action_exemplars());
    const LabelId with_none[] = {0, 1, unknown_label};
    reps.view.exemplar_labels = with_none;
    CHECK(reps.view.has_no_action_exemplars());
    float to_none = 0.0f;
    exemplar_distances(reps.view, feature, d, &to_none);
    CHECK(d[0] == 5.0f);  // (0,0) alone now
    CHECK(d[1] == 8.0f);
    CHECK(d[2] == std::numeric_limits<float>::infinity());
    CHECK(to_none == 1.0f);  // (1,1)
    // Not last: refused by validation (test_model.cpp).
    const LabelId none_first[] = {unknown_label, 1, 0};
    reps.view.exemplar_labels = none_first;
    CHECK_FALSE(reps.view.has_no_action_exemplars());
    reps.view.exemplar_labels = labels;
    // Without a weight the model has no exemplars to use.
    reps.view.exemplar_weight = 0.0f;
    CHECK_FALSE(reps.view.has_exemplars());
    exemplar_penalties(reps.view, sums, 4, p);
    CHECK((p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f));
}
