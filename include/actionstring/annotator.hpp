// actionstring — the per-frame annotator: every stage in order (design.md §2).
//
// push_frame(): StringEncoder (normalise → project → GMM posterior → tree
// descent, at the string rate) → two labelling rules fed the same characters:
//  * WindowMatcher (one DP line per open window and representative) → kNN
//    label whenever a window completes: the paper's rule, label();
//  * ActionSegmenter (the string explained as representatives end to end) →
//    a live label and, settle_delay later, a final label per character:
//    live_label(), settled_label(). This rule labels streams of actions far
//    better (models/README.md has the figures).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "actionstring/capacity.hpp"
#include "actionstring/classify.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/matcher.hpp"
#include "actionstring/model.hpp"
#include "actionstring/segmenter.hpp"
#include "actionstring/status.hpp"

namespace actionstring {
namespace detail {

/// Stands in for the WindowMatcher when the capacity has no windows: counts
/// characters and never completes a window.
class NoWindows {
public:
    Status init(const ModelView&) noexcept { return Status::ok; }
    void reset() noexcept { pushed_ = 0; }
    bool push(Character) noexcept {
        ++pushed_;
        return false;
    }
    const float* completed_distances() const noexcept { return nullptr; }
    std::uint64_t completed_window_start() const noexcept { return 0; }
    std::uint64_t characters_pushed() const noexcept { return pushed_; }

private:
    std::uint64_t pushed_ = 0;
};

}  // namespace detail

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
    /// Settings of the segmenter (settle delay, penalties, unknown cost).
    SegmenterConfig segmenter;
};

/// The default timing with the model's own online settings.
constexpr AnnotatorConfig annotator_config(const ModelView& model) noexcept {
    AnnotatorConfig c;
    c.segmenter = segmenter_config(model);
    return c;
}

/// What one push_frame() did.
struct FrameResult {
    /// ok or stream_restarted when the frame was accepted; otherwise the reason
    /// it was rejected (non_finite_input, tracking_lost, degenerate_pose,
    /// pose_out_of_range, time_went_backwards, not_initialized, invalid_argument).
    /// A rejected frame changes nothing: the string, windows and label hold.
    Status status = Status::ok;
    /// Characters this frame appended to the action string.
    std::uint32_t characters = 0;
    /// Windows that completed during this frame (the last one is last_window()).
    std::uint32_t windows_completed = 0;
    /// Characters whose label the segmenter settled during this frame (the
    /// last one is settled_character(); one per character once the stream is
    /// settle_chars() long).
    std::uint32_t characters_settled = 0;
};

/// One completed sliding window and the label it voted for.
struct WindowResult {
    std::uint64_t first_character = 0;  ///< Stream index of its first character.
    std::int64_t start_time_us = 0;     ///< Time of its first character's tick.
    std::int64_t end_time_us = 0;       ///< Time of its last character's tick.
    Classification classification;
};

/// The runtime recogniser. All storage is inside the object and fixed by `Cap`;
/// it never allocates. With `Cap::without_windows` the paper's window rule is
/// left out (label() stays unknown) and only the segmenter's state is paid for. Keeps a pointer to the ModelView given to init(): that
/// object and its tables must outlive the annotator (or the next init()).
template <class Cap>
class Annotator {
public:
    /// Binds a model with its own online settings (annotator_config()).
    Status init(const ModelView& model) noexcept { return init(model, annotator_config(model)); }

    /// Binds a model with the given settings. Returns invalid_model
    /// (inconsistent tables, or precision factors that could overflow float),
    /// model_exceeds_capacity, invalid_argument (config) or ok. Not usable
    /// until it returns ok.
    Status init(const ModelView& model, const AnnotatorConfig& config) noexcept {
        model_ = nullptr;
        Status status = matcher_.init(model);
        if (status == Status::ok) status = segmenter_.init(model, config.segmenter);
        if (status == Status::ok) status = encoder_.init(model, config.max_gap_us, config.max_backward_us);
        if (status != Status::ok) return status;
        model_ = &model;
        reset();
        return Status::ok;
    }

    /// Starts another stream: forgets the string, the windows and the label.
    void reset() noexcept {
        encoder_.reset();
        matcher_.reset();
        segmenter_.reset();
        has_window_ = false;
        window_ = WindowResult{};
        last_character_ = 0;
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
        const EncodedFrame encoded = encoder_.push_frame(time_us, positions);
        result.status = encoded.status;
        if (!encoded.accepted()) return result;
        if (encoded.status == Status::stream_restarted) {
            matcher_.reset();
            segmenter_.reset();
            has_window_ = false;
        }
        emit(encoded.previous, encoded.from_previous, result);
        emit(encoded.current, encoded.from_current, result);
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
    /// Characters between a character and its settled label.
    std::uint32_t settle_chars() const noexcept { return segmenter_.settle_chars(); }
    /// Time of a character's tick (any character of the current stream).
    std::int64_t character_time_us(std::uint64_t character) const noexcept { return encoder_.tick_time_us(character); }
    /// Characters in the current stream's string so far.
    std::uint64_t characters() const noexcept { return matcher_.characters_pushed(); }
    /// The most recent character (meaningful once characters() > 0).
    Character last_character() const noexcept { return last_character_; }
    bool initialized() const noexcept { return model_ != nullptr; }

private:
    void emit(Character character, std::uint32_t count, FrameResult& result) noexcept {
        for (std::uint32_t t = 0; t < count; ++t) {
            const std::uint64_t index = matcher_.characters_pushed();
            last_character_ = character;
            ++result.characters;
            if (segmenter_.push(character)) ++result.characters_settled;
            if (!matcher_.push(character)) continue;
            ++result.windows_completed;
            has_window_ = true;
            window_.first_character = matcher_.completed_window_start();
            window_.start_time_us = encoder_.tick_time_us(window_.first_character);
            window_.end_time_us = encoder_.tick_time_us(index);
            window_.classification =
                classify_distances<Cap::max_representatives>(*model_, matcher_.completed_distances());
        }
    }

    const ModelView* model_ = nullptr;
    StringEncoder<Cap> encoder_;
    std::conditional_t<Cap::has_windows, WindowMatcher<Cap>, detail::NoWindows> matcher_;
    ActionSegmenter<Cap> segmenter_;
    bool has_window_ = false;
    WindowResult window_;
    Character last_character_ = 0;
};

}  // namespace actionstring
