// The clip descriptor: the pyramid's parts and summaries by hand, the
// penalties, and training's ridge regression (descriptor.hpp, src/train/descriptor.*).
#include <doctest/doctest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "actionstring/blob.hpp"
#include "actionstring/classify.hpp"
#include "actionstring/descriptor.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/descriptor.hpp"
#include "train/pipeline.hpp"
#include "train/rejection.hpp"

using namespace actionstring;
using namespace actionstring::host;

TEST_CASE("descriptor: the pyramid's parts are as equal as whole characters allow, never empty") {
    CHECK(descriptor_parts(1) == 1);
    CHECK(descriptor_parts(3) == 6);
    CHECK(descriptor_part_size(2) == 5);  // mean 2, covariance 3
    CHECK(descriptor_part_size(24) == 324);
    // Ten characters in three parts: [0, 3), [3, 6), [6, 10).
    CHECK(descriptor_part_begin(10, 3, 0) == 0);
    CHECK(descriptor_part_end(10, 3, 0) == 3);
    CHECK(descriptor_part_begin(10, 3, 1) == 3);
    CHECK(descriptor_part_end(10, 3, 1) == 6);
    CHECK(descriptor_part_begin(10, 3, 2) == 6);
    CHECK(descriptor_part_end(10, 3, 2) == 10);
    // Fewer characters than parts: each part still holds one.
    for (std::size_t n = 1; n <= 8; ++n)
        for (std::size_t level = 1; level <= 8; ++level)
            for (std::size_t part = 0; part < level; ++part) {
                CAPTURE(n);
                CAPTURE(level);
                CAPTURE(part);
                const std::size_t begin = descriptor_part_begin(n, level, part),
                                  end = descriptor_part_end(n, level, part);
                CHECK(begin < end);
                CHECK(end <= n);
                CHECK(end - begin <= (n + level - 1) / level);
            }
    CHECK(descriptor_part_end(0, 2, 1) == 0);
}

TEST_CASE("descriptor: each part's mean and covariance, by hand") {
    // Four characters, stride 3, the first two coordinates read, two levels.
    const std::vector<float> features = {1, 2, 99,  //
                                         3, 6, 99,  //
                                         5, 2, 99,  //
                                         7, 6, 99};
    std::vector<float> out(descriptor_parts(2) * descriptor_part_size(2), -1.0f);
    clip_descriptor(features.data(), 4, 3, 2, 2, out.data());
    // Level 1: mean (4, 4); covariance xx = (9 + 1 + 1 + 9) / 4, xy = (-3·-2 + -1·2 + 1·-2 + 3·2) / 4, yy = 4.
    const std::vector<float> whole = {4, 4, 5, 2, 4};
    // Level 2, characters 0-1: mean (2, 4), xx 1, xy 2, yy 4; characters 2-3: mean (6, 4), xx 1, xy 2, yy 4.
    const std::vector<float> first = {2, 4, 1, 2, 4}, second = {6, 4, 1, 2, 4};
    std::vector<float> expected = whole;
    expected.insert(expected.end(), first.begin(), first.end());
    expected.insert(expected.end(), second.begin(), second.end());
    CHECK(out == expected);  // exact: every value is a small integer over a power of two
    // A negative covariance keeps its sign: x rising while y falls.
    const std::vector<float> opposed = {0, 2, 0,  //
                                        2, 0, 0};
    std::vector<float> one_part(descriptor_part_size(2));
    clip_descriptor(opposed.data(), 2, 3, 2, 1, one_part.data());
    CHECK(one_part == std::vector<float>{1, 1, 1, -1, 1});  // covariance xx 1, xy −1, yy 1
    // The coordinates past `dims` are never read.
    std::vector<float> changed = features;
    for (std::size_t t = 0; t < 4; ++t) changed[t * 3 + 2] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> again(out.size());
    clip_descriptor(changed.data(), 4, 3, 2, 2, again.data());
    CHECK(again == out);
    // No characters: zeros.
    clip_descriptor(features.data(), 0, 3, 2, 2, again.data());
    CHECK(std::all_of(again.begin(), again.end(), [](float v) { return v == 0.0f; }));
    // One character: its own mean, no spread, in every part of every level.
    std::vector<float> single(descriptor_parts(3) * descriptor_part_size(2));
    clip_descriptor(features.data() + 3, 1, 3, 2, 3, single.data());
    for (std::size_t part = 0; part < 6; ++part) {
        CHECK(single[part * 5 + 0] == 3.0f);
        CHECK(single[part * 5 + 1] == 6.0f);
        CHECK((single[part * 5 + 2] == 0.0f && single[part * 5 + 3] == 0.0f && single[part * 5 + 4] == 0.0f));
    }
}

namespace {
// A three-label view with a descriptor of one level over one coordinate (P = 2: mean, variance).
struct Described {
    static constexpr char names_text[] = "a\0b\0c";
    static constexpr std::uint32_t names_offsets[4] = {0, 2, 4, 6};
    std::vector<float> weights = {1,  0,   // a: the mean
                                  -1, 0,   // b: minus the mean
                                  0,  1};  // c: the variance
    std::vector<float> bias = {0, 0, 0.5f};
    ModelView view;
    Described() {
        view.label_count = 3;
        view.label_names = NameTable{names_text, names_offsets};
        view.feature_dim = 2;
        view.descriptor_levels = 1;
        view.descriptor_dim = 1;
        view.descriptor_weight = 2.0f;
        view.descriptor_weights = weights.data();
        view.descriptor_bias = bias.data();
    }
};
}  // namespace

TEST_CASE("descriptor: scores, penalties relative to the best label, and they can decide") {
    Described d;
    REQUIRE(d.view.has_descriptor());
    REQUIRE(d.view.descriptor_size() == 2);
    // Features 1 and 3 on the coordinate read: mean 2, variance 1.
    const std::vector<float> features = {1, 50, 3, -50};
    float scratch[2], scores[3], penalties[3];
    clip_descriptor(features.data(), 2, 2, 1, 1, scratch);
    CHECK(scratch[0] == 2.0f);
    CHECK(scratch[1] == 1.0f);
    descriptor_scores(d.view, scratch, scores);
    CHECK(scores[0] == 2.0f);
    CHECK(scores[1] == -2.0f);
    CHECK(scores[2] == 1.5f);
    descriptor_penalties(d.view, features.data(), 2, scratch, penalties);
    CHECK(penalties[0] == 0.0f);
    CHECK(penalties[1] == 2.0f * 4.0f);
    CHECK(penalties[2] == 2.0f * 0.5f);
    // They decide between representatives the strings find equally near.
    const std::vector<LabelId> labels = {0, 1, 2};
    d.view.representative_count = 3;
    d.view.representative_labels = labels.data();
    d.view.neighbours = 1;
    d.view.unknown_distance = std::numeric_limits<float>::infinity();
    const float distances[] = {1.0f, 1.0f - 1e-3f, 1.0f - 2e-3f};
    CHECK(classify_distances(d.view, distances).label == 2);
    CHECK(classify_distances(d.view, distances, penalties).label == 0);
    // No characters, no weight, or a score that is not finite: no opinion.
    descriptor_penalties(d.view, features.data(), 0, scratch, penalties);
    CHECK((penalties[0] == 0.0f && penalties[1] == 0.0f && penalties[2] == 0.0f));
    const std::vector<float> huge = {3e38f, 0, 3e38f, 0};
    d.weights[0] = 1e6f;
    descriptor_penalties(d.view, huge.data(), 2, scratch, penalties);
    CHECK((penalties[0] == 0.0f && penalties[1] == 0.0f && penalties[2] == 0.0f));
    d.weights[0] = 1.0f;
    d.view.descriptor_weight = 0.0f;
    CHECK_FALSE(d.view.has_descriptor());
    descriptor_penalties(d.view, features.data(), 2, scratch, penalties);
    CHECK((penalties[0] == 0.0f && penalties[1] == 0.0f && penalties[2] == 0.0f));
}

TEST_CASE("descriptor: validation refuses what the runtime could not use") {
    ToyWorld world = make_toy_world();
    TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.descriptor_levels = 2;
    options.descriptor_weight = 1.0;
    ModelData model = train_model(toy_clips(world, 3, 5), options);
    const char* problem = nullptr;
    REQUIRE(validate_model(model.view(), &problem) == Status::ok);
    const std::string text = serialize_model(model);
    ModelData bad = parse_model("copy.model", text);
    bad.descriptor_dim = 7;  // beyond feature_dim (6)
    CHECK(validate_model(bad.view(), &problem) != Status::ok);
    CHECK(std::string(problem) == "descriptor_dim: more than feature_dim");
    bad = parse_model("copy.model", text);
    bad.descriptor_weights[3] = std::numeric_limits<float>::infinity();
    CHECK(validate_model(bad.view(), &problem) != Status::ok);
    CHECK(std::string(problem) == "descriptor_weights: missing, non-finite or beyond 1e6");
    bad = parse_model("copy.model", text);
    bad.descriptor_weight = -1.0f;
    CHECK(validate_model(bad.view(), &problem) != Status::ok);
    bad = parse_model("copy.model", text);
    bad.descriptor_levels = 9;
    CHECK(validate_model(bad.view(), &problem) != Status::ok);
    // The artifact refuses a table of the wrong size (levels changed, weights not).
    bad = parse_model("copy.model", text);
    bad.descriptor_levels = 3;
    CHECK_THROWS_AS(parse_model("bad.model", serialize_model(bad)), ReadError);
}

namespace {
// Clips of two labels whose features have the same mean and differ only in
// how the first two coordinates move together (in phase or in opposition),
// and a third whose first half differs from its second: the pyramid sees both.
std::vector<std::vector<float>> synthetic_clips(std::size_t per_label, std::uint32_t seed, std::vector<LabelId>& labels,
                                                std::size_t d) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    std::uniform_int_distribution<int> length(8, 20);
    std::vector<std::vector<float>> clips;
    labels.clear();
    for (std::size_t i = 0; i < 3 * per_label; ++i) {
        const LabelId label = static_cast<LabelId>(i % 3);
        const int n = length(rng);
        std::vector<float> f(static_cast<std::size_t>(n) * d);
        for (int t = 0; t < n; ++t) {
            const float s = std::sin(0.9f * static_cast<float>(t));
            float* x = &f[static_cast<std::size_t>(t) * d];
            for (std::size_t j = 0; j < d; ++j) x[j] = noise(rng);
            if (label == 0) x[0] += s, x[1] += s;
            if (label == 1) x[0] += s, x[1] -= s;
            if (label == 2) x[0] += t < n / 2 ? s : -s, x[1] += t < n / 2 ? s : s;
        }
        clips.push_back(std::move(f));
        labels.push_back(label);
    }
    return clips;
}

ModelData described_model(std::size_t d) {
    ModelData m;
    m.feature_dim = static_cast<std::uint16_t>(d);
    const std::vector<std::string> names = {"in phase", "opposed", "turning"};
    m.label_names.assign(names.begin(), names.end());
    return m;
}
}  // namespace

TEST_CASE("descriptor: ridge regression fits the pyramids, separates what a mean cannot, deterministic") {
    const std::size_t d = 4;
    std::vector<LabelId> labels, held_labels;
    const auto train = synthetic_clips(12, 1, labels, d);
    const auto held = synthetic_clips(10, 2, held_labels, d);
    ModelData m = described_model(d);
    set_descriptor(m, train, labels, 2, 3, 10.0, 1.5);
    const ModelView view = m.view();
    REQUIRE(view.has_descriptor());
    CHECK(view.descriptor_levels == 2);
    CHECK(view.descriptor_dim == 3);
    CHECK(view.descriptor_weight == 1.5f);
    CHECK(m.descriptor_weights.size() == 3u * 3u * descriptor_part_size(3));
    // Held-out clips: the best score is the right label for nearly all.
    std::vector<float> scratch(view.descriptor_size()), scores(3), penalties(3);
    std::size_t right = 0;
    for (std::size_t i = 0; i < held.size(); ++i) {
        clip_descriptor(held[i].data(), held[i].size() / d, d, view.descriptor_dims(), 2, scratch.data());
        descriptor_scores(view, scratch.data(), scores.data());
        right +=
            static_cast<LabelId>(std::max_element(scores.begin(), scores.end()) - scores.begin()) == held_labels[i];
        descriptor_penalties(view, held[i].data(), held[i].size() / d, scratch.data(), penalties.data());
        CHECK(*std::min_element(penalties.begin(), penalties.end()) == 0.0f);
    }
    CHECK(right >= held.size() - 2);
    // The folded weights give what the regression on standardised pyramids does (in double).
    {
        const Eigen::Index n = static_cast<Eigen::Index>(train.size()),
                           P = static_cast<Eigen::Index>(view.descriptor_size());
        Eigen::MatrixXd x(n, P);
        for (Eigen::Index i = 0; i < n; ++i) {
            clip_descriptor(train[static_cast<std::size_t>(i)].data(), train[static_cast<std::size_t>(i)].size() / d, d,
                            3, 2, scratch.data());
            for (Eigen::Index p = 0; p < P; ++p) x(i, p) = scratch[static_cast<std::size_t>(p)];
        }
        const Eigen::RowVectorXd mean = x.colwise().mean();
        const Eigen::RowVectorXd sd =
            ((x.rowwise() - mean).array().square().colwise().sum() / static_cast<double>(n)).sqrt();
        const Eigen::MatrixXd z = (x.rowwise() - mean).array().rowwise() / sd.array();
        Eigen::MatrixXd y = Eigen::MatrixXd::Constant(n, 3, -1.0);
        for (Eigen::Index i = 0; i < n; ++i) y(i, labels[static_cast<std::size_t>(i)]) = 1.0;
        const Eigen::RowVectorXd intercept = y.colwise().mean();
        y.rowwise() -= intercept;
        Eigen::MatrixXd gram = z.transpose() * z;
        gram.diagonal().array() += 10.0;
        const Eigen::MatrixXd w = gram.ldlt().solve(z.transpose() * y);
        const Eigen::MatrixXd expected = (z * w).rowwise() + intercept;
        for (Eigen::Index i = 0; i < n; ++i) {
            for (Eigen::Index p = 0; p < P; ++p) scratch[static_cast<std::size_t>(p)] = static_cast<float>(x(i, p));
            descriptor_scores(view, scratch.data(), scores.data());
            for (Eigen::Index l = 0; l < 3; ++l)
                CHECK(scores[static_cast<std::size_t>(l)] == doctest::Approx(expected(i, l)).epsilon(1e-3));
        }
    }
    // Deterministic.
    ModelData again = described_model(d);
    set_descriptor(again, train, labels, 2, 3, 10.0, 1.5);
    CHECK(again.descriptor_weights == m.descriptor_weights);
    CHECK(again.descriptor_bias == m.descriptor_bias);
    // Every coordinate (dims 0 = all) is stored as 0.
    set_descriptor(again, train, labels, 1, 0, 10.0, 1.5);
    CHECK(again.descriptor_dim == 0);
    CHECK(again.view().descriptor_dims() == d);
    // Clips labelled unknown_label take no part.
    std::vector<std::vector<float>> with_none = train;
    std::vector<LabelId> none_labels = labels;
    with_none.push_back(held[0]);
    none_labels.push_back(unknown_label);
    ModelData ignoring = described_model(d);
    set_descriptor(ignoring, with_none, none_labels, 2, 3, 10.0, 1.5);
    CHECK(ignoring.descriptor_weights == m.descriptor_weights);
    // Levels 0 or weight 0: none; refused settings.
    set_descriptor(again, train, labels, 0, 3, 10.0, 1.5);
    CHECK_FALSE(again.view().has_descriptor());
    CHECK(again.descriptor_weights.empty());
    set_descriptor(again, train, labels, 2, 3, 10.0, 0.0);
    CHECK_FALSE(again.view().has_descriptor());
    CHECK_THROWS_AS(set_descriptor(again, train, labels, 2, 5, 10.0, 1.0), std::invalid_argument);  // 5 > d
    CHECK_THROWS_AS(set_descriptor(again, train, labels, 9, 3, 10.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(set_descriptor(again, train, labels, 2, 3, 0.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(set_descriptor(again, {train[0]}, {labels[0]}, 2, 3, 10.0, 1.0), std::invalid_argument);
    ModelData wide = described_model(70);
    std::vector<float> one(70 * 4, 0.5f);
    CHECK_THROWS_WITH_AS(set_descriptor(wide, {one, one}, {0, 1}, 1, 0, 10.0, 1.0), doctest::Contains("1 to 64"),
                         std::invalid_argument);
}

TEST_CASE(
    "descriptor: trained into a model, stored, read back, in the header and the blob, used by clip classification") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.epsilon = 0.5;
    options.sigma = 0.5;
    options.descriptor_levels = 3;
    options.descriptor_dims = 4;
    options.descriptor_ridge = 100.0;
    options.descriptor_weight = 2.0;
    const ModelData model = train_model(train, options);
    const ModelView view = model.view();
    REQUIRE(validate_model(view) == Status::ok);
    REQUIRE(view.has_descriptor());
    CHECK(view.descriptor_levels == 3);
    CHECK(view.descriptor_dims() == 4);
    CHECK(model.descriptor_weights.size() == view.label_count * 6u * descriptor_part_size(4));
    // Deterministic, and through the artifact, the header and the blob.
    const std::string text = serialize_model(model);
    CHECK(serialize_model(train_model(train, options)) == text);
    CHECK(serialize_model(parse_model("x.model", text)) == text);
    const std::string header = generate_header(model, artifact_checksum(text), "toy", "toy.model");
    CHECK(header.find("m.descriptor_levels = 3;") != std::string::npos);
    CHECK(header.find("m.descriptor_dim = 4;") != std::string::npos);
    const ModelData from_blob = read_blob("toy.blob", write_blob(model));
    REQUIRE(from_blob.view().has_descriptor());
    CHECK(from_blob.descriptor_weights == model.descriptor_weights);
    CHECK(from_blob.descriptor_bias == model.descriptor_bias);
    CHECK(serialize_model(from_blob) == text);
    // Clip classification adds the penalties: the winner's distance grew by exactly its own.
    CHECK(clip_accuracy(view, held_out) >= 0.9);
    for (const LabelledClip& c : held_out) {
        const EncodedClip encoded = encode_clip(view, c.clip, true);
        const std::vector<float> penalties = clip_descriptor_penalties(view, encoded.features, encoded.records);
        CHECK(*std::min_element(penalties.begin(), penalties.end()) == 0.0f);
        const Classification with = classify_string(view, encoded.string, {}, nullptr, penalties.data());
        CHECK(with.label == classify_clip(view, c.clip).label);
        const Classification without = classify_string(view, encoded.string);
        if (with.label == without.label && with.representative == without.representative)
            CHECK(with.distance == doctest::Approx(without.distance + penalties[with.label]));
    }
    // Learned rejection with the descriptor: each sample's penalties measured by
    // a descriptor fitted without its subjects, as its representatives leave
    // them out. The positives are kept, held-out clips still recognised, and
    // the bounds reach the distances classify_clip() compares (penalties included).
    options.reject = true;
    TrainingReport report;
    const ModelData rejecting = train_model(train, options, &report);
    const ModelView rview = rejecting.view();
    REQUIRE(validate_model(rview) == Status::ok);
    REQUIRE(rview.has_descriptor());
    REQUIRE(rview.has_label_bounds == 1);
    for (const LabelBoundReport& b : report.label_bounds) {
        CHECK(b.positives > 0);
        CHECK(b.negatives > 0);
        CHECK(b.positives_kept >= options.reject_keep);
    }
    CHECK(serialize_model(train_model(train, options)) == serialize_model(rejecting));  // deterministic
    CHECK(clip_accuracy(rview, held_out) >= 0.8);
    // Each sample's descriptor penalties reach its distance: the same strings with
    // penalties that only push the synthetic negatives (spliced pairs and warped
    // clips) further away give bounds at least as large, and larger for some label.
    std::vector<std::vector<Character>> strings;
    std::vector<LabelId> labels;
    std::vector<std::string> subjects;
    DescriptorSamples samples;
    samples.width = rview.feature_dim;
    for (const LabelledClip& c : train) {
        EncodedClip encoded = encode_clip(rview, c.clip, true);
        strings.push_back(encoded.string);
        samples.strings.push_back(encoded.features);
        labels.push_back(
            static_cast<LabelId>(std::find(rejecting.label_names.begin(), rejecting.label_names.end(), c.label) -
                                 rejecting.label_names.begin()));
        subjects.push_back(c.subject);
    }
    const std::vector<long> none(strings.size(), -1);
    std::size_t calls = 0;
    samples.of_stretch = [&](const std::vector<float>&, std::size_t) { return std::vector<float>(rview.label_count); };
    samples.of_strings = [&](const std::vector<float>& features, std::size_t first, std::size_t) {
        ++calls;
        const bool own = features == samples.strings[first];  // a training clip as it is: a positive
        return std::vector<float>(rview.label_count, own ? 0.0f : 50.0f);
    };
    const std::vector<float> pushed =
        learn_label_bounds(rview, strings, labels, subjects, none, {}, 0.95, 1, nullptr, nullptr, &samples);
    samples.of_strings = [&](const std::vector<float>&, std::size_t, std::size_t) {
        return std::vector<float>(rview.label_count, 0.0f);
    };
    const std::vector<float> flat =
        learn_label_bounds(rview, strings, labels, subjects, none, {}, 0.95, 1, nullptr, nullptr, &samples);
    CHECK(calls >= 3 * strings.size());  // every positive and every negative (one spliced, two warped per string)
    bool larger = false;
    for (std::size_t l = 0; l < flat.size(); ++l) {
        CHECK(pushed[l] >= flat[l]);
        larger |= pushed[l] > flat[l];
    }
    CHECK(larger);
}
