// actionstring — action events from the settled labels: once when an action
// starts, once when it ends (design.md §1.8).
//
// The segmenter settles one label per character. A device usually wants less:
// "a squat started at 12.3 s", then "it ended at 14.1 s", each exactly once.
// The tracker turns the settled labels into runs of one label and reports a
// run as `started` once it has lasted `min_chars` characters (shorter runs are
// flicker and are never reported). A started action ends only when another
// label (or no action) has lasted `min_chars` after it, or the stream ends; a
// shorter interruption is flicker inside the action and joins it. So each
// action gives one `started` and one `ended`. "No action" never makes an
// event. Each event carries the action's first and last character, their
// times, and a confidence: the share of its characters whose live label
// (decided without the settle delay) already said this label.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/model.hpp"

namespace actionstring {

/// One action event.
struct ActionEvent {
    enum class Kind : std::uint8_t { started = 0, ended = 1 };
    Kind kind = Kind::started;
    LabelId label = unknown_label;
    /// The action's first character, and its last (ended) or newest so far (started).
    std::uint64_t first_character = 0;
    std::uint64_t last_character = 0;
    /// Where the action's labels apply, in the stream's clock (microseconds):
    /// from its first character's label time (its tick, less the label lead;
    /// Annotator::label_time_us()) to the next character's after its last
    /// (or newest so far), where the last one's label stops applying.
    std::int64_t start_time_us = 0;
    std::int64_t end_time_us = 0;
    /// Share in [0, 1] of the action's characters (so far) whose live label was this label.
    float confidence = 0.0f;
};

/// Settled labels in, action events out. Holds its few events in the object
/// (no storage of its own to size); events stay readable until the next
/// begin_frame(). Characters are given in stream order, one call each.
class ActionEventTracker {
public:
    /// Events one frame can hold. A frame settles one character at a 120 Hz
    /// stream and a 12 Hz string, or with early settling a run of them; only a
    /// burst of flicker inside one frame's characters could exceed it (each
    /// event needs min_chars of them), and then the oldest are dropped (counted).
    static constexpr std::size_t max_events = 16;

    /// Starts a stream; `min_chars` (≥ 1) is the shortest run reported.
    void reset(std::uint32_t min_chars) noexcept {
        min_chars_ = min_chars == 0 ? 1u : min_chars;
        run_ = Run{};
        pending_ = Run{};
        count_ = 0;
    }

    /// Forgets the previous frame's events.
    void begin_frame() noexcept { count_ = 0; }

    /// One settled character: its label, whether its live label agreed, and
    /// the time its label applies from and the time it stops applying (its
    /// label time, and the next character's).
    void settle(std::uint64_t character, LabelId label, bool live_agreed, std::int64_t time_us,
                std::int64_t until_us) noexcept {
        if (!run_.reported) {
            // A candidate: the same label extends it, another replaces it.
            if (run_.active && label == run_.label) extend(run_, character, until_us, live_agreed);
            else begin_run(run_, character, label, live_agreed, time_us, until_us);
            report_if_long(run_);
            return;
        }
        // Inside a started action.
        if (label == run_.label) {
            if (pending_.active) {  // flicker: the interruption joins the action
                run_.last = pending_.last;
                run_.end_us = pending_.end_us;
                pending_ = Run{};
            }
            extend(run_, character, until_us, live_agreed);
            return;
        }
        if (pending_.active && label == pending_.label) extend(pending_, character, until_us, live_agreed);
        else begin_run(pending_, character, label, live_agreed, time_us, until_us);
        if (length(pending_) < min_chars_) return;
        // The interruption lasted: the action ended before it, and it is the new candidate.
        push(ActionEvent::Kind::ended, run_);
        run_ = pending_;
        pending_ = Run{};
        report_if_long(run_);
    }

    /// The stream ends (or restarts): an action still running ends here.
    void close() noexcept {
        if (run_.active && run_.reported) push(ActionEvent::Kind::ended, run_);
        run_ = Run{};
        pending_ = Run{};
    }

    std::size_t event_count() const noexcept { return count_; }
    /// Event i of this frame (i < event_count()).
    const ActionEvent& event(std::size_t i) const noexcept { return events_[i]; }
    /// Events dropped since the tracker was made because a frame held more than max_events.
    std::uint32_t dropped() const noexcept { return dropped_; }
    /// Whether an action has started and not yet ended.
    bool in_action() const noexcept { return run_.active && run_.reported; }

private:
    struct Run {
        bool active = false;
        LabelId label = unknown_label;
        std::uint64_t first = 0, last = 0;
        std::int64_t start_us = 0, end_us = 0;
        std::uint32_t agreed = 0;
        bool reported = false;
    };

    static std::uint64_t length(const Run& run) noexcept { return run.last - run.first + 1; }
    // A run of one character (built in place: a character that extends a run,
    // the common case, pays nothing for it).
    static void begin_run(Run& run, std::uint64_t character, LabelId label, bool live_agreed, std::int64_t time_us,
                          std::int64_t until_us) noexcept {
        run = Run{true, label, character, character, time_us, until_us, live_agreed ? 1u : 0u, false};
    }
    static void extend(Run& run, std::uint64_t character, std::int64_t until_us, bool live_agreed) noexcept {
        run.last = character;
        run.end_us = until_us;
        run.agreed += live_agreed ? 1u : 0u;
    }
    void report_if_long(Run& run) noexcept {
        if (run.reported || run.label == unknown_label || length(run) < min_chars_) return;
        run.reported = true;
        push(ActionEvent::Kind::started, run);
    }

    void push(ActionEvent::Kind kind, const Run& run) noexcept {
        if (count_ == max_events) {
            for (std::size_t i = 1; i < max_events; ++i) events_[i - 1] = events_[i];
            --count_;
            ++dropped_;
        }
        ActionEvent& e = events_[count_++];
        e.kind = kind;
        e.label = run.label;
        e.first_character = run.first;
        e.last_character = run.last;
        e.start_time_us = run.start_us;
        e.end_time_us = run.end_us;
        e.confidence = static_cast<float>(run.agreed) / static_cast<float>(length(run));
    }

    std::uint32_t min_chars_ = 1;
    Run run_;      // the current action, or the candidate for one
    Run pending_;  // another label's run inside a started action, not yet long enough to end it
    ActionEvent events_[max_events] = {};
    std::size_t count_ = 0;
    std::uint32_t dropped_ = 0;
};

}  // namespace actionstring
