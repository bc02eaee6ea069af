// A whole clip's label in the runtime (clip.hpp): the same as its stages
// composed by hand, bit for bit, from characters and features a
// StringEncoder gives; what the host's classify_clip() returns.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "actionstring/clip.hpp"
#include "actionstring/encoder.hpp"
#include "hdm05_model.hpp"
#include "run/classify.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// A model with votes, exemplars, a clip descriptor and motion directions, so every stage adds something.
ModelData described_model(const std::vector<LabelledClip>& train) {
    TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.epsilon = 0.5;
    options.sigma = 0.5;
    options.exemplars = 4;
    options.exemplar_weight = 1.0;
    options.descriptor_levels = 2;
    options.descriptor_ridge = 100.0;
    options.descriptor_weight = 1.0;
    options.direction_levels = 2;
    options.direction_ridge = 100.0;
    options.direction_weight = 1.0;
    return train_model(train, options);
}

// The clip's characters, their features and records (pose, facing), as a device collects them from a StringEncoder.
struct Collected {
    std::vector<Character> string;
    std::vector<float> features;
    std::vector<float> records;
};

Collected collect(const ModelView& model, const Clip& clip) {
    Stateful<StringEncoder> encoder;
    REQUIRE(encoder.init(model, EncoderConfig{}) == Status::ok);
    Collected out;
    const std::size_t d = model.feature_dim, D = model.pose_dim();
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const EncodedFrame e = encoder->push_frame(static_cast<std::int64_t>(clip.times[f] * 1e6), clip.frame(f));
        for (std::uint32_t k = 0; k < e.from_previous; ++k) {
            out.string.push_back(e.previous);
            out.features.insert(out.features.end(), e.previous_feature, e.previous_feature + d);
            out.records.insert(out.records.end(), e.previous_pose, e.previous_pose + D);
            out.records.insert(out.records.end(), e.previous_facing, e.previous_facing + 2);
        }
        for (std::uint32_t k = 0; k < e.from_current; ++k) {
            out.string.push_back(e.current);
            out.features.insert(out.features.end(), e.current_feature, e.current_feature + d);
            out.records.insert(out.records.end(), e.current_pose, e.current_pose + D);
            out.records.insert(out.records.end(), e.current_facing, e.current_facing + 2);
        }
    }
    return out;
}

// The stages one after another, each with its own buffers: the reference.
// The representatives' distances, and what the clip adds to each label's (when `any`).
struct HandScores {
    std::vector<float> distances, penalties;
    bool any = false;
};

HandScores scores_by_hand(const ModelView& model, const Collected& c, bool with_features) {
    const std::size_t L = model.label_count, n = c.string.size();
    std::vector<float> distances(model.representative_count, detail::infinity());
    for (std::size_t r = 0; r < model.representative_count; ++r) {
        std::vector<detail::Cell> cells(string_distance_cells(n, model.representative_length(r)));
        if (n > 0)
            (void)string_distance(c.string.data(), n, model.representative_chars + model.representative_offsets[r],
                                  model.representative_length(r), character_weights(model),
                                  MatchOptions{model.variant, model.normalization}, cells.data(), &distances[r]);
    }
    std::vector<float> penalties(L);
    vote_penalties(model, c.string.data(), n, penalties.data());
    bool any = model.has_votes();
    if (with_features && model.has_exemplars()) {
        std::vector<float> sums(L, 0.0f), row(L);
        for (std::size_t k = 0; k < n; ++k) {
            exemplar_distances(model, &c.features[k * model.feature_dim], row.data());
            for (std::size_t l = 0; l < L; ++l) sums[l] += row[l];
        }
        exemplar_penalties(model, sums.data(), n, row.data());
        for (std::size_t l = 0; l < L; ++l) penalties[l] += row[l];
        any = true;
    }
    // The two clip summaries are summed first, then added (clip_summary_penalties(), clip_penalties()).
    std::vector<float> summaries(L, 0.0f);
    if (with_features && model.has_descriptor()) {
        std::vector<float> scratch(model.descriptor_size());
        descriptor_penalties(model, c.features.data(), n, scratch.data(), summaries.data());
        any = true;
    }
    if (with_features && model.has_directions()) {
        std::vector<float> scratch(model.direction_size()), directed(L);
        direction_penalties(model, c.records.data(), n, scratch.data(), directed.data());
        for (std::size_t l = 0; l < L; ++l) summaries[l] += directed[l];
        any = true;
    }
    if (with_features && (model.has_descriptor() || model.has_directions()))
        for (std::size_t l = 0; l < L; ++l) penalties[l] += summaries[l];
    return HandScores{distances, penalties, any};
}

Classification by_hand(const ModelView& model, const Collected& c, bool with_features) {
    const HandScores s = scores_by_hand(model, c, with_features);
    return classify_distances(model, s.distances.data(), s.any ? s.penalties.data() : nullptr);
}

// The toy world, the described model trained on it, and `held` held-out clips per action.
struct Fixture {
    explicit Fixture(int held) : held_out(toy_clips(world, held, 9000, 30.0)), model(described_model(train)) {}
    ToyWorld world = make_toy_world();
    std::vector<LabelledClip> train = toy_clips(world, 6, 100);
    std::vector<LabelledClip> held_out;
    ModelData model;
};

void check_same(const Classification& a, const Classification& b) {
    CHECK(a.label == b.label);
    CHECK(a.nearest_label == b.nearest_label);
    CHECK(a.representative == b.representative);
    // Bit for bit (both +inf for an empty clip).
    CHECK(std::memcmp(&a.distance, &b.distance, sizeof(float)) == 0);
    CHECK(std::memcmp(&a.confidence, &b.confidence, sizeof(float)) == 0);
}

}  // namespace

TEST_CASE("clip: the runtime's whole-clip label is its stages composed, bit for bit, and the host's") {
    const Fixture fixture(5);
    const std::vector<LabelledClip>& held_out = fixture.held_out;
    const ModelView view = fixture.model.view();
    REQUIRE(view.has_votes());
    REQUIRE(view.has_exemplars());
    REQUIRE(view.has_descriptor());
    REQUIRE(view.has_directions());
    CHECK(clip_scratch_floats(view) ==
          view.representative_count + 5u * view.label_count + std::max(view.descriptor_size(), view.direction_size()));
    std::uint32_t longest = 0;
    for (std::size_t r = 0; r < view.representative_count; ++r)
        longest = std::max(longest, view.representative_length(r));
    CHECK(longest_representative(view) == longest);
    CHECK(clip_cells(view, 7) == string_distance_cells(7, longest));

    std::size_t right = 0;
    for (const LabelledClip& c : held_out) {
        const Collected collected = collect(view, c.clip);
        REQUIRE(collected.features.size() == collected.string.size() * view.feature_dim);
        // Scratch filled with garbage first: every float is written before it is read.
        std::vector<float> scratch(clip_scratch_floats(view), 12345.0f);
        std::vector<detail::Cell> cells(clip_cells(view, collected.string.size()));
        REQUIRE(collected.records.size() == collected.string.size() * view.direction_record_floats());
        const Classification runtime =
            classify_clip(view, collected.string.data(), collected.features.data(), collected.records.data(),
                          collected.string.size(), scratch.data(), cells.data());
        check_same(runtime, by_hand(view, collected, true));
        check_same(runtime, host::classify_clip(view, c.clip));
        right += runtime.label != unknown_label && view.label_names[runtime.label] == c.label;
        // Without features: the strings and the votes alone.
        std::fill(scratch.begin(), scratch.end(), -7.0f);
        check_same(classify_clip(view, collected.string.data(), nullptr, nullptr, collected.string.size(),
                                 scratch.data(), cells.data()),
                   by_hand(view, collected, false));
    }
    CHECK(static_cast<double>(right) >= 0.9 * static_cast<double>(held_out.size()));

    // Nothing to classify: unknown, and nothing read past what was given.
    std::vector<float> scratch(clip_scratch_floats(view));
    const Classification empty = classify_clip(view, nullptr, nullptr, nullptr, 0, scratch.data(), nullptr);
    CHECK(empty.label == unknown_label);
    CHECK(classify_clip(view, nullptr, nullptr, nullptr, 0, nullptr, nullptr).label == unknown_label);
    // A string too long for a path is compared with nothing, as string_distance() refuses it.
    std::vector<Character> too_long(0x10000, 0);
    std::vector<detail::Cell> one_cell(1);
    CHECK(classify_clip(view, too_long.data(), nullptr, nullptr, too_long.size(), scratch.data(), one_cell.data())
              .label == unknown_label);
}

TEST_CASE("clip: each label's score is its nearest representative with its penalty, and ranks the label") {
    const Fixture fixture(3);
    const ModelView view = fixture.model.view();
    REQUIRE(view.neighbours == 1);
    const std::size_t L = view.label_count;
    std::size_t ranked_first = 0, labelled = 0;
    for (const LabelledClip& c : fixture.held_out) {
        const Collected collected = collect(view, c.clip);
        std::vector<float> scratch(clip_scratch_floats(view), 12345.0f), scores(L, -1.0f);
        std::vector<detail::Cell> cells(clip_cells(view, collected.string.size()));
        clip_label_distances(view, collected.string.data(), collected.features.data(), collected.records.data(),
                             collected.string.size(), scratch.data(), cells.data(), scores.data());
        // By hand: the minimum over each label's representatives, bit for bit.
        const HandScores hand = scores_by_hand(view, collected, true);
        REQUIRE(hand.any);
        std::vector<float> expected(L, detail::infinity());
        for (std::size_t r = 0; r < view.representative_count; ++r) {
            const LabelId l = view.representative_labels[r];
            expected[l] = std::min(expected[l], hand.distances[r] + hand.penalties[l]);
        }
        CHECK(std::memcmp(scores.data(), expected.data(), L * sizeof(float)) == 0);
        const std::vector<float> host_scores = host::label_distances(view, c.clip);
        REQUIRE(host_scores.size() == L);
        CHECK(std::memcmp(scores.data(), host_scores.data(), L * sizeof(float)) == 0);
        // The host's one pass for both gives classify_clip()'s label and these scores.
        const ScoredClip scored = score_clip(view, c.clip);
        check_same(scored.classification, host::classify_clip(view, c.clip));
        REQUIRE(scored.label_distances.size() == L);
        CHECK(std::memcmp(scores.data(), scored.label_distances.data(), L * sizeof(float)) == 0);
        // With one neighbour the smallest score is the label classify_clip() reports.
        const Classification k = host::classify_clip(view, c.clip);
        const auto best = static_cast<LabelId>(std::min_element(scores.begin(), scores.end()) - scores.begin());
        CHECK(best == k.nearest_label);
        CHECK(std::memcmp(&scores[best], &k.distance, sizeof(float)) == 0);
        ranked_first += best == k.nearest_label;
        labelled += k.label != unknown_label;
    }
    CHECK(ranked_first == fixture.held_out.size());
    CHECK(labelled > 0);

    // Nothing to compare: every label +inf, and nothing read past what was given.
    std::vector<float> scratch(clip_scratch_floats(view)), scores(L, 0.0f);
    clip_label_distances(view, nullptr, nullptr, nullptr, 0, scratch.data(), nullptr, scores.data());
    for (const float d : scores) CHECK(d == detail::infinity());
    std::fill(scores.begin(), scores.end(), 0.0f);
    clip_label_distances(view, nullptr, nullptr, nullptr, 0, nullptr, nullptr, scores.data());
    for (const float d : scores) CHECK(d == detail::infinity());
    clip_label_distances(view, nullptr, nullptr, nullptr, 0, scratch.data(), nullptr, nullptr);  // no output: no write
}

TEST_CASE("clip: label_distances() passes over NaN and +inf distances and adds each label's penalty") {
    const Fixture fixture(1);
    const ModelView view = fixture.model.view();
    const std::size_t R = view.representative_count, L = view.label_count;
    REQUIRE(L >= 2);
    std::vector<float> distances(R), penalties(L), out(L);
    for (std::size_t r = 0; r < R; ++r) distances[r] = 1.0f + static_cast<float>(r);
    for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.5f * static_cast<float>(l);
    // Label 0's representatives: all NaN (excluded, as training's exclusions do) but its last, which is +inf.
    std::size_t last_of_0 = R;
    for (std::size_t r = 0; r < R; ++r)
        if (view.representative_labels[r] == 0) {
            distances[r] = std::numeric_limits<float>::quiet_NaN();
            last_of_0 = r;
        }
    REQUIRE(last_of_0 < R);
    distances[last_of_0] = detail::infinity();
    label_distances(view, distances.data(), penalties.data(), out.data());
    CHECK(out[0] == detail::infinity());
    for (std::size_t l = 1; l < L; ++l) {
        float nearest = detail::infinity();
        for (std::size_t r = 0; r < R; ++r)
            if (view.representative_labels[r] == l) nearest = std::min(nearest, distances[r]);
        CHECK(out[l] == nearest + penalties[l]);
    }
    // Without penalties, the distances alone; without distances, +inf.
    label_distances(view, distances.data(), nullptr, out.data());
    for (std::size_t l = 1; l < L; ++l) CHECK(out[l] < detail::infinity());
    label_distances(view, nullptr, nullptr, out.data());
    for (const float d : out) CHECK(d == detail::infinity());
}

TEST_CASE("clip: the scratch a generated header's model needs is known at compile time") {
    namespace model = actionstring_hdm05;
    constexpr std::size_t floats = clip_scratch_floats(model::kModel);
    constexpr std::size_t cells = clip_cells(model::kModel, 64);
    static_assert(floats >= model::kModel.representative_count, "one distance per representative");
    static_assert(cells >= 65, "a 64-character clip needs more than its own row");
    CHECK(floats == model::kModel.representative_count + 5u * model::kModel.label_count +
                        std::max(model::kModel.descriptor_size(), model::kModel.direction_size()));
    CHECK(cells == string_distance_cells(64, longest_representative(model::kModel)));
}

TEST_CASE("clip: a recorder collects what an encoder gives and labels it as classify_clip() does") {
    const Fixture fixture(2);
    const std::vector<LabelledClip>& held_out = fixture.held_out;
    const ModelView view = fixture.model.view();
    const std::size_t capacity = 256;
    const std::size_t bytes = ClipRecorder::required_bytes(view, capacity);
    REQUIRE(bytes != unsatisfiable_bytes);
    std::vector<std::uint64_t> storage_words(bytes / 8 + 2);  // 16-byte aligned by the allocator
    void* storage = storage_words.data();
    ClipRecorder recorder;
    CHECK(recorder.push_frame(0, nullptr) == Status::not_initialized);
    CHECK(recorder.classify().label == unknown_label);
    CHECK(recorder.init(view, capacity, EncoderConfig{}, nullptr, bytes) == Status::storage_too_small);
    CHECK(recorder.init(view, capacity, EncoderConfig{}, storage, bytes - 1) == Status::storage_too_small);
    CHECK(recorder.init(view, 0, EncoderConfig{}, storage, bytes) == Status::invalid_argument);
    ModelView broken = view;
    broken.descriptor_levels = 9;  // more than the runtime's 8
    CHECK(recorder.init(broken, capacity, EncoderConfig{}, storage, bytes) == Status::invalid_model);
    broken = view;
    broken.direction_levels = 9;
    CHECK(recorder.init(broken, capacity, EncoderConfig{}, storage, bytes) == Status::invalid_model);
    CHECK(ClipRecorder::required_bytes(view, unsatisfiable_bytes / 2) == unsatisfiable_bytes);
    REQUIRE(recorder.init(view, capacity, EncoderConfig{}, storage, bytes) == Status::ok);
    CHECK(recorder.classify().label == unknown_label);  // nothing yet
    for (const LabelledClip& c : held_out) {
        recorder.reset();
        for (std::size_t f = 0; f < c.clip.frame_count(); ++f) {
            const Status s = recorder.push_frame(static_cast<std::int64_t>(c.clip.times[f] * 1e6), c.clip.frame(f));
            CHECK((s == Status::ok || s == Status::stream_restarted));
        }
        const Collected collected = collect(view, c.clip);
        REQUIRE(recorder.length() == collected.string.size());
        CHECK(std::equal(collected.string.begin(), collected.string.end(), recorder.characters()));
        CHECK(std::equal(collected.features.begin(), collected.features.end(), recorder.features()));
        REQUIRE(recorder.records() != nullptr);
        CHECK(std::equal(collected.records.begin(), collected.records.end(), recorder.records()));
        CHECK_FALSE(recorder.overflowed());
        check_same(recorder.classify(), by_hand(view, collected, true));
    }
    // A clip longer than the room keeps its beginning and says so.
    const LabelledClip& c = held_out.front();
    const Collected all = collect(view, c.clip);
    REQUIRE(all.string.size() > 6);
    const std::size_t small = all.string.size() / 2;
    std::vector<std::uint64_t> small_words(ClipRecorder::required_bytes(view, small) / 8 + 2);
    ClipRecorder short_one;
    REQUIRE(short_one.init(view, small, EncoderConfig{}, small_words.data(), small_words.size() * 8) == Status::ok);
    std::size_t refused = 0;
    for (std::size_t f = 0; f < c.clip.frame_count(); ++f)
        refused += short_one.push_frame(static_cast<std::int64_t>(c.clip.times[f] * 1e6), c.clip.frame(f)) ==
                   Status::storage_too_small;
    CHECK(refused > 0);
    CHECK(short_one.overflowed());
    REQUIRE(short_one.length() == small);
    Collected first;
    first.string.assign(all.string.begin(), all.string.begin() + static_cast<long>(small));
    first.features.assign(all.features.begin(), all.features.begin() + static_cast<long>(small * view.feature_dim));
    first.records.assign(all.records.begin(),
                         all.records.begin() + static_cast<long>(small * view.direction_record_floats()));
    check_same(short_one.classify(), by_hand(view, first, true));
    short_one.reset();
    CHECK(short_one.length() == 0);
    CHECK_FALSE(short_one.overflowed());
    // A frame that is not a pose changes nothing.
    std::vector<float> lost(view.joint_count * 3u, 0.0f);
    CHECK(short_one.push_frame(0, lost.data()) != Status::ok);
    CHECK(short_one.length() == 0);
    // Sized at compile time for a generated header's model.
    static_assert(ClipRecorder::required_bytes(actionstring_hdm05::kModel, 64) > 0, "constexpr");
}
