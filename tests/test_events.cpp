// Action events: exactly one start and one end per action, none in silence,
// flicker joined, the tail flushed at the end of a stream.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/events.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"

using namespace actionstring;

namespace {

constexpr LabelId U = unknown_label;

// Feeds settled labels (one per character, 100 ms apart) and collects every event as text.
std::vector<std::string> run(const std::vector<LabelId>& labels, std::uint32_t min_chars, bool close = true) {
    ActionEventTracker tracker;
    tracker.reset(min_chars);
    std::vector<std::string> out;
    auto collect = [&] {
        for (std::size_t i = 0; i < tracker.event_count(); ++i) {
            const ActionEvent& e = tracker.event(i);
            out.push_back(std::string(e.kind == ActionEvent::Kind::started ? "start " : "end ") +
                          std::to_string(e.label) + " " + std::to_string(e.first_character) + "-" +
                          std::to_string(e.last_character));
        }
    };
    for (std::size_t c = 0; c < labels.size(); ++c) {
        tracker.begin_frame();
        tracker.settle(c, labels[c], true, static_cast<std::int64_t>(c) * 100000,
                       static_cast<std::int64_t>(c + 1) * 100000);
        collect();
    }
    if (close) {
        tracker.begin_frame();
        tracker.close();
        collect();
    }
    return out;
}

}  // namespace

TEST_CASE("each action gives one start (after min_chars) and one end; silence gives none") {
    const std::vector<std::string> expected{"start 0 2-3", "end 0 2-5", "start 1 8-9", "end 1 8-10"};
    CHECK(run({U, U, 0, 0, 0, 0, U, U, 1, 1, 1, U, U}, 2) == expected);
    CHECK(run(std::vector<LabelId>(50, U), 1).empty());
    CHECK(run({U, 0, U, U, 1, U}, 2).empty());  // single characters are flicker at min_chars 2
}

TEST_CASE("an action's times run from its first character's label time to where its last one's stops") {
    ActionEventTracker tracker;
    tracker.reset(2);
    const std::vector<LabelId> labels{U, 0, 0, 0, U, U};
    std::vector<ActionEvent> events;
    for (std::size_t c = 0; c < labels.size(); ++c) {
        tracker.begin_frame();
        // Characters 100 ms apart, each label applying until the next character's.
        tracker.settle(c, labels[c], true, 1000000 + static_cast<std::int64_t>(c) * 100000,
                       1000000 + static_cast<std::int64_t>(c + 1) * 100000);
        for (std::size_t i = 0; i < tracker.event_count(); ++i) events.push_back(tracker.event(i));
    }
    REQUIRE(events.size() == 2);
    CHECK(events[0].kind == ActionEvent::Kind::started);
    CHECK(events[0].start_time_us == 1100000);
    CHECK(events[0].end_time_us == 1300000);  // characters 1 and 2 so far
    CHECK(events[1].kind == ActionEvent::Kind::ended);
    CHECK(events[1].start_time_us == 1100000);
    CHECK(events[1].end_time_us == 1400000);  // characters 1 to 3: until character 4's label time
}

TEST_CASE("an interruption shorter than min_chars joins the action") {
    const std::vector<std::string> expected{"start 0 0-2", "end 0 0-8"};
    CHECK(run({0, 0, 0, 1, 0, 0, U, 0, 0}, 3) == expected);
    // Back to back: the second action ends the first once it has lasted.
    const std::vector<std::string> back_to_back{"start 0 0-1", "end 0 0-3", "start 1 4-5", "end 1 4-6"};
    CHECK(run({0, 0, 0, 0, 1, 1, 1}, 2) == back_to_back);
}

TEST_CASE("an action still running when the stream ends is closed then, once") {
    CHECK(run({U, 0, 0, 0}, 2, false) == std::vector<std::string>{"start 0 1-2"});
    CHECK(run({U, 0, 0, 0}, 2, true) == std::vector<std::string>{"start 0 1-2", "end 0 1-3"});
}

TEST_CASE("the annotator reports each performed action once, and flushes a short clip") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    host::ToyStreamOptions options;
    options.position_noise_m = 0.005;
    const std::vector<int> sequence{0, 1, 2, 3, 1};
    const auto frames = host::toy_stream(world, sequence, options);

    AnnotatorConfig config = annotator_config(view);
    config.segmenter.settle_delay_us = 1000000;
    host::Stateful<Annotator> annotator;
    REQUIRE(annotator.init(view, config) == Status::ok);
    std::vector<ActionEvent> events;
    for (const auto& frame : frames) {
        const FrameResult r = annotator->push_frame(frame.time_us, frame.positions.data());
        REQUIRE(r.events == annotator->event_count());
        for (std::size_t i = 0; i < r.events; ++i) events.push_back(annotator->event(i));
    }
    const std::uint32_t flushed = annotator->flush();
    for (std::size_t i = 0; i < flushed; ++i) events.push_back(annotator->event(i));
    CHECK(annotator->events_dropped() == 0);
    // Alternating start/end, one pair per action, labels in the order performed.
    REQUIRE(events.size() == 2 * sequence.size());
    for (std::size_t a = 0; a < sequence.size(); ++a) {
        const ActionEvent& start = events[2 * a];
        const ActionEvent& end = events[2 * a + 1];
        CHECK(start.kind == ActionEvent::Kind::started);
        CHECK(end.kind == ActionEvent::Kind::ended);
        CHECK(start.label == sequence[a]);
        CHECK(end.label == sequence[a]);
        CHECK(end.first_character == start.first_character);
        CHECK(end.end_time_us > end.start_time_us);
        CHECK(end.confidence >= 0.0f);
        CHECK(end.confidence <= 1.0f);
        if (a > 0) CHECK(start.first_character > events[2 * a - 1].last_character);
    }
    CHECK(!annotator->in_action());

    // One action shorter than the settle delay: nothing settles while streaming,
    // the flush gives it its label.
    config.segmenter.settle_delay_us = 10000000;
    REQUIRE(annotator.init(view, config) == Status::ok);
    std::size_t streamed = 0;
    for (const auto& frame : host::toy_stream(world, {2}, options))
        streamed += annotator->push_frame(frame.time_us, frame.positions.data()).events;
    CHECK(streamed == 0);
    REQUIRE(annotator->flush() == 2);
    CHECK(annotator->event(0).kind == ActionEvent::Kind::started);
    CHECK(annotator->event(0).label == 2);
    CHECK(annotator->event(1).kind == ActionEvent::Kind::ended);
    CHECK(annotator->characters() == 0);  // the next frame starts a new stream
}

TEST_CASE("a gap that restarts the stream ends the running action at once") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    AnnotatorConfig config = annotator_config(view);
    config.segmenter.settle_delay_us = 500000;
    host::Stateful<Annotator> annotator;
    REQUIRE(annotator.init(view, config) == Status::ok);
    host::ToyStreamOptions options;
    std::int64_t last = 0;
    std::size_t started = 0;
    for (const auto& frame : host::toy_stream(world, {1, 1}, options)) {
        started += annotator->push_frame(frame.time_us, frame.positions.data()).events;
        last = frame.time_us;
    }
    CHECK(started >= 1);  // the action started while streaming
    REQUIRE(annotator->in_action());
    const auto again = host::toy_stream(world, {3}, options);
    const FrameResult r = annotator->push_frame(last + 5000000, again.front().positions.data());  // 5 s later
    CHECK(r.status == Status::stream_restarted);
    REQUIRE(r.events >= 1);
    CHECK(annotator->event(r.events - 1).kind == ActionEvent::Kind::ended);
    CHECK(annotator->event(r.events - 1).label == 1);
    // It ends with the old stream: where its last character's label stops, one tick after it at most.
    CHECK(annotator->event(r.events - 1).end_time_us <= last + static_cast<std::int64_t>(view.string_period_us));
}
