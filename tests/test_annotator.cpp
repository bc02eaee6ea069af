// The whole per-frame pipeline on the synthetic toy world.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/string_distance.hpp"
#include "model/artifact.hpp"
#include "model/header.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"
#include "test_support.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

namespace {

struct Fixture {
    host::ToyWorld world;
    ModelView view;
    host::Stateful<Annotator> annotator;
    explicit Fixture(const host::ToyOptions& options = {}) : world(host::make_toy_world(options)) {
        view = world.model.view();
        REQUIRE(annotator.init(view, test::every_rule(view)) == Status::ok);
    }
};

}  // namespace

TEST_CASE("each action performed alone is recognised by its last window") {
    for (const MatchVariant variant : {MatchVariant::whole, MatchVariant::subsequence, MatchVariant::paper}) {
        host::ToyOptions options;
        options.variant = variant;
        Fixture f(options);
        int right = 0, total = 0;
        for (int action = 0; action < static_cast<int>(f.world.actions.size()); ++action) {
            for (std::uint32_t seed = 1; seed <= 5; ++seed) {
                host::ToyStreamOptions stream;
                stream.seed = seed * 31 + static_cast<std::uint32_t>(action);
                stream.frame_rate_hz = seed % 2 ? 30.0 : 120.0;
                f.annotator->reset();
                for (const auto& frame : host::toy_stream(f.world, {action}, stream))
                    REQUIRE(f.annotator->push_frame(frame.time_us, frame.positions.data()).status == Status::ok);
                REQUIRE(f.annotator->last_window() != nullptr);
                right += f.annotator->label() == action;
                ++total;
            }
        }
        CAPTURE(static_cast<int>(variant));
        // Whole and subsequence matching must get every clean toy action; the
        // paper's boundaries may not (design.md §1.6), but must beat chance (1/4).
        if (variant == MatchVariant::paper) CHECK(right * 2 >= total);
        else CHECK(right == total);
    }
}

TEST_CASE("window results carry their time span and the matcher's distances") {
    Fixture f;
    host::ToyStreamOptions stream;
    stream.frame_rate_hz = 50.0;
    const auto frames = host::toy_stream(f.world, {1, 3}, stream);
    std::uint32_t windows = 0, characters = 0;
    for (const auto& frame : frames) {
        const FrameResult r = f.annotator->push_frame(frame.time_us, frame.positions.data());
        windows += r.windows_completed;
        characters += r.characters;
    }
    const std::uint32_t expected_chars =
        static_cast<std::uint32_t>((frames.back().time_us - frames.front().time_us) / f.view.string_period_us) + 1;
    CHECK(characters == expected_chars);
    CHECK(f.annotator->characters() == expected_chars);
    CHECK(windows == (expected_chars - f.view.window_chars) / f.view.step_chars + 1);
    const WindowResult* w = f.annotator->last_window();
    REQUIRE(w != nullptr);
    CHECK(w->end_time_us - w->start_time_us ==
          static_cast<std::int64_t>(f.view.window_chars - 1) * f.view.string_period_us);
    CHECK(w->start_time_us ==
          frames.front().time_us + static_cast<std::int64_t>(w->first_character) * f.view.string_period_us);
    const float* distances = f.annotator->last_window_distances();
    REQUIRE(distances != nullptr);
    float best = std::numeric_limits<float>::infinity();
    for (std::size_t r = 0; r < f.view.representative_count; ++r) best = std::min(best, distances[r]);
    CHECK(w->classification.distance == best);
}

TEST_CASE("rejected frames are skipped: the string and label hold, time keeps the rate") {
    Fixture f;
    host::ToyStreamOptions stream;
    const auto frames = host::toy_stream(f.world, {0, 2}, stream);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::uint32_t rejected = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        std::vector<float> positions = frames[i].positions;
        const bool lost = i >= 40 && i < 52;  // 0.4 s without tracking, shorter than the maximum gap
        if (lost) std::fill(positions.begin(), positions.end(), 0.0f);
        if (i == 70) positions[4] = nan;
        const std::uint64_t before = f.annotator->characters();
        const LabelId label_before = f.annotator->label();
        const FrameResult r = f.annotator->push_frame(frames[i].time_us, positions.data());
        if (lost || i == 70) {
            CHECK(r.status == (lost ? Status::tracking_lost : Status::non_finite_input));
            CHECK(r.characters == 0);
            CHECK(f.annotator->characters() == before);
            CHECK(f.annotator->label() == label_before);
            ++rejected;
        } else {
            CHECK(r.status == Status::ok);
        }
    }
    CHECK(rejected == 13);
    // The gap was bridged: the string has one character per period of stream time.
    CHECK(f.annotator->characters() ==
          static_cast<std::uint64_t>((frames.back().time_us - frames.front().time_us) / f.view.string_period_us) + 1);
}

TEST_CASE("a gap longer than the maximum restarts the stream") {
    Fixture f;
    host::ToyStreamOptions stream;
    const auto frames = host::toy_stream(f.world, {3, 3}, stream);
    std::size_t i = 0;
    for (; frames[i].time_us < 3000000; ++i) f.annotator->push_frame(frames[i].time_us, frames[i].positions.data());
    REQUIRE(f.annotator->label() != unknown_label);
    const std::vector<float> lost(15, 0.0f);
    const std::int64_t resume = frames[i].time_us + 1500000;
    for (std::int64_t t = frames[i].time_us; t < resume; t += 33333)
        CHECK(f.annotator->push_frame(t, lost.data()).status == Status::tracking_lost);
    const FrameResult r = f.annotator->push_frame(resume, frames[i].positions.data());
    CHECK(r.status == Status::stream_restarted);
    CHECK(r.characters == 1);
    CHECK(f.annotator->characters() == 1);
    CHECK(f.annotator->label() == unknown_label);
    CHECK(f.annotator->last_window() == nullptr);
    CHECK(f.annotator->push_frame(resume - 1, frames[i].positions.data()).status == Status::time_went_backwards);
}

TEST_CASE("garbage frames never crash, hang or leak NaN into labels") {
    Fixture f;
    std::mt19937 rng(77);
    std::uniform_int_distribution<int> kind(0, 9);
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
    const auto clean = host::toy_stream(f.world, {0, 1, 2, 3, 0, 1}, {});
    const float specials[] = {std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              1e38f,
                              -1e38f,
                              1e-40f,
                              0.0f,
                              -0.0f};
    std::int64_t time = 0;
    for (int i = 0; i < 6000; ++i) {
        std::vector<float> positions = clean[static_cast<std::size_t>(i) % clean.size()].positions;
        switch (kind(rng)) {
            case 0:
                for (auto& p : positions) p = coordinate(rng);
                break;
            case 1:
                positions[static_cast<std::size_t>(i) % 15] = specials[static_cast<std::size_t>(i) % 8];
                break;
            case 2:
                for (auto& p : positions) p = specials[static_cast<std::size_t>(i + kind(rng)) % 8];
                break;
            case 3:
                time -= 10000;
                break;
            case 4:
                time += 3000000;
                break;
            default:
                break;
        }
        time += 33333;
        f.annotator->push_frame(time, positions.data());
        const LabelId label = f.annotator->label();
        CHECK((label == unknown_label || label < f.view.label_count));
        const float confidence = f.annotator->confidence();
        CHECK((confidence >= 0.0f && confidence <= 1.0f));
        if (const float* d = f.annotator->last_window_distances())
            for (std::size_t r = 0; r < f.view.representative_count; ++r) CHECK_FALSE(std::isnan(d[r]));
    }
}

TEST_CASE("reset() gives the same results as a fresh annotator") {
    Fixture f;
    host::Stateful<Annotator> second;
    REQUIRE(second.init(f.view, test::every_rule(f.view)) == Status::ok);
    const auto frames = host::toy_stream(f.world, {2, 0, 1}, {});
    for (const auto& frame : frames) f.annotator->push_frame(frame.time_us + 777, frame.positions.data());
    f.annotator->reset();
    for (const auto& frame : frames) {
        f.annotator->push_frame(frame.time_us, frame.positions.data());
        second->push_frame(frame.time_us, frame.positions.data());
        REQUIRE(f.annotator->label() == second->label());
        REQUIRE(f.annotator->confidence() == second->confidence());
        REQUIRE(f.annotator->last_character() == second->last_character());
    }
}

TEST_CASE("the online settings travel in the model: training stores them, init() uses them") {
    host::ToyWorld world = host::make_toy_world();
    host::TrainingOptions options;
    options.pca_dim = 8;
    options.components = 6;
    options.string_rate_hz = 10.0;
    options.online.settle_delay_us = 1000000;
    options.online.settle_stable_us = 500000;
    options.online.segment_penalty = 1.5f;
    options.online.unknown_cost = 0.25f;
    options.min_action_us = 750000;
    options.label_lead_us = 300000;
    const host::ModelData model = host::train_model(host::toy_clips(world, 2, 8), options);
    const ModelView view = model.view();
    CHECK(view.settle_delay_us == 1000000u);
    CHECK(view.settle_stable_us == 500000u);
    CHECK(view.segment_penalty == 1.5f);
    CHECK(view.unknown_cost == 0.25f);
    CHECK(view.min_action_us == 750000u);
    CHECK(view.label_lead_us == 300000u);
    const AnnotatorConfig config = annotator_config(view);
    CHECK(config.segmenter.unknown_cost == 0.25f);
    CHECK(config.segmenter.settle_stable_us == 500000);
    CHECK(config.min_action_us == 750000);
    CHECK(config.label_lead_us == 300000);
    host::Stateful<Annotator> annotator;
    REQUIRE(annotator.init(view, config) == Status::ok);
    CHECK(annotator->settle_chars() == 10u);  // 1 s at the toy's 10 Hz string
    AnnotatorConfig slower = config;
    slower.segmenter.settle_delay_us = 2000000;
    REQUIRE(annotator.init(view, slower) == Status::ok);  // an explicit config overrides the model's
    CHECK(annotator->settle_chars() == 20u);
    // The artifact and the header carry them.
    const host::ModelData loaded = host::parse_model("online.model", host::serialize_model(model));
    CHECK(loaded.unknown_cost == 0.25f);
    CHECK(loaded.min_action_us == 750000u);
    CHECK(loaded.label_lead_us == 300000u);
    CHECK(loaded.settle_stable_us == 500000u);
    const std::string header = host::generate_header(model, "0", "online", "online.model");
    CHECK(header.find("m.segment_penalty = 0x1.8p+0f;") != std::string::npos);
    CHECK(header.find("m.min_action_us = 750000;") != std::string::npos);
    CHECK(header.find("m.label_lead_us = 300000;") != std::string::npos);
    CHECK(header.find("m.settle_stable_us = 500000;") != std::string::npos);
}

namespace {

// The same action event, its times `earlier_us` earlier.
void check_same_event(const ActionEvent& a, const ActionEvent& b, std::int64_t earlier_us = 0) {
    CHECK(a.kind == b.kind);
    CHECK(a.label == b.label);
    CHECK(a.first_character == b.first_character);
    CHECK(a.last_character == b.last_character);
    CHECK(a.confidence == b.confidence);
    CHECK(a.start_time_us == b.start_time_us - earlier_us);
    CHECK(a.end_time_us == b.end_time_us - earlier_us);
}

}  // namespace

TEST_CASE("the label lead moves every label's time and the events' times, and nothing else") {
    const host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    REQUIRE(view.label_lead_us == 0u);
    struct Run {
        std::vector<std::pair<std::uint64_t, LabelId>> settled;
        std::vector<std::int64_t> ticks, label_times;  // of each settled character
        std::vector<ActionEvent> events;
    };
    host::ToyStreamOptions stream;
    stream.frame_time_jitter = 0.3;
    stream.drop_probability = 0.1;
    const auto frames = host::toy_stream(world, {0, 2, 1, 3, 0}, stream);
    const auto run = [&](std::int64_t lead_us) {
        AnnotatorConfig config = annotator_config(view);
        config.label_lead_us = lead_us;
        host::Stateful<Annotator> annotator;
        REQUIRE(annotator.init(view, config) == Status::ok);
        Run out;
        for (const host::ToyFrame& frame : frames) {
            const FrameResult r = annotator->push_frame(frame.time_us, frame.positions.data());
            for (std::uint32_t k = 0; k < r.characters_settled; ++k) {
                const std::uint64_t c = annotator->settled_character() - (r.characters_settled - 1 - k);
                out.settled.emplace_back(c, annotator->settled_label(c));
                out.ticks.push_back(annotator->character_time_us(c));
                out.label_times.push_back(annotator->label_time_us(c));
            }
            for (std::uint32_t e = 0; e < r.events; ++e) out.events.push_back(annotator->event(e));
        }
        const std::uint32_t flushed = annotator->flush();
        for (std::uint32_t e = 0; e < flushed; ++e) out.events.push_back(annotator->event(e));
        return out;
    };
    const Run at_ticks = run(0);
    REQUIRE(at_ticks.settled.size() > 20);
    REQUIRE(at_ticks.events.size() >= 4);
    CHECK(at_ticks.label_times == at_ticks.ticks);
    for (const std::int64_t lead_us :
         {std::int64_t{1}, std::int64_t{150000}, std::int64_t{view.string_period_us} * 3}) {
        CAPTURE(lead_us);
        const Run led = run(lead_us);
        CHECK(led.settled == at_ticks.settled);  // what is settled, and when, is the same
        CHECK(led.ticks == at_ticks.ticks);
        REQUIRE(led.label_times.size() == led.ticks.size());
        for (std::size_t i = 0; i < led.ticks.size(); ++i) CHECK(led.label_times[i] == led.ticks[i] - lead_us);
        REQUIRE(led.events.size() == at_ticks.events.size());
        for (std::size_t i = 0; i < led.events.size(); ++i)
            check_same_event(led.events[i], at_ticks.events[i], lead_us);
    }
    // A negative lead, or one past the longest settle delay, is refused.
    host::Stateful<Annotator> annotator;
    AnnotatorConfig bad = annotator_config(view);
    bad.label_lead_us = -1;
    CHECK(annotator.init(view, bad) == Status::invalid_argument);
    bad.label_lead_us = max_settle_delay_us + 1;
    CHECK(annotator.init(view, bad) == Status::invalid_argument);
    bad.label_lead_us = max_settle_delay_us;
    CHECK(annotator.init(view, bad) == Status::ok);
}

TEST_CASE("a tilted sensor whose up direction is given labels the stream as an upright one") {
    const host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    host::ToyStreamOptions stream;
    stream.frame_time_jitter = 0.2;
    const auto frames = host::toy_stream(world, {0, 2, 1, 3, 0, 1}, stream);
    // The sensor pitched by 0.4 rad about x and rolled by 0.2 about z: every position turned alike.
    const float cx = std::cos(0.4f), sx = std::sin(0.4f), cz = std::cos(0.2f), sz = std::sin(0.2f);
    const float turn[9] = {cz, -sz * cx, sz * sx, sz, cz * cx, -cz * sx, 0.0f, sx, cx};  // Rz · Rx, row-major
    auto tilted = frames;
    for (host::ToyFrame& frame : tilted)
        for (std::size_t j = 0; j < frame.positions.size() / 3; ++j) {
            const float x = frame.positions[3 * j], y = frame.positions[3 * j + 1], z = frame.positions[3 * j + 2];
            for (int i = 0; i < 3; ++i)
                frame.positions[3 * j + static_cast<std::size_t>(i)] =
                    turn[3 * i] * x + turn[3 * i + 1] * y + turn[3 * i + 2] * z;
        }
    struct Run {
        std::vector<LabelId> labels;  // settled
        std::vector<float> margins;   // each frame's live margin
    };
    const auto run = [&](const std::vector<host::ToyFrame>& input, const float* up) {
        AnnotatorConfig config = annotator_config(view);
        if (up != nullptr)
            for (int a = 0; a < 3; ++a) config.up[a] = up[a];
        host::Stateful<Annotator> annotator;
        REQUIRE(annotator.init(view, config) == Status::ok);
        Run out;
        for (const host::ToyFrame& frame : input) {
            const FrameResult r = annotator->push_frame(frame.time_us, frame.positions.data());
            REQUIRE((r.status == Status::ok || r.status == Status::stream_restarted));
            for (std::uint32_t k = 0; k < r.characters_settled; ++k)
                out.labels.push_back(
                    annotator->settled_label(annotator->settled_character() - (r.characters_settled - 1 - k)));
            out.margins.push_back(annotator->live_margin());
        }
        return out;
    };
    const auto farthest = [](const std::vector<float>& a, const std::vector<float>& b) {
        float worst = 0.0f;
        for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
        return worst;
    };
    const Run upright = run(frames, nullptr);
    REQUIRE(upright.labels.size() > 20);
    // The sensor's up: the world's up (y) as the tilted sensor sees it, the second column of the turn.
    const float up[3] = {turn[1], turn[4], turn[7]};
    const Run given = run(tilted, up);
    CHECK(given.labels == upright.labels);
    CHECK(farthest(given.margins, upright.margins) < 1e-3f);
    // Without it the tilt is a shift the model sees (the toy's actions differ enough to keep their labels).
    CHECK(farthest(run(tilted, nullptr).margins, upright.margins) > 0.05f);
    // The model's own axis given as the up changes nothing, bit for bit.
    const float along[3] = {0.0f, 2.0f, 0.0f};
    const Run same = run(frames, along);
    CHECK(same.labels == upright.labels);
    CHECK(same.margins == upright.margins);
    // An up that is not a direction is refused.
    host::Stateful<Annotator> annotator;
    AnnotatorConfig bad = annotator_config(view);
    bad.up[1] = std::numeric_limits<float>::infinity();
    CHECK(annotator.init(view, bad) == Status::invalid_argument);
    bad.up[1] = 1e-8f;
    CHECK(annotator.init(view, bad) == Status::invalid_argument);
}

TEST_CASE("with a label lead, a frame takes the label of the character that lead after it") {
    const host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    // Frames every 25 ms, so a lead of a whole number of frames maps each frame onto a later one exactly.
    host::ToyStreamOptions stream;
    stream.frame_rate_hz = 40.0;
    const auto frames = host::toy_stream(world, {1, 3, 0, 2}, stream);
    std::vector<double> times;
    std::vector<float> positions;
    for (const host::ToyFrame& frame : frames) {
        REQUIRE(frame.time_us % 25000 == 0);
        times.push_back(static_cast<double>(frame.time_us) * 1e-6);
        positions.insert(positions.end(), frame.positions.begin(), frame.positions.end());
    }
    const std::size_t joints = frames.front().positions.size() / 3;
    AnnotatorConfig config = annotator_config(view);
    const host::StreamLabels at_ticks = host::label_stream(view, config, times, positions.data(), joints);
    for (const std::size_t shift : {std::size_t{1}, std::size_t{4}, std::size_t{10}}) {
        CAPTURE(shift);
        config.label_lead_us = static_cast<std::int64_t>(shift) * 25000;
        const host::StreamLabels led = host::label_stream(view, config, times, positions.data(), joints);
        REQUIRE(led.settled.size() == frames.size());
        std::size_t changed = 0;
        for (std::size_t f = 0; f + shift < frames.size(); ++f) {
            CHECK(led.settled[f] == at_ticks.settled[f + shift]);
            // Its label comes when that later frame's does.
            CHECK(led.settled_at_s[f] == std::max(at_ticks.settled_at_s[f + shift], times[f]));
            changed += led.settled[f] != at_ticks.settled[f];
        }
        CHECK(changed > 0);                // the actions' boundaries moved
        CHECK(led.live == at_ticks.live);  // the live label is the newest character's, whatever the lead
    }
    // Without the paper's window rule: the segmenter's labels and events are the same, the window's unknown.
    config.label_lead_us = 0;
    const host::StreamLabels segmenter_only =
        host::label_stream(view, config, times, positions.data(), joints, /*paper_rule=*/false);
    CHECK(segmenter_only.settled == at_ticks.settled);
    CHECK(segmenter_only.settled_at_s == at_ticks.settled_at_s);
    CHECK(segmenter_only.live == at_ticks.live);
    REQUIRE(segmenter_only.events.size() == at_ticks.events.size());
    for (std::size_t i = 0; i < at_ticks.events.size(); ++i)
        CHECK(segmenter_only.events[i].event.start_time_us == at_ticks.events[i].event.start_time_us);
    const auto unknown_windows = [](const host::StreamLabels& labels) {
        return std::count(labels.window.begin(), labels.window.end(), host::unknown_frame);
    };
    CHECK(unknown_windows(at_ticks) < static_cast<std::ptrdiff_t>(frames.size()));
    CHECK(unknown_windows(segmenter_only) == static_cast<std::ptrdiff_t>(frames.size()));
}

TEST_CASE("spread_work reports the same labels and events, at most one character later") {
    host::ToyOptions toy;
    const host::ToyWorld world = host::make_toy_world(toy);
    const ModelView view = world.model.view();
    struct Report {
        std::vector<std::pair<std::uint64_t, LabelId>> settled;  // in the order reported
        std::vector<std::int64_t> settled_at;                    // the frame time each was reported at
        std::vector<ActionEvent> events;
        std::vector<std::int64_t> events_at;
        std::vector<std::uint64_t> restarts;  // frames that restarted the stream
        std::vector<WindowResult> windows;
        std::size_t later_frames = 0;
    };
    const auto run = [&](const std::vector<host::ToyFrame>& frames, bool spread, const std::vector<bool>& lost) {
        AnnotatorConfig config = test::every_rule(view);
        config.spread_work = spread;
        host::Stateful<Annotator> annotator;
        REQUIRE(annotator.init(view, config) == Status::ok);
        Report out;
        const std::vector<float> zeros(frames.front().positions.size(), 0.0f);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const FrameResult r =
                annotator->push_frame(frames[i].time_us, lost[i] ? zeros.data() : frames[i].positions.data());
            if (r.status == Status::stream_restarted) out.restarts.push_back(i);
            if (r.windows_completed > 0) out.windows.push_back(*annotator->last_window());
            for (std::uint32_t k = 0; k < r.characters_settled; ++k) {
                const std::uint64_t c = annotator->settled_character() - (r.characters_settled - 1 - k);
                out.settled.emplace_back(c, annotator->settled_label(c));
                out.settled_at.push_back(frames[i].time_us);
            }
            for (std::uint32_t e = 0; e < r.events; ++e) {
                out.events.push_back(annotator->event(e));
                out.events_at.push_back(frames[i].time_us);
            }
        }
        // The work still in progress at the end, then the tail.
        const FrameResult last = annotator->finish_work();
        CHECK(last.status == Status::ok);
        // Spread, the character in progress and one queued at most.
        CHECK(last.characters_settled <= (spread ? 2u : 0u));
        for (std::uint32_t k = 0; k < last.characters_settled; ++k) {
            const std::uint64_t c = annotator->settled_character() - (last.characters_settled - 1 - k);
            out.settled.emplace_back(c, annotator->settled_label(c));
            out.settled_at.push_back(frames.back().time_us + 1);
        }
        if (last.windows_completed > 0) out.windows.push_back(*annotator->last_window());
        for (std::uint32_t e = 0; e < last.events; ++e) {
            out.events.push_back(annotator->event(e));
            out.events_at.push_back(frames.back().time_us + 1);
        }
        const std::uint32_t flushed = annotator->flush();
        for (std::uint32_t e = 0; e < flushed; ++e) {
            out.events.push_back(annotator->event(e));
            out.events_at.push_back(frames.back().time_us + 2);
        }
        return out;
    };
    for (const double rate : {30.0, 120.0, 200.0}) {
        for (const int kind : {0, 1, 2}) {  // regular frames; jitter and drops; a loss long enough to restart
            INFO("rate ", rate, " kind ", kind);
            host::ToyStreamOptions options;
            options.frame_rate_hz = rate;
            options.seed = static_cast<std::uint32_t>(rate) + static_cast<std::uint32_t>(kind);
            if (kind == 1) options.frame_time_jitter = 0.3, options.drop_probability = 0.2;
            const auto frames = host::toy_stream(world, {0, 2, 1, 3, 0}, options);
            std::vector<bool> lost(frames.size(), false);
            if (kind == 2)
                for (std::size_t i = frames.size() / 3; i < frames.size() / 2; ++i) lost[i] = true;
            const Report plain = run(frames, false, lost);
            const Report spread = run(frames, true, lost);
            REQUIRE(plain.settled.size() > 20);
            // A restart finishes the old stream's last characters (the one
            // in progress, one queued) without counting what they settle
            // (their events are reported): the settled labels just before
            // the restart are missing then (when the work was still open).
            std::vector<std::pair<std::uint64_t, LabelId>> expected = plain.settled;
            std::vector<std::int64_t> expected_at = plain.settled_at;
            REQUIRE(spread.settled.size() <= plain.settled.size());
            const std::size_t missing = plain.settled.size() - spread.settled.size();
            CHECK(missing <= (kind == 2 ? 2u : 0u));
            if (kind == 2 && missing > 0 && missing <= 2) {
                REQUIRE(plain.restarts.size() == 1);
                const std::int64_t restart_us = frames[plain.restarts.front()].time_us;
                const auto it = std::lower_bound(expected_at.begin(), expected_at.end(), restart_us);
                REQUIRE(it - expected_at.begin() >= static_cast<std::ptrdiff_t>(missing));
                expected.erase(it - static_cast<std::ptrdiff_t>(missing) - expected_at.begin() + expected.begin(),
                               it - expected_at.begin() + expected.begin());
                expected_at.erase(it - static_cast<std::ptrdiff_t>(missing), it);
            }
            // The windows too, in order (a restart's old windows are not the new stream's).
            if (kind != 2) {
                REQUIRE(spread.windows.size() == plain.windows.size());
                CHECK(!plain.windows.empty());
                for (std::size_t w = 0; w < plain.windows.size(); ++w) {
                    CHECK(spread.windows[w].first_character == plain.windows[w].first_character);
                    CHECK(spread.windows[w].start_time_us == plain.windows[w].start_time_us);
                    CHECK(spread.windows[w].end_time_us == plain.windows[w].end_time_us);
                    CHECK(spread.windows[w].classification.label == plain.windows[w].classification.label);
                    CHECK(spread.windows[w].classification.confidence == plain.windows[w].classification.confidence);
                }
            }
            CHECK(spread.settled == expected);
            CHECK(spread.restarts == plain.restarts);
            const bool restarted = !plain.restarts.empty();
            CHECK(restarted == (kind == 2));
            REQUIRE(spread.events.size() == plain.events.size());
            CHECK(!plain.events.empty());
            for (std::size_t e = 0; e < plain.events.size(); ++e) {
                check_same_event(plain.events[e], spread.events[e]);
                CHECK(spread.events_at[e] >= plain.events_at[e]);
            }
            // Never earlier, and on a stream that does not restart at most
            // one string period and a frame interval later (the next
            // character's frame finishes the last one's work).
            std::size_t later = 0;
            std::int64_t longest_interval = 0;
            for (std::size_t i = 1; i < frames.size(); ++i)
                longest_interval = std::max(longest_interval, frames[i].time_us - frames[i - 1].time_us);
            REQUIRE(spread.settled_at.size() == expected_at.size());
            for (std::size_t k = 0; k < expected_at.size(); ++k) {
                CHECK(spread.settled_at[k] >= expected_at[k]);
                later += spread.settled_at[k] > expected_at[k];
                if (kind != 2 && k + 1 < expected_at.size())
                    CHECK(spread.settled_at[k] - expected_at[k] <= view.string_period_us + longest_interval);
            }
            // With several frames per character, most characters' work was
            // spread (at 30 Hz a toy string period holds about one frame).
            const double frames_per_char = static_cast<double>(view.string_period_us) * rate / 1e6;
            if (frames_per_char >= 3.0) CHECK(later * 2 > plain.settled_at.size());
        }
    }
}

TEST_CASE("a restart and flush() give the ended stream's tail its labels: flushed, never lost") {
    const host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    auto frames = host::toy_stream(world, {0, 2, 1, 3, 0, 2}, {});
    // A gap of 3 s (over max_gap_us) two thirds of the way in restarts the stream there.
    const std::size_t gap = frames.size() * 2 / 3;
    for (std::size_t i = gap; i < frames.size(); ++i) frames[i].time_us += 3000000;
    // With early settling too (variants 2 and 3): the tail is then what the rule has not settled.
    for (const int variant : {0, 1, 2, 3}) {
        const bool spread = variant % 2 == 1;
        const std::int64_t stable_us = variant >= 2 ? 500000 : 0;
        CAPTURE(spread);
        CAPTURE(stable_us);
        AnnotatorConfig config = annotator_config(view);
        config.spread_work = spread;
        config.label_lead_us = 100000;
        config.segmenter.settle_stable_us = stable_us;
        // What the best explanation says of the unsettled tail just before the gap, by hand.
        host::Stateful<Annotator> before;
        REQUIRE(before.init(view, config) == Status::ok);
        std::uint64_t reported = 0;  // characters reported settled so far
        for (std::size_t i = 0; i < gap; ++i) {
            const FrameResult r = before->push_frame(frames[i].time_us, frames[i].positions.data());
            reported += r.characters_settled;
        }
        const FrameResult rest = before->finish_work();  // what the restart finishes first, spread
        std::vector<LabelId> expected;
        for (std::uint64_t c = 0; c < rest.characters_settled; ++c)
            expected.push_back(before->settled_label(reported + c));
        for (std::uint64_t c = reported + rest.characters_settled; c < before->characters(); ++c)
            expected.push_back(before->provisional_label(c));
        if (stable_us == 0) REQUIRE(expected.size() >= before->settle_chars());
        const std::uint64_t ended_characters = before->characters();
        const std::int64_t ended_origin = before->character_time_us(0);
        // The same frames and the one after the gap: the restart flushes exactly those.
        host::Stateful<Annotator> annotator;
        REQUIRE(annotator.init(view, config) == Status::ok);
        for (std::size_t i = 0; i < gap; ++i) {
            const FrameResult r = annotator->push_frame(frames[i].time_us, frames[i].positions.data());
            CHECK(r.characters_flushed == 0);
        }
        const FrameResult restart = annotator->push_frame(frames[gap].time_us, frames[gap].positions.data());
        REQUIRE(restart.status == Status::stream_restarted);
        REQUIRE(restart.characters_flushed == expected.size());
        CHECK(restart.characters_flushed <= annotator->settled_history());
        REQUIRE(annotator->flushed_characters() == expected.size());
        for (std::size_t i = 0; i < expected.size(); ++i) {
            CHECK(annotator->flushed_character(i) == reported + i);
            CHECK(annotator->flushed_label(i) == expected[i]);
            CHECK(annotator->flushed_label_time_us(i) ==
                  ended_origin + static_cast<std::int64_t>((reported + i) * view.string_period_us) - 100000);
        }
        CHECK(annotator->flushed_character(expected.size() - 1) + 1 == ended_characters);
        CHECK(annotator->flushed_label(expected.size()) == unknown_label);
        // The next frame's result starts afresh.
        const FrameResult next = annotator->push_frame(frames[gap + 1].time_us, frames[gap + 1].positions.data());
        CHECK(next.characters_flushed == 0);
        CHECK(annotator->flushed_characters() == 0);
        // flush() at the end flushes the new stream's tail the same way.
        for (std::size_t i = gap + 2; i < frames.size(); ++i)
            annotator->push_frame(frames[i].time_us, frames[i].positions.data());
        annotator->finish_work();  // spread: the character in progress settles first, reported
        std::vector<LabelId> tail;
        const std::uint64_t first = annotator->has_settled() ? annotator->settled_character() + 1 : 0;
        for (std::uint64_t c = first; c < annotator->characters(); ++c) tail.push_back(annotator->provisional_label(c));
        annotator->flush();
        REQUIRE(annotator->flushed_characters() == tail.size());
        for (std::size_t i = 0; i < tail.size(); ++i) {
            CHECK(annotator->flushed_character(i) == first + i);
            CHECK(annotator->flushed_label(i) == tail[i]);
        }
        annotator->reset();
        CHECK(annotator->flushed_characters() == 0);
    }
    // label_stream() labels the ended stream's tail with them: nothing before the gap is unknown
    // but frames before the first character.
    std::vector<double> times;
    std::vector<float> positions;
    for (const host::ToyFrame& frame : frames) {
        times.push_back(static_cast<double>(frame.time_us) * 1e-6);
        positions.insert(positions.end(), frame.positions.begin(), frame.positions.end());
    }
    const host::StreamLabels labels =
        host::label_stream(view, annotator_config(view), times, positions.data(), frames.front().positions.size() / 3);
    std::size_t unknown_before_gap = 0;
    for (std::size_t i = 0; i < gap; ++i) unknown_before_gap += labels.settled[i] == host::unknown_frame;
    CHECK(unknown_before_gap <= 2);  // the frames before the first character at most
    std::size_t unknown_after = 0;
    for (std::size_t i = gap; i < frames.size(); ++i) unknown_after += labels.settled[i] == host::unknown_frame;
    CHECK(unknown_after <= 2);  // and the end of the stream is flushed too
}

TEST_CASE("a stream's jump bound: 3 m/s unless set, 0 turns it off, a negative or NaN one refused") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    CHECK(AnnotatorConfig{}.max_pose_speed == default_max_pose_speed);
    CHECK(annotator_config(view).max_pose_speed == default_max_pose_speed);
    CHECK(default_max_pose_speed == 3.0f);
    // The encoder takes a clip as recorded unless told otherwise.
    CHECK(EncoderConfig{}.max_pose_speed == 0.0f);
    host::Stateful<Annotator> annotator;
    AnnotatorConfig config = annotator_config(view);
    config.max_pose_speed = 0.0f;
    CHECK(annotator.init(view, config) == Status::ok);
    for (const float bad : {-1.0f, std::nanf("")}) {
        config.max_pose_speed = bad;
        CHECK(annotator.init(view, config) == Status::invalid_argument);
    }
}
