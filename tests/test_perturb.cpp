// eval --perturb: the evaluated clips changed as another sensor or person would.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/clip_eval.hpp"
#include "eval/evaluation.hpp"
#include "eval/perturb.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/augment.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// `frames` frames of two joints at `rate` Hz: joint 0 at the origin, joint 1 at (t, 2t, −t).
Clip line_clip(std::size_t frames, double rate) {
    Clip c;
    c.source = "line";
    c.joint_names = {"a", "b"};
    for (std::size_t f = 0; f < frames; ++f) {
        const double t = static_cast<double>(f) / rate;
        c.times.push_back(t);
        const float x = static_cast<float>(t);
        c.positions.insert(c.positions.end(), {0.0f, 0.0f, 0.0f, x, 2.0f * x, -x});
    }
    return c;
}

std::string message_of(const std::string& spec) {
    try {
        parse_perturbation(spec);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("perturbation specs: every name, and clear errors for the rest") {
    const Perturbation p = parse_perturbation("scale=0.7,noise=0.01,drop=0.25,rate=15,jitter=0.005,seed=9");
    CHECK(p.scale == 0.7);
    CHECK(p.noise_m == 0.01);
    CHECK(p.drop == 0.25);
    CHECK(p.rate_hz == 15.0);
    CHECK(p.jitter_s == 0.005);
    CHECK(p.seed == 9);
    CHECK(p.any());
    CHECK(
        p.describe() ==
        "resampled to 15 Hz, scale 0.7, noise 0.01 m, timestamp jitter ±0.005 s, 0.25 of the frames dropped (seed 9)");
    CHECK(Perturbation{}.describe() == "none");
    CHECK_FALSE(Perturbation{}.any());
    CHECK_FALSE(parse_perturbation("seed=4").any());  // a seed alone changes nothing

    CHECK(message_of("") != "");
    CHECK(message_of("scale=abc").find("'scale=abc': expected a factor") != std::string::npos);
    CHECK(message_of("scale=0").find("'scale=0'") != std::string::npos);
    CHECK(message_of("noise=-0.1").find("metres") != std::string::npos);
    CHECK(message_of("drop=1").find("probability") != std::string::npos);
    CHECK(message_of("rate=nan").find("frames per second") != std::string::npos);
    CHECK(message_of("seed=1.5").find("whole number") != std::string::npos);
    CHECK(message_of("bright=1").find("'bright' is not a perturbation") != std::string::npos);
    CHECK(message_of("scale=1,scale=2").find("given twice") != std::string::npos);
    CHECK(message_of("scale").find("expected name=value") != std::string::npos);
    CHECK(message_of("scale=0.7,").find("expected name=value") != std::string::npos);
}

TEST_CASE("a scaled clip has every position times the factor, nothing else changed") {
    Clip c = line_clip(50, 30.0);
    const Clip before = c;
    Perturbation p;
    p.scale = 0.7;
    perturb_clip(c, p, 0);
    CHECK(c.times == before.times);
    REQUIRE(c.positions.size() == before.positions.size());
    for (std::size_t i = 0; i < c.positions.size(); ++i)
        CHECK(c.positions[i] == static_cast<float>(static_cast<double>(before.positions[i]) * 0.7));
}

TEST_CASE("tilt turns each tracked frame about the hips' line, lost frames and a clip without roles unchanged") {
    // y up; root at (1, 1, 2), hips 0.1 m either side along x, a head 0.5 m above the root.
    Clip c;
    c.source = "tilt";
    c.joint_names = {"root", "left", "right", "head"};
    c.roles = JointRoles{0, 1, 2};
    for (std::size_t f = 0; f < 3; ++f) {
        c.times.push_back(static_cast<double>(f) / 30.0);
        const float z = 2.0f + 0.01f * static_cast<float>(f);
        c.positions.insert(c.positions.end(), {1.0f, 1.0f, z, 0.9f, 1.0f, z, 1.1f, 1.0f, z, 1.0f, 1.5f, z});
    }
    c.lost = {0, 0, 1};  // the third frame was lost (its positions are kept as they are)
    const Clip before = c;
    Perturbation p;
    p.tilt_deg = 90.0;
    perturb_clip(c, p, 0);
    CHECK(c.times == before.times);
    // The line runs through the tracked frames' mean root, z = 2.005: a right-handed quarter turn about +x
    // takes the head's +0.5 in y to +0.5 in z, and a root 0.005 before the line in z to 0.005 below it in y.
    const float* f0 = c.frame(0);
    CHECK(f0[0] == doctest::Approx(1.0));
    CHECK(f0[1] == doctest::Approx(1.005));
    CHECK(f0[2] == doctest::Approx(2.005));
    CHECK(f0[9] == doctest::Approx(1.0));
    CHECK(f0[10] == doctest::Approx(1.005));
    CHECK(f0[11] == doctest::Approx(2.505));
    // Lengths about the root keep, and so do the hips' line and the lost frame.
    for (std::size_t f = 0; f < 2; ++f) {
        const float* at = c.frame(f);
        CHECK(std::hypot(at[9] - at[0], at[10] - at[1], at[11] - at[2]) == doctest::Approx(0.5));
        CHECK(at[3] == doctest::Approx(0.9));
        CHECK(at[6] == doctest::Approx(1.1));
    }
    for (std::size_t i = 24; i < 36; ++i) CHECK(c.positions[i] == before.positions[i]);
    // Without roles there is no hip line: nothing moves.
    Clip bare = before;
    bare.roles = JointRoles{};
    perturb_clip(bare, p, 0);
    CHECK(bare.positions == before.positions);
    CHECK(parse_perturbation("tilt=-15").tilt_deg == -15.0);
    CHECK(message_of("tilt=100").find("degrees") != std::string::npos);
}

TEST_CASE("mirror: the clip as training's mirroring gives it, before the tilt") {
    Clip c;
    c.source = "sides";
    c.joint_names = {"HipCenter", "HipLeft", "HipRight", "HandLeft", "HandRight"};
    c.roles = JointRoles{0, 1, 2};
    for (std::size_t f = 0; f < 4; ++f) {
        const float t = static_cast<float>(f);
        c.times.push_back(static_cast<double>(f) / 30.0);
        c.positions.insert(c.positions.end(), {0.0f, 1.0f, 2.0f, -0.1f, 1.0f, 2.0f, 0.1f, 1.0f, 2.0f, -0.3f, 1.2f, 2.0f,
                                               0.3f + 0.1f * t, 1.5f + 0.1f * t, 1.8f});
    }
    Perturbation p = parse_perturbation("mirror=1");
    CHECK(p.mirror);
    CHECK(p.describe() == "mirrored (seed 1)");
    Clip mirrored = c;
    perturb_clip(mirrored, p, 0);
    CHECK(mirrored.positions == mirror_clip(c).positions);
    CHECK(mirrored.positions != c.positions);
    CHECK(mirrored.times == c.times);
    // The moving right hand now moves on the left, reflected.
    CHECK(mirrored.frame(3)[9] == mirror_clip(c).frame(3)[9]);
    CHECK_FALSE(parse_perturbation("mirror=0").any());
    CHECK(message_of("mirror=0.5").find("0 or 1") != std::string::npos);
    // Mirroring comes first: with a tilt, the tilt of the mirrored clip.
    p.tilt_deg = 20.0;
    Clip both = c;
    perturb_clip(both, p, 0);
    Perturbation tilt_only;
    tilt_only.tilt_deg = 20.0;
    Clip expected = mirror_clip(c);
    perturb_clip(expected, tilt_only, 0);
    CHECK(both.positions == expected.positions);
}

TEST_CASE("noise: Gaussian of the asked deviation, its own per clip, the same for the same seed and index") {
    Clip zero = line_clip(4000, 30.0);
    for (float& v : zero.positions) v = 0.0f;
    zero.lost.assign(zero.frame_count(), 0);
    zero.lost[7] = 1;  // a lost frame stays all zero
    Perturbation p;
    p.noise_m = 0.02;
    Clip a = zero, b = zero, other = zero;
    perturb_clip(a, p, 3);
    perturb_clip(b, p, 3);
    perturb_clip(other, p, 4);
    CHECK(a.positions == b.positions);
    CHECK(a.positions != other.positions);
    for (std::size_t c = 0; c < 6; ++c) CHECK(a.frame(7)[c] == 0.0f);
    double sum = 0, squares = 0;
    std::size_t n = 0;
    for (std::size_t f = 0; f < a.frame_count(); ++f) {
        if (f == 7) continue;
        for (std::size_t c = 0; c < 6; ++c, ++n) {
            sum += a.frame(f)[c];
            squares += static_cast<double>(a.frame(f)[c]) * a.frame(f)[c];
        }
    }
    const double mean = sum / static_cast<double>(n), deviation = std::sqrt(squares / static_cast<double>(n));
    CHECK(std::fabs(mean) < 4.0 * 0.02 / std::sqrt(static_cast<double>(n)));
    CHECK(deviation == doctest::Approx(0.02).epsilon(0.03));
}

TEST_CASE("resampling interpolates between frames at the new rate and loses frames next to lost ones") {
    Clip c = line_clip(61, 60.0);  // 0 … 1 s
    c.lost.assign(c.frame_count(), 0);
    c.lost[30] = 1;  // t = 0.5 s
    for (std::size_t k = 0; k < 6; ++k) c.frame(30)[k] = 0.0f;
    Perturbation p;
    p.rate_hz = 25.0;
    perturb_clip(c, p, 0);
    REQUIRE(c.frame_count() == 26);  // 0, 0.04, …, 1.0
    REQUIRE(c.lost.size() == 26);
    for (std::size_t f = 0; f < c.frame_count(); ++f) {
        const double t = static_cast<double>(f) / 25.0;
        CHECK(c.times[f] == doctest::Approx(t));
        // 0.48 and 0.52 s lie between frame 30 and a neighbour; 0.5 s is not a multiple of 0.04.
        const bool lost = std::fabs(t - 0.5) < 1.0 / 60.0;
        CHECK(static_cast<bool>(c.lost[f]) == lost);
        if (lost) continue;
        CHECK(c.frame(f)[3] == doctest::Approx(t).epsilon(1e-5));
        CHECK(c.frame(f)[4] == doctest::Approx(2.0 * t).epsilon(1e-5));
        CHECK(c.frame(f)[0] == 0.0f);
    }
    Clip up = line_clip(16, 15.0);
    p.rate_hz = 30.0;
    perturb_clip(up, p, 0);
    CHECK(up.frame_count() == 31);
    CHECK(up.lost.empty());  // nothing was lost, so no flags appear
}

TEST_CASE("jitter keeps the timestamps in order, near their own and never before the first") {
    Clip c = line_clip(300, 30.0);
    const std::vector<double> before = c.times;
    Perturbation p;
    p.jitter_s = 0.03;  // almost a frame either way: reorderings are clamped
    perturb_clip(c, p, 1);
    CHECK(c.times != before);
    for (std::size_t f = 0; f < c.times.size(); ++f) {
        CHECK(c.times[f] >= before.front());
        CHECK(c.times[f] <= before[f] + 0.03 + 1e-12);
        CHECK(c.times[f] >= before[f] - 2 * 0.03 - 1e-12);  // the clamp never pulls a time back further
        if (f > 0) CHECK(c.times[f] >= c.times[f - 1]);
    }
}

TEST_CASE("dropped frames: the first and last stay, the rest keep their own times and poses") {
    Clip c = line_clip(2000, 30.0);
    Perturbation p;
    p.drop = 0.3;
    perturb_clip(c, p, 2);
    CHECK(c.times.front() == 0.0);
    CHECK(c.times.back() == doctest::Approx(1999.0 / 30.0));
    CHECK(c.positions.size() == c.frame_count() * 6);
    CHECK(static_cast<double>(c.frame_count()) == doctest::Approx(1400.0).epsilon(0.05));
    for (std::size_t f = 0; f < c.frame_count(); ++f) {
        if (f > 0) CHECK(c.times[f] > c.times[f - 1]);
        CHECK(c.frame(f)[3] == static_cast<float>(c.times[f]));  // each frame kept whole
    }
}

TEST_CASE("an evaluation measures the perturbed clips, not the training clips") {
    ToyWorld world = make_toy_world();
    const TrainingOptions options = test::toy_options();
    const auto train = toy_clips(world, 5, 300);
    const auto test = toy_clips(world, 4, 7000, 30.0);
    ModelData model = train_model(train, options);
    const ModelView view = model.view();
    const AnnotatorConfig config = annotator_config(view);

    const Evaluation plain = evaluate(view, test, train, {}, false, 1, config);
    CHECK(plain.perturbation == "none");
    CHECK(plain.results.front().clip_accuracy >= 0.9);
    // The same clips at another frame rate and another size are still recognised
    // (rates are read from the timestamps; the toy's training clips vary in size).
    const Evaluation moved = evaluate(view, test, train, {}, false, 1, config, parse_perturbation("rate=20,scale=1.3"));
    CHECK(moved.perturbation == "resampled to 20 Hz, scale 1.3 (seed 1)");
    CHECK(moved.results.front().clip_accuracy >= 0.9);
    CHECK(moved.clips.front().clip.frame_count() < test.front().clip.frame_count());
    // Noise as large as the hands' motion leaves little to recognise, for the model and DTW alike.
    const Evaluation noisy = evaluate(view, test, train, {}, false, 1, config, parse_perturbation("noise=0.3"));
    CHECK(noisy.results.front().clip_accuracy < plain.results.front().clip_accuracy);
    REQUIRE(noisy.results.size() == 4);
    CHECK(noisy.results.back().clip_accuracy < plain.results.back().clip_accuracy);
    // The same perturbation twice gives the same evaluation.
    const Evaluation again = evaluate(view, test, train, {}, false, 1, config, parse_perturbation("noise=0.3"));
    CHECK(again.results.front().predictions == noisy.results.front().predictions);
}

TEST_CASE("random perturbation specs either parse into a valid perturbation or throw invalid_argument") {
    const std::string alphabet = "scaleoisdrptjd=,.0123456789-+enaif ";
    std::uint64_t state = 12345;
    auto next = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<std::size_t>(state >> 33);
    };
    const std::vector<std::string> words{"scale=", "noise=", "drop=", "rate=", "jitter=", "seed=", ","};
    int parsed = 0;
    for (int i = 0; i < 3000; ++i) {
        std::string spec;
        const std::size_t pieces = 1 + next() % 6;
        for (std::size_t k = 0; k < pieces; ++k) {
            if (next() % 2 == 0) spec += words[next() % words.size()];
            const std::size_t chars = next() % 5;
            for (std::size_t c = 0; c < chars; ++c) spec += alphabet[next() % alphabet.size()];
        }
        try {
            const Perturbation p = parse_perturbation(spec);
            ++parsed;
            CHECK(std::isfinite(p.scale));
            CHECK(p.scale > 0.0);
            CHECK(p.noise_m >= 0.0);
            CHECK(p.drop >= 0.0);
            CHECK(p.drop < 1.0);
            CHECK(p.rate_hz >= 0.0);
            CHECK(p.jitter_s >= 0.0);
        } catch (const std::invalid_argument& e) {
            CHECK(std::string(e.what()).rfind("--perturb: ", 0) == 0);
        }
    }
    CHECK(parsed > 0);
}
