// actionstring — the per-frame annotator: every stage in order (design.md §2).
//
// push_frame(): StringEncoder (normalise → project → GMM posterior → tree
// descent, at the string rate) → two labelling rules fed the same characters:
//  * WindowMatcher (one DP line per open window and representative) → kNN
//    label whenever a window completes: the paper's rule, label();
//  * ActionSegmenter (the string explained as representatives end to end) →
//    a live label and, settle_delay later (or sooner, once the explanation
//    has kept it settle_stable long), a final label per character:
//    live_label(), settled_label(). This rule labels streams of actions far
//    better (models/README.md has the figures).
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/classify.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/events.hpp"
#include "actionstring/matcher.hpp"
#include "actionstring/model.hpp"
#include "actionstring/segmenter.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"

namespace actionstring {

/// Stream settings that are not part of the model.
struct AnnotatorConfig {
    /// A gap longer than this between accepted frames (dropped or rejected
    /// frames, a paused source) restarts the stream: open windows are
    /// discarded and the label becomes unknown. At least one string period, at
    /// most 60 s and at most max_ticks_per_frame periods, so no frame's work
    /// grows with its gap (StringSampler::settings_ok()).
    std::int64_t max_gap_us = 1000000;
    /// A frame up to this much earlier than the last accepted one is rejected
    /// (jitter, reordered packets); one further back means the clock was reset
    /// or wrapped (a 32-bit microsecond timer wraps every 71.6 minutes), and
    /// the stream restarts at it instead of waiting for the clock to catch up.
    /// In [0, max_gap_us].
    std::int64_t max_backward_us = 100000;
    /// The sensor's up direction in the positions' coordinates, when the
    /// device knows it and it differs from the model's up axis (a Kinect's
    /// floor plane normal, gravity from a headset's IMU): every frame is
    /// turned to put it along the axis, so a sensor mounted higher, lower or
    /// rolled gives the poses the training sensor gave (normalize.hpp,
    /// up_rotation()). All zero: the positions' up is the model's. Not finite
    /// or shorter than 1e-6: init() refuses it.
    float up[3] = {0.0f, 0.0f, 0.0f};
    /// A pose that moved faster than this since the previous frame (the mean
    /// over its coordinates, metres per second), and by much more than the
    /// stream's frames typically move, jumped, and its motion starts again
    /// from it (EncoderConfig::max_pose_speed, which says why; 0: never). A
    /// stream is where joined clips and a tracker that loses the body make
    /// jumps; a clip is taken as recorded (the encoder's default, 0).
    /// Negative or NaN: init() refuses it.
    float max_pose_speed = default_max_pose_speed;
    /// Whether to run the paper's sliding-window rule beside the segmenter
    /// (label(), last_window()). Off, its state (the largest part) is not
    /// paid for and label() stays unknown; the settled label is the better
    /// rule on streams (models/README.md).
    bool window_rule = false;
    /// Settings of the segmenter (settle delay, penalties, unknown cost).
    SegmenterConfig segmenter;
    /// Action events (events.hpp): a settled run of one label shorter than
    /// this is flicker and is never reported. Longer filters more flicker
    /// but reports each action later; a model carries its own (chosen at
    /// training, ModelView::min_action_us).
    std::int64_t min_action_us = 250000;
    /// How much earlier than its tick a character's label applies
    /// (label_time_us(), and the events' start and end times). A character
    /// is made from the feature at its tick, whose motion is a difference
    /// back over the model's span: an action shows in the characters a
    /// little after it shows in the body, so placing each label this much
    /// earlier puts the boundaries where the actions change. It moves times
    /// only: what is settled, and when, is the same. A model carries its own
    /// (chosen at training, ModelView::label_lead_us); 0 to max_settle_delay_us.
    std::int64_t label_lead_us = 0;
    /// Spread each character's work (the encoder's projection, GMM and tree;
    /// the segmenter's pass over every representative character, and over
    /// the exemplars when the settings weigh them) over the frames until the
    /// next character is due, instead of doing it all in the frame that
    /// emits the character. The frames' cost becomes flat (a real-time budget
    /// is set by the costliest frame): each frame does its share of what is
    /// left, judged from the last frame interval and the next tick's time.
    /// The characters, labels, their times and the events are bit for bit the
    /// same; each is reported up to one string period later (last_character(),
    /// live_label(), settled labels, windows, events), and a frame that emits
    /// the next character first finishes the last (finish_work() does it at
    /// once). A frame that restarts the stream finishes the old stream's last
    /// characters too (the one in progress and those queued): their events
    /// are reported, but the labels they settle and the windows they complete
    /// are not counted in its FrameResult, as they are not the new stream's.
    /// Needs more storage: two queued poses (required_bytes()).
    bool spread_work = false;
};

/// The default timing with the model's own online settings (the segmenter's
/// and the events' shortest action).
constexpr AnnotatorConfig annotator_config(const ModelView& model) noexcept {
    AnnotatorConfig c;
    c.segmenter = segmenter_config(model);
    c.min_action_us = model.min_action_us;
    c.label_lead_us = model.label_lead_us;
    return c;
}

/// What one push_frame() did.
struct FrameResult {
    /// ok or stream_restarted when the frame was accepted; otherwise the reason
    /// it was rejected (non_finite_input, tracking_lost, degenerate_pose,
    /// pose_out_of_range, time_went_backwards, not_initialized, invalid_argument).
    /// A rejected frame changes nothing: the string, windows and label hold.
    Status status = Status::ok;
    /// Characters this frame appended to the action string (with spread_work,
    /// the ticks it took: their characters are computed over the next frames).
    std::uint32_t characters = 0;
    /// Windows that completed during this frame (the last one is last_window()).
    std::uint32_t windows_completed = 0;
    /// Characters whose label the segmenter settled during this frame (the
    /// last one is settled_character(); one per character once the stream is
    /// settle_chars() long, or with SegmenterConfig::settle_stable_us none on
    /// some characters and several on others).
    std::uint32_t characters_settled = 0;
    /// When this frame restarted the stream: the ended stream's last
    /// characters, whose labels became final with the restart (those not
    /// reported settled before; the best explanation's labels at the end, as
    /// flush() gives them): flushed_label(0 … characters_flushed − 1).
    std::uint32_t characters_flushed = 0;
    /// Action events (started, ended) this frame produced: event(0 … events − 1).
    std::uint32_t events = 0;
};

/// One completed sliding window and the label it voted for.
struct WindowResult {
    std::uint64_t first_character = 0;  ///< Stream index of its first character.
    std::int64_t start_time_us = 0;     ///< Time of its first character's tick.
    std::int64_t end_time_us = 0;       ///< Time of its last character's tick.
    Classification classification;
};

/// The runtime recogniser. It works in caller-owned storage of
/// required_bytes(model, config) bytes (storage.hpp) and never allocates. A
/// generated header emits that size for its model and own settings
/// (kAnnotatorBytes), so firmware keeps a static StateBuffer; a host allocates
/// exactly what a loaded model needs. Keeps pointers to the ModelView given to
/// init() and to the storage: both must outlive the annotator (or its next init()).
class Annotator {
public:
    /// Bytes of storage init() needs for this model and these settings
    /// (constexpr when both are); unsatisfiable_bytes for settings init() refuses.
    static constexpr std::size_t required_bytes(const ModelView& model, const AnnotatorConfig& config) noexcept {
        return plan(model, config).bytes;
    }

    /// Binds a model with the given settings, in `storage` (`bytes` long,
    /// aligned to state_alignment). Returns invalid_model (inconsistent
    /// tables, or precision factors that could overflow float),
    /// invalid_argument (config), storage_too_small, model_exceeds_capacity
    /// or ok. Not usable until it returns ok.
    Status init(const ModelView& model, const AnnotatorConfig& config, void* storage, std::size_t bytes) noexcept {
        model_ = nullptr;
        // Settings first, so a bad one is reported as such rather than as a size.
        Status status = ActionSegmenter::check(model, config.segmenter);
        if (status != Status::ok) return status;
        if (!(config.min_action_us >= 0 && config.min_action_us <= max_settle_delay_us) ||
            !(config.label_lead_us >= 0 && config.label_lead_us <= max_settle_delay_us))
            return Status::invalid_argument;
        const Plan p = plan(model, config);
        if (!detail::storage_fits(storage, bytes, p.bytes)) {
            // Report a broken model before a size computed from it.
            status = validate_model(model);
            return status != Status::ok ? status : Status::storage_too_small;
        }
        auto* base = static_cast<unsigned char*>(storage);
        window_rule_ = config.window_rule;
        status =
            window_rule_ ? matcher_.init(model, base + p.matcher, p.matcher_bytes) : validate_matching_tables(model);
        if (status == Status::ok)
            status = segmenter_.init(model, config.segmenter, base + p.segmenter, p.segmenter_bytes);
        if (status == Status::ok)
            status = encoder_.init(model, encoder_config(config), base + p.encoder, p.encoder_bytes);
        if (status != Status::ok) return status;
        live_ = reinterpret_cast<LabelId*>(base + p.live);
        live_ring_ = p.live_count;
        flushed_ = reinterpret_cast<LabelId*>(base + p.flushed);
        flushed_count_ = 0;
        const std::int64_t period = model.string_period_us;
        min_action_chars_ = static_cast<std::uint32_t>((config.min_action_us + period - 1) / period);
        config_ = config;
        model_ = &model;
        reset();
        return Status::ok;
    }

    /// The settings given to the last successful init().
    const AnnotatorConfig& config() const noexcept { return config_; }

    /// Starts another stream: forgets the string, the windows, the label and the events.
    void reset() noexcept {
        clear_stream();
        events_.reset(min_action_chars_);
        flushed_count_ = 0;
    }

    /// Ends the stream: the characters not settled yet take the label the
    /// best explanation gives them now, an action still running ends, and the
    /// events this produces are in event(…) (a clip shorter than the settle
    /// delay still gets its label). The next frame starts a new stream.
    /// Returns the number of events.
    /// The labels of the characters it made final (those not reported
    /// settled before) are flushed_label(0 … flushed_characters() − 1).
    std::uint32_t flush() noexcept {
        events_.begin_frame();
        flushed_count_ = 0;
        if (model_ == nullptr) return 0;
        FrameResult finished;
        const std::int64_t origin_us = pushed_ > 0 ? encoder_.tick_time_us(0) : 0;
        const std::uint64_t unreported = first_unreported();
        work_on(all_work, finished, origin_us);
        finish_stream(origin_us, unreported);
        clear_stream();
        return static_cast<std::uint32_t>(events_.event_count());
    }

    /// With spread_work: finishes the work of the characters in progress now,
    /// rather than over the frames to come, and reports it as a frame would
    /// (characters_settled, events; status ok, no characters). Call it before
    /// reading provisional_label() at the end of a stream, or whenever the
    /// next frames will not come soon; flush() does it itself. Without
    /// spread_work, or with nothing in progress, it does nothing.
    FrameResult finish_work() noexcept {
        FrameResult result;
        if (model_ == nullptr) {
            result.status = Status::not_initialized;
            return result;
        }
        events_.begin_frame();
        flushed_count_ = 0;
        work_on(all_work, result, encoder_.tick_time_us(0));
        result.events = static_cast<std::uint32_t>(events_.event_count());
        return result;
    }

    /// Feeds one frame.
    /// @param time_us   the frame's capture time in microseconds (any origin,
    ///                  non-decreasing; equal times are treated as one instant)
    /// @param positions joint_count × 3 floats, xyz per joint in metres; read
    ///                  only during the call
    FrameResult push_frame(std::int64_t time_us, const float* positions) noexcept {
        FrameResult result;
        if (model_ == nullptr) {
            result.status = Status::not_initialized;
            return result;
        }
        events_.begin_frame();
        flushed_count_ = 0;
        // The old stream's clock, for events of its tail should this frame restart it.
        const std::int64_t origin_us = pushed_ > 0 ? encoder_.tick_time_us(0) : 0;
        // Spread, the frame is taken now and its characters computed later.
        const EncodedFrame encoded =
            config_.spread_work ? encoder_.accept_frame(time_us, positions) : encoder_.push_frame(time_us, positions);
        result.status = encoded.status;
        if (!encoded.accepted()) return result;
        if (encoded.status == Status::stream_restarted) {
            FrameResult old_stream;  // its settled characters are not this stream's: they are flushed
            const std::uint64_t unreported = first_unreported();
            work_on(all_work, old_stream, origin_us);  // the old stream's last characters count
            finish_stream(origin_us, unreported);      // the old stream ends: its tail settles, its action ends
            result.characters_flushed = flushed_count_;
            if (window_rule_) matcher_.reset();
            segmenter_.reset();
            has_window_ = false;
            has_last_time_ = false;  // the gap is no frame interval
            pushed_ = 0;
            fed_ = 0;
        }
        pushed_ += encoded.count();
        result.characters = encoded.count();
        if (!config_.spread_work) {
            feed(Fed{encoded.previous, encoded.from_previous, encoded.previous_feature, encoded.previous_pose,
                     encoded.previous_facing, encoded.previous_epoch},
                 result, encoder_.tick_time_us(0));
            feed(Fed{encoded.current, encoded.from_current, encoded.current_feature, encoded.current_pose,
                     encoded.current_facing, encoded.current_epoch},
                 result, encoder_.tick_time_us(0));
        } else {
            if (encoded.count() > 0) {
                // The characters before are computed and given to the
                // segmenter first (normally they are already), so the queue
                // has room for this frame's.
                while (encoder_.deferred_count() > 0) work_on_queue(all_work, result, encoder_.tick_time_us(0));
                encoder_.defer(encoded);
            }
            continue_work(time_us, result);
        }
        last_time_us_ = time_us;
        has_last_time_ = true;
        result.events = static_cast<std::uint32_t>(events_.event_count());
        return result;
    }

    /// Label of the latest completed window, or unknown_label (before the first
    /// window, after a restart, or when nothing is close enough).
    LabelId label() const noexcept { return has_window_ ? window_.classification.label : unknown_label; }
    float confidence() const noexcept { return has_window_ ? window_.classification.confidence : 0.0f; }
    /// Name of label(), or "unknown". Static storage owned by the model.
    const char* label_name() const noexcept {
        const LabelId id = label();
        return id == unknown_label || model_ == nullptr ? "unknown" : model_->label_names[id];
    }
    /// The latest completed window, or null before the first one.
    const WindowResult* last_window() const noexcept { return has_window_ ? &window_ : nullptr; }
    /// Its distance to each representative (representative_count floats, owned
    /// by the annotator, valid until the next push_frame()), or null.
    const float* last_window_distances() const noexcept {
        return has_window_ ? matcher_.completed_distances() : nullptr;
    }
    /// The segmenter's label for the newest character: no delay, but it may
    /// still change as the action goes on. unknown_label before the first character.
    LabelId live_label() const noexcept { return segmenter_.live_label(); }
    /// How far the live label leads every other label, "no action" included
    /// (units of W; ActionSegmenter::live_margin()): a confidence for it.
    float live_margin() const noexcept { return segmenter_.live_margin(); }
    /// Whether a character has settled since the stream (re)started.
    bool has_settled() const noexcept { return segmenter_.has_settled(); }
    /// Index of the last settled character, and its final label.
    std::uint64_t settled_character() const noexcept { return segmenter_.settled_character(); }
    LabelId settled_label() const noexcept { return segmenter_.settled_label(); }
    /// Final label of any of the last ActionSegmenter::settled_history()
    /// settled characters (a frame can settle several); unknown_label otherwise.
    LabelId settled_label(std::uint64_t character) const noexcept { return segmenter_.settled_label(character); }
    /// The current best explanation's label for a character not settled yet
    /// (the last settle_chars() + 1): what to report when a stream ends.
    LabelId provisional_label(std::uint64_t character) const noexcept {
        return segmenter_.provisional_label(character);
    }
    /// Action events of the last push_frame() or flush() (i < FrameResult::events).
    std::size_t event_count() const noexcept { return events_.event_count(); }
    const ActionEvent& event(std::size_t i) const noexcept { return events_.event(i); }
    /// Events dropped because one frame produced more than ActionEventTracker::max_events.
    std::uint32_t events_dropped() const noexcept { return events_.dropped(); }
    /// Whether an action event has started and not yet ended.
    bool in_action() const noexcept { return events_.in_action(); }

    /// The characters of the stream that ended with the last push_frame()
    /// (a restart, FrameResult::characters_flushed) or flush() whose labels
    /// became final then: the best explanation's labels of its unsettled
    /// tail, and before them those settled while finishing its work (with
    /// spread_work), which no FrameResult reported; the last
    /// settled_history() of these at most, which always holds the whole
    /// tail. Valid until the next push_frame(), finish_work(), flush() or
    /// reset(); 0 otherwise.
    std::uint32_t flushed_characters() const noexcept { return flushed_count_; }
    /// The ended stream's index of flushed character i (i < flushed_characters()).
    std::uint64_t flushed_character(std::size_t i) const noexcept { return flushed_first_ + i; }
    /// Final label of flushed character i, or unknown_label for i ≥ flushed_characters().
    LabelId flushed_label(std::size_t i) const noexcept { return i < flushed_count_ ? flushed_[i] : unknown_label; }
    /// Label time of flushed character i on the ended stream's clock (its
    /// tick less the label lead, as label_time_us()).
    std::int64_t flushed_label_time_us(std::size_t i) const noexcept {
        return model_ != nullptr ? label_time(flushed_origin_us_, flushed_first_ + i) : 0;
    }

    /// Characters between a character and its settled label.
    std::uint32_t settle_chars() const noexcept { return segmenter_.settle_chars(); }
    /// Time of a character's tick (any character of the current stream).
    std::int64_t character_time_us(std::uint64_t character) const noexcept { return encoder_.tick_time_us(character); }
    /// The stream time from which a character's label applies: its tick,
    /// less the label lead (AnnotatorConfig::label_lead_us). A frame at time
    /// t takes the label of the last character whose label time is at most
    /// t, which may be up to the lead after the frame; the events' start and
    /// end times are label times too.
    std::int64_t label_time_us(std::uint64_t character) const noexcept {
        return encoder_.tick_time_us(character) - config_.label_lead_us;
    }
    /// Characters in the current stream's string so far.
    std::uint64_t characters() const noexcept { return pushed_; }
    /// How many settled labels settled_label(character) remembers.
    std::size_t settled_history() const noexcept { return segmenter_.settled_history(); }
    /// The most recent character (meaningful once characters() > 0; with
    /// spread_work, the most recent one computed).
    Character last_character() const noexcept { return last_character_; }
    bool initialized() const noexcept { return model_ != nullptr; }

private:
    // A character for the segmenter: `count` ticks take it; what it was made
    // from (its feature, pose and facing turn; each may be null).
    struct Fed {
        Character character;
        std::uint32_t count;
        const float* feature;
        const float* pose;
        const float* facing;
        std::uint32_t epoch;  // its pose's stretch of unbroken motion (EncodedFrame::current_epoch)
    };

    // Gives a character to the segmenter (and the window rule), in a stream
    // whose character 0 ticked at origin_us. The segmenter's character before
    // is finished first (when spread, it usually is).
    void feed(const Fed& c, FrameResult& result, std::int64_t origin_us) noexcept {
        const Character character = c.character;
        for (std::uint32_t t = 0; t < c.count; ++t) {
            const std::uint64_t index = fed_++;
            last_character_ = character;
            report(segmenter_.finish(), result, origin_us);
            // Across a jump a step is no movement: the window of directions starts again.
            if (c.epoch != epoch_) segmenter_.restart_window();
            epoch_ = c.epoch;
            segmenter_.begin(character, c.feature, c.pose, c.facing);
            if (!config_.spread_work || t + 1 < c.count) report(segmenter_.finish(), result, origin_us);
            if (!window_rule_ || !matcher_.push(character)) continue;
            ++result.windows_completed;
            has_window_ = true;
            window_.first_character = matcher_.completed_window_start();
            window_.start_time_us = tick_time(origin_us, window_.first_character);
            window_.end_time_us = tick_time(origin_us, index);
            window_.classification = classify_distances(*model_, matcher_.completed_distances());
        }
    }

    static constexpr std::size_t all_work = ~static_cast<std::size_t>(0);

    // With spread_work: about `work` units (at least one step) of what is
    // open, oldest first: the segmenter's character in progress, then the
    // queued characters' encoding, each given to the segmenter once computed,
    // and its segmenter work. all_work finishes everything.
    void work_on(std::size_t work, FrameResult& result, std::int64_t origin_us) noexcept {
        std::size_t budget = work == 0 ? 1u : work;
        for (;;) {
            if (segmenter_.in_progress()) {
                const std::size_t before = segmenter_.work_left();
                report(segmenter_.advance(budget), result, origin_us);
                budget = spend(budget, before - segmenter_.work_left());
                if (segmenter_.in_progress() || budget == 0) return;
            }
            if (encoder_.deferred_count() == 0) return;
            budget = work_on_queue(budget, result, origin_us);
            if (budget == 0) return;
        }
    }

    // About `budget` units of the oldest queued character's encoding; once it
    // is computed, it goes to the segmenter. Returns the budget left.
    std::size_t work_on_queue(std::size_t budget, FrameResult& result, std::int64_t origin_us) noexcept {
        const std::size_t before = encoder_.deferred_work_left();
        const bool ready = encoder_.advance_deferred(budget);
        budget = spend(budget, before - encoder_.deferred_work_left());
        if (!ready) return 0;
        const DeferredCharacter* c = encoder_.ready_character();
        feed(Fed{c->character, c->count, c->feature, c->pose, c->facing, c->epoch}, result, origin_us);
        encoder_.pop_character();
        return budget;
    }

    static std::size_t spend(std::size_t budget, std::size_t units) noexcept {
        return budget == all_work ? all_work : units >= budget ? 0u : budget - units;
    }

    // With spread_work: this frame's share of the work open, what is left
    // divided by the frames left before the next tick (judged from the
    // interval since the last accepted frame; all of it when the tick is
    // due). A stream's first frame has no interval to judge by: it takes the
    // least step, and the next frame, which has one, goes on.
    void continue_work(std::int64_t time_us, FrameResult& result) noexcept {
        if (!segmenter_.in_progress() && encoder_.deferred_count() == 0) return;
        if (!has_last_time_) {
            work_on(1, result, encoder_.tick_time_us(0));
            return;
        }
        const std::int64_t next_tick = encoder_.tick_time_us(pushed_);  // the next tick to be taken
        const std::int64_t interval = time_us - last_time_us_;
        std::size_t frames_left = 1;
        if (interval > 0 && next_tick > time_us) {
            const std::int64_t ahead = (next_tick - time_us + interval - 1) / interval;
            frames_left = ahead > 1 ? static_cast<std::size_t>(ahead < 1000000 ? ahead : 1000000) : 1u;
        }
        // The queued characters' segmenter work is not begun yet, but it is known.
        const std::size_t left = segmenter_.work_left() + encoder_.deferred_work_left() +
                                 static_cast<std::size_t>(pushed_ - fed_) * segmenter_.work_per_character();
        const std::size_t share = left / frames_left + (left % frames_left != 0 ? 1u : 0u);
        work_on(share, result, encoder_.tick_time_us(0));
    }

    // A character the segmenter has just finished: its live label, and the
    // label it settled with its events (the stream's character 0 ticked at origin_us).
    void report(ActionSegmenter::Progress progress, FrameResult& result, std::int64_t origin_us) noexcept {
        if (progress != ActionSegmenter::Progress::done && progress != ActionSegmenter::Progress::settled) return;
        const std::uint64_t index = segmenter_.characters_pushed() - 1;
        live_[index % live_ring_] = segmenter_.live_label();
        if (progress != ActionSegmenter::Progress::settled) return;
        // One character, or with early settling (settle_stable_us) several in order.
        const std::uint32_t settled = segmenter_.just_settled();
        result.characters_settled += settled;
        const std::uint64_t last = segmenter_.settled_character();
        for (std::uint64_t c = last + 1u - settled; c <= last; ++c)
            settle_event(c, segmenter_.settled_label(c), origin_us);
    }

    // The first character of the stream whose settled label no FrameResult
    // has reported yet (every one settled before this call was).
    std::uint64_t first_unreported() const noexcept {
        return segmenter_.has_settled() ? segmenter_.settled_character() + 1 : 0;
    }

    // The unsettled tail of a stream (whose character 0 ticked at origin_us)
    // takes its provisional labels, and a running action ends. The labels
    // from character `unreported` on are kept as the flushed ones, the last
    // settled_history() of them at most: the whole unsettled tail (at most
    // settle_chars()), and before it what the segmenter still remembers of
    // those settled while the stream's work was finished.
    void finish_stream(std::int64_t origin_us, std::uint64_t unreported) noexcept {
        const std::uint64_t first = first_unreported();
        if (fed_ - unreported > live_ring_) unreported = fed_ - live_ring_;
        flushed_first_ = unreported;
        flushed_origin_us_ = origin_us;
        flushed_count_ = 0;
        for (std::uint64_t c = unreported; c < first; ++c) keep_flushed(segmenter_.settled_label(c));
        for (std::uint64_t c = first; c < fed_; ++c) {
            const LabelId label = segmenter_.provisional_label(c);
            keep_flushed(label);
            settle_event(c, label, origin_us);
        }
        events_.close();
    }
    // One more flushed label (the buffer holds settled_history() of them).
    void keep_flushed(LabelId label) noexcept {
        if (flushed_count_ < live_ring_) flushed_[flushed_count_++] = label;
    }

    // Character c's tick in a stream whose character 0 ticked at origin_us
    // (StringSampler::tick_time_us(), which a restart has already moved on).
    std::int64_t tick_time(std::int64_t origin_us, std::uint64_t c) const noexcept {
        return static_cast<std::int64_t>(static_cast<std::uint64_t>(origin_us) +
                                         c * static_cast<std::uint64_t>(model_->string_period_us));
    }
    // Character c's label time there: its tick, less the label lead.
    std::int64_t label_time(std::int64_t origin_us, std::uint64_t c) const noexcept {
        return tick_time(origin_us, c) - config_.label_lead_us;
    }
    // A final label to the events: whether the character's live label agreed,
    // and the span its label applies over (to the next character's label time).
    void settle_event(std::uint64_t c, LabelId label, std::int64_t origin_us) noexcept {
        events_.settle(c, label, live_[c % live_ring_] == label, label_time(origin_us, c),
                       label_time(origin_us, c + 1));
    }

    // Forgets the stream but not the events just produced.
    void clear_stream() noexcept {
        encoder_.reset();
        if (window_rule_) matcher_.reset();
        segmenter_.reset();
        has_window_ = false;
        has_last_time_ = false;
        window_ = WindowResult{};
        last_character_ = 0;
        pushed_ = 0;
        fed_ = 0;
    }

    static constexpr EncoderConfig encoder_config(const AnnotatorConfig& config) noexcept {
        return EncoderConfig{config.max_gap_us,
                             config.max_backward_us,
                             config.spread_work,
                             {config.up[0], config.up[1], config.up[2]},
                             config.max_pose_speed};
    }

    // One block: the encoder's, the window matcher's (with the window rule)
    // and the segmenter's storage, each aligned, a live label per character
    // the segmenter remembers (for the events' confidence), and as many
    // flushed labels (an ended stream's tail).
    struct Plan {
        std::size_t encoder = 0, encoder_bytes = 0, matcher = 0, matcher_bytes = 0, segmenter = 0, segmenter_bytes = 0,
                    live = 0, live_count = 0, flushed = 0, bytes = 0;
    };
    static constexpr Plan plan(const ModelView& model, const AnnotatorConfig& config) noexcept {
        Plan p;
        p.encoder_bytes = StringEncoder::required_bytes(model, encoder_config(config));
        p.matcher_bytes = config.window_rule ? WindowMatcher::required_bytes(model) : 0u;
        p.segmenter_bytes = ActionSegmenter::required_bytes(model, config.segmenter);
        detail::StorageLayout layout;
        p.encoder = layout.add<unsigned char>(p.encoder_bytes);
        p.matcher = layout.add<unsigned char>(p.matcher_bytes);
        p.segmenter = layout.add<unsigned char>(p.segmenter_bytes);
        p.live_count = ActionSegmenter::settled_history(model, config.segmenter);
        p.live = layout.add<LabelId>(p.live_count);
        p.flushed = layout.add<LabelId>(p.live_count);
        p.bytes = p.encoder_bytes == unsatisfiable_bytes || p.matcher_bytes == unsatisfiable_bytes ||
                          p.segmenter_bytes == unsatisfiable_bytes
                      ? unsatisfiable_bytes
                      : layout.bytes();
        return p;
    }

    const ModelView* model_ = nullptr;
    AnnotatorConfig config_;
    StringEncoder encoder_;
    WindowMatcher matcher_;
    ActionSegmenter segmenter_;
    bool window_rule_ = false;
    std::uint64_t pushed_ = 0;  // ticks taken in this stream
    std::uint64_t fed_ = 0;     // characters given to the segmenter (pushed_ less those queued)
    std::uint32_t epoch_ = 0;   // the epoch of the last character given to the segmenter
    ActionEventTracker events_;
    LabelId* live_ = nullptr;  // live label of each remembered character, by index mod live_ring_
    std::size_t live_ring_ = 1;
    LabelId* flushed_ = nullptr;  // the ended stream's flushed labels (live_ring_ of them at most)
    std::uint32_t flushed_count_ = 0;
    std::uint64_t flushed_first_ = 0;
    std::int64_t flushed_origin_us_ = 0;
    std::uint32_t min_action_chars_ = 1;
    bool has_window_ = false;
    WindowResult window_;
    Character last_character_ = 0;
    std::int64_t last_time_us_ = 0;  // the last accepted frame's time (spread_work's frame interval)
    bool has_last_time_ = false;
};

}  // namespace actionstring
