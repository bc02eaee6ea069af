// actionstring — online segmentation of the character stream (design.md §1.8).
//
// The paper labels a stream by its most recent sliding window. Windows of a
// fixed length straddle the boundaries of actions shorter than a window, and
// the label changes only when a window completes. This stage instead explains
// the whole string so far as a sequence of representatives laid end to end
// (one-pass connected DTW, as in connected-word recognition):
//
//   C_r[i](t) = W(rep_r[i], c_t) + min( C_r[i−1](t−1)            advance
//                                      C_r[i](t−1) + stay          repeat a character
//                                      C_r[i−2](t−1) + skip )      skip a character
//   C_r[1](t) may also open the next segment from E(t−1) + segment_penalty, where
//   E(t) = min_r C_r[n_r](t) is the best explanation ending exactly at t
//   (or E(t−1) + unknown_cost, a character of "no action").
//
// Every stream character adds exactly one W term, so explanations of the same
// string compare fairly whatever their segment lengths. Each cell also carries
// the index where its segment started, and a short ring of segment ends lets
// the best current hypothesis be traced back: the label of the character
// `settle_chars` back is final and is emitted; the newest one is the live guess.
// With `settle_stable_us`, a character also becomes final sooner, once every
// best explanation for that long has given it the same label: a clear action
// settles early, an ambiguous one still waits the whole delay.
// State: two words per representative character, the ring, and K floats; work per
// character: one pass over the representative characters.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/detail/lanes.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/exemplars.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"

namespace actionstring {

/// Settings of the online segmentation (units: entries of W, the model's
/// character distances). The defaults were chosen by cross-validation over the
/// HDM05 training actors (models/README.md), never on a test list.
struct SegmenterConfig {
    /// How long after a character its label becomes final. Longer sees more
    /// of the action before deciding; the paper's rule answers one window late.
    /// At most max_settle_delay_us; the state's storage grows with it.
    std::int64_t settle_delay_us = 2000000;
    /// A character's label also becomes final sooner, once the best
    /// explanation has given it the same label, unchanged, for this long (and
    /// all characters before it are final): where the stream has made its
    /// action clear the label and the events come early, and where it has not
    /// they still wait settle_delay_us. 0 (or at least settle_delay_us): the
    /// delay alone. At most max_settle_delay_us; it needs two more rings as
    /// long as the delay's. On the training subjects' folds, 1 s instead of the
    /// delay alone (2 s) cut HDM05's mean detection latency from 2.56 to 1.79 s
    /// at the same events' segment F1 within 0.01 (models/README.md).
    std::int64_t settle_stable_us = 0;
    /// Cost of starting another segment (discourages flicker).
    float segment_penalty = 3.0f;
    /// Extra cost of matching two stream characters to one representative character.
    float stay_penalty = 0.3f;
    /// Extra cost of skipping a representative character.
    float skip_penalty = 0.3f;
    /// Cost per character of "no action" (labelled unknown); infinity turns it off.
    float unknown_cost = detail::infinity();
    /// Weight of the characters' label votes (design.md §1.8) in the
    /// explanation: each stream character also costs a label's
    /// representatives vote_weight × (best log P(c | l) − their label's), so
    /// an explanation pays for key-poses its action rarely shows. 0 = off;
    /// without votes in the model it has no effect.
    float vote_weight = 0.0f;
    /// Weight of the exemplars (exemplars.hpp) in the explanation: each stream
    /// character also costs a label's representatives exemplar_weight × (its
    /// feature's squared distance to the label's nearest exemplar − the
    /// nearest label's) / exemplar_scale, so an explanation pays for poses its
    /// action's training poses lie far from. With centres of "no action" in
    /// the model (ModelView::has_no_action_exemplars()), "no action" pays the
    /// same way and "nearest" includes it. 0 = off; it needs push() given
    /// the character's feature, and exemplars in the model.
    float exemplar_weight = 0.0f;
    /// Weight of the motion directions of the stream's last characters
    /// (descriptor.hpp, window_direction_penalties()) in the explanation: each
    /// stream character also costs a label's representatives
    /// direction_weight × (the best label's window score − their label's), so
    /// an explanation pays for a motion its action's training windows did not
    /// make; "no action" pays nothing here. 0 = off; it needs push() given
    /// the character's pose and facing, and window directions in the model.
    float direction_weight = 0.0f;
};

/// The online settings a model carries (chosen at training); a device uses
/// them unless told otherwise.
constexpr SegmenterConfig segmenter_config(const ModelView& m) noexcept {
    SegmenterConfig c;
    c.settle_delay_us = m.settle_delay_us;
    c.settle_stable_us = m.settle_stable_us;
    c.segment_penalty = m.segment_penalty;
    c.stay_penalty = m.stay_penalty;
    c.skip_penalty = m.skip_penalty;
    c.unknown_cost = m.unknown_cost;
    c.vote_weight = m.segment_vote_weight;
    c.exemplar_weight = m.segment_exemplar_weight;
    c.direction_weight = m.segment_direction_weight;
    return c;
}

/// Online segmentation state. Works in caller-owned storage of
/// required_bytes(model, config) bytes (storage.hpp): two words per
/// representative character and two rings as long as the settle delay (four
/// with settle_stable_us).
/// Keeps pointers to the ModelView passed to init() and to the storage: both
/// must outlive the segmenter (or its next init()).
class ActionSegmenter {
public:
    /// Bytes of storage init() needs for this model and these settings
    /// (constexpr when both are); unsatisfiable_bytes for settings check() refuses.
    static constexpr std::size_t required_bytes(const ModelView& model, const SegmenterConfig& config) noexcept {
        return plan(model, config).bytes;
    }

    /// Binds a model (W, representatives, labels, string period). Returns
    /// invalid_model, invalid_argument (a negative, NaN or too long setting),
    /// storage_too_small, or ok.
    Status init(const ModelView& model, const SegmenterConfig& config, void* storage, std::size_t bytes) noexcept {
        model_ = nullptr;
        const Status status = check(model, config);
        if (status != Status::ok) return status;
        const Plan p = plan(model, config);
        if (!detail::storage_fits(storage, bytes, p.bytes)) return Status::storage_too_small;
        detail::clear_storage(storage, p.bytes);
        settle_chars_ = settle_chars_for(model, config);
        ring_size_ = p.ring_size;
        cells_ = cells_in(storage, p);
        ends_ = detail::storage_at<SegmentEnd>(storage, p.ends);
        settled_ = detail::storage_at<LabelId>(storage, p.settled);
        stable_chars_ = p.stable_bytes == 0 ? 0u : stable_chars_for(model, config);
        candidates_ = p.stable_bytes == 0 ? nullptr : detail::storage_at<LabelId>(storage, p.candidates);
        agreed_since_ = p.stable_bytes == 0 ? nullptr : detail::storage_at<std::uint32_t>(storage, p.agreed_since);
        vote_costs_ = p.votes_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.votes);
        exemplar_distances_ = p.exemplars_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.exemplars);
        feature_ = p.exemplars_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.feature);
        window_ = p.window_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.window);
        histogram_ = p.window_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.histogram);
        window_costs_ = p.window_bytes == 0 ? nullptr : detail::storage_at<float>(storage, p.window_costs);
        use_votes_ = uses_votes(model, config);
        config_ = config;
        model_ = &model;
        column_ = detail::storage_at<float>(storage, p.column);
        w_symmetric_ = model.character_distances_symmetric();
        reset();
        return Status::ok;
    }

    /// What init() would return for this model and these settings given
    /// enough storage, with no state touched (a caller can check settings
    /// before applying them).
    static Status check(const ModelView& model, const SegmenterConfig& config) noexcept {
        const Status status = validate_matching_tables(model);
        if (status != Status::ok) return status;
        if (!(config.settle_delay_us >= 0) || !(config.settle_stable_us >= 0) || !(config.segment_penalty >= 0.0f) ||
            !(config.stay_penalty >= 0.0f) || !(config.skip_penalty >= 0.0f) || !(config.unknown_cost >= 0.0f) ||
            !detail::is_finite(config.segment_penalty) || !detail::is_finite(config.stay_penalty) ||
            !detail::is_finite(config.skip_penalty) || !detail::is_weight(config.vote_weight) ||
            !detail::is_weight(config.exemplar_weight) || !detail::is_weight(config.direction_weight))
            return Status::invalid_argument;
        if (model.representative_count >= unknown_rep) return Status::model_exceeds_capacity;
        if (model.string_period_us == 0) return Status::invalid_model;
        if (config.settle_delay_us > max_settle_delay_us || config.settle_stable_us > max_settle_delay_us)
            return Status::invalid_argument;
        return Status::ok;
    }

    /// Forgets the stream; the model stays bound.
    void reset() noexcept {
        pushed_ = 0;
        settled_count_ = 0;
        just_settled_ = 0;
        last_end_ = 0.0f;
        margin_ = 0.0f;
        best_ = Hypothesis{};
        update_ = Update{};
        window_count_ = 0;
        const std::size_t cells = model_->total_representative_chars();
        for (std::size_t i = 0; i < cells; ++i) {
            cells_.cost(i) = detail::infinity();
            cells_.start(i) = 0u;
        }
        for (std::size_t i = 0; i < ring_size_; ++i) {
            ends_[i] = SegmentEnd{};
            settled_[i] = unknown_label;
        }
        if (stable_chars_ != 0)
            for (std::size_t i = 0; i < ring_size_; ++i) {
                candidates_[i] = unknown_label;
                agreed_since_[i] = 0u;
            }
    }

    bool initialized() const noexcept { return model_ != nullptr; }

    /// Feeds the next character and updates every representative at once.
    /// Returns true when it settled characters (the one settle_chars() back;
    /// with settle_stable_us none, or several: just_settled()): the last one's
    /// label is then in settled_label(). The same as begin() then finish().
    /// @param feature null, or the feature the character was made from
    ///                (feature_dim floats, EncodedFrame's previous_feature /
    ///                current_feature; read only during the call), for the
    ///                exemplars' costs when the settings weigh them
    /// @param pose    null, or the normalised pose it was projected from (its
    ///                first pose_dim() floats are read: EncodedFrame's
    ///                previous_pose / current_pose) and
    /// @param facing  the facing turn taken out of it ({cos, sin}), for the
    ///                window's directions when the settings weigh them; read
    ///                only during the call
    bool push(Character character, const float* feature = nullptr, const float* pose = nullptr,
              const float* facing = nullptr) noexcept {
        if (!begin(character, feature, pose, facing)) return false;
        return finish() == Progress::settled;
    }

    /// What the window's directions added to each label's cost for the
    /// newest character begun (label_count floats, owned by the segmenter,
    /// valid until the next begin()), all 0 when it came without a pose or
    /// the window held one pose; null when the settings do not weigh them.
    const float* window_costs() const noexcept { return window_costs_; }

    /// Empties the window of directions (the next character starts it
    /// again), as at a stream's start: across a jump in the pose a step is no
    /// movement (the annotator calls it where the encoder's epoch changes).
    void restart_window() noexcept { window_count_ = 0; }

    /// How far a character begun with begin() has come.
    enum class Progress : std::uint8_t {
        idle,     ///< no character in progress
        working,  ///< some of its work is left: call advance() again
        done,     ///< it is in: the live label is its, nothing settled
        settled,  ///< it is in and settled just_settled() characters, the last settled_character()
    };

    /// Starts the next character without updating anything yet: the work is
    /// then done by advance() in slices, so a device can spread it over the
    /// frames until the next character (AnnotatorConfig::spread_work). Until
    /// the character is done every query answers as before it (live_label(),
    /// characters_pushed(), …); the result is bit for bit push()'s. A character
    /// still in progress is finished first, and what it settled is then in
    /// settled_label() without being reported: finish() it before, to know.
    /// The feature is copied; the window's directions are scored here, at
    /// once (the pose and facing join the window). Returns false (nothing
    /// begun) when not initialised or the character is not the model's.
    bool begin(Character character, const float* feature = nullptr, const float* pose = nullptr,
               const float* facing = nullptr) noexcept {
        if (model_ == nullptr || character >= model_->character_count) return false;
        if (update_.active) finish();
        const ModelView& m = *model_;
        Update& u = update_;
        u = Update{};
        u.active = true;
        u.now = static_cast<std::uint32_t>(pushed_);
        // W(·, character) as one contiguous array, so each cell reads it from
        // the cache: W's own row when W is symmetric (every trained model's), else a copy.
        const std::size_t K = m.character_count;
        u.column = m.character_distances + std::size_t{character} * K;
        if (!w_symmetric_) {
            for (std::size_t a = 0; a < K; ++a) column_[a] = m.character_distances[a * K + character];
            u.column = column_;
        }
        // What this character costs each label's explanations, and "no action"
        // when the model learned its votes (0 without votes).
        if (use_votes_) {
            const bool no_action = m.has_no_action_votes != 0;
            float best_vote = no_action ? m.no_action_votes[character] : -detail::infinity();
            for (std::size_t l = 0; l < m.label_count; ++l)
                if (m.character_votes[l * K + character] > best_vote) best_vote = m.character_votes[l * K + character];
            for (std::size_t l = 0; l < m.label_count; ++l)
                vote_costs_[l] = config_.vote_weight * (best_vote - m.character_votes[l * K + character]);
            if (no_action) u.no_action_vote = config_.vote_weight * (best_vote - m.no_action_votes[character]);
        } else if (vote_costs_ != nullptr) {
            for (std::size_t l = 0; l < m.label_count; ++l) vote_costs_[l] = 0.0f;
        }
        // And what the window's motion costs them (its directions), now.
        if (window_ != nullptr) {
            if (pose != nullptr && facing != nullptr) {
                fold_window(pose, facing);
            } else {
                for (std::size_t l = 0; l < m.label_count; ++l) window_costs_[l] = 0.0f;
            }
        }
        // And what its pose costs them (the exemplars' distances), once
        // advance() has measured them: the feature is kept until then.
        u.exemplars = exemplar_distances_ != nullptr && feature != nullptr;
        if (u.exemplars) {
            for (std::size_t j = 0; j < m.feature_dim; ++j) feature_[j] = feature[j];
            for (std::size_t l = 0; l < m.label_count; ++l) exemplar_distances_[l] = detail::infinity();
            u.none = detail::infinity();
        }
        // Costs are stored relative to the previous step's best so they stay small on endless streams.
        u.shift = best_.cost;
        u.previous_end = pushed_ == 0 ? 0.0f : last_end_ - u.shift;
        u.entry = u.previous_end + config_.segment_penalty;
        return true;
    }

    /// The work left of the character in progress (0 when idle), in units of
    /// about one representative character's update: what advance() takes.
    std::size_t work_left() const noexcept {
        if (!update_.active) return 0;
        const ModelView& m = *model_;
        std::size_t work = (m.representative_count - update_.next_rep) * rep_overhead +
                           (m.total_representative_chars() - cells_before(update_.next_rep));
        if (update_.exemplars) work += (m.exemplar_count - update_.next_centre) * centre_work(m);
        return work;
    }

    /// The work of one character from begin() (given a feature) to done:
    /// work_left() just after begin(). The same for every character.
    std::size_t work_per_character() const noexcept {
        if (model_ == nullptr) return 0;
        const ModelView& m = *model_;
        std::size_t work = m.representative_count * rep_overhead + m.total_representative_chars();
        if (exemplar_distances_ != nullptr) work += m.exemplar_count * centre_work(m);
        return work;
    }

    /// Does about `work` units (work_left()) of the character in progress, and
    /// at least one representative's or four exemplars' worth, so every call
    /// moves on. Returns idle, working, or (when it finished the character)
    /// done or settled, as finish().
    Progress advance(std::size_t work) noexcept {
        if (!update_.active) return Progress::idle;
        const ModelView& m = *model_;
        Update& u = update_;
        std::size_t budget = work == 0 ? 1 : work;
        if (u.exemplars) {
            // The exemplars first: every representative's cost reads them.
            const std::size_t per = centre_work(m);
            std::size_t take = budget / per + (budget % per != 0 ? 1u : 0u);
            take = take > m.exemplar_count ? m.exemplar_count : (take + 3) & ~static_cast<std::size_t>(3);
            const std::size_t last =
                m.exemplar_count - u.next_centre < take ? m.exemplar_count : u.next_centre + take;
            nearest_exemplars(m, feature_, u.next_centre, last, exemplar_distances_, &u.none);
            const std::size_t spent = (last - u.next_centre) * per;
            u.next_centre = last;
            if (u.next_centre < m.exemplar_count) return Progress::working;
            fold_exemplars();
            u.exemplars = false;
            if (spent >= budget) return Progress::working;
            budget -= spent;
        }
        if (!u.candidates) {
            // "No action" for this one character is the first candidate for both.
            u.end = SegmentEnd{unknown_rep, u.now};
            u.end_cost = u.previous_end + (config_.unknown_cost + u.no_action_vote);
            u.best = Hypothesis{u.end_cost, unknown_rep, u.now};
            u.runner_up = detail::infinity();
            u.candidates = true;
        }
        // The representatives from next_rep on, until the budget is spent
        // (all of them for finish(), without counting).
        std::size_t last = budget == all_work ? std::size_t{m.representative_count} : u.next_rep;
        std::size_t spent = 0;
        while (last < m.representative_count && spent < budget)
            spent += m.representative_length(last++) + rep_overhead;
        update_representatives(u.next_rep, last);
        u.next_rep = last;
        if (last < m.representative_count) return Progress::working;
        return complete();
    }

    /// Finishes the character in progress (all its work left); idle when none.
    Progress finish() noexcept { return advance(all_work); }

    /// Whether a character is begun and not yet done.
    bool in_progress() const noexcept { return update_.active; }

    /// Label of the best explanation's newest character (no delay, may change).
    LabelId live_label() const noexcept { return pushed_ == 0 ? unknown_label : label_of(best_.rep); }
    /// How much better the live label's best explanation is than the best one
    /// whose newest character has any other label ("no action" included), in
    /// units of W: a confidence for the live label. 0 before the first
    /// character or on a tie; infinity when no other label can explain the
    /// stream (a model of one label with "no action" turned off).
    float live_margin() const noexcept { return margin_; }
    /// Whether any character is settled yet.
    bool has_settled() const noexcept { return settled_count_ > 0; }
    /// Index of the last settled character (meaningful when has_settled()).
    /// Characters settle in order; each one settle_chars() after it at the
    /// latest, and with settle_stable_us possibly sooner.
    std::uint64_t settled_character() const noexcept { return settled_count_ - 1; }
    /// How many characters the last character done settled (the last of them
    /// settled_character()): 1 once the stream is settle_chars() long, and with
    /// settle_stable_us 0 to settle_chars() + 1.
    std::uint32_t just_settled() const noexcept { return just_settled_; }
    /// Final label of the last settled character.
    LabelId settled_label() const noexcept { return settled_label(settled_character()); }
    /// Final label of a settled character among the last settled_history();
    /// unknown_label for any other index.
    LabelId settled_label(std::uint64_t index) const noexcept {
        if (!has_settled() || index > settled_character() || settled_character() - index >= ring_size_)
            return unknown_label;
        return settled_[slot(index)];
    }
    /// How many settled labels settled_label(index) remembers.
    std::size_t settled_history() const noexcept { return ring_size_; }
    /// settled_history() for a model and settings, before init() (0 for settings check() refuses).
    static constexpr std::size_t settled_history(const ModelView& model, const SegmenterConfig& config) noexcept {
        return plan(model, config).ring_size;
    }
    /// What the current best explanation says of a character that is not yet
    /// settled (index within the last settle_chars() + 1): to flush the end of
    /// a stream. Returns unknown_label for other indices.
    LabelId provisional_label(std::uint64_t index) const noexcept {
        if (pushed_ == 0 || index >= pushed_ || pushed_ - 1 - index > settle_chars_) return unknown_label;
        return label_at(index);
    }
    std::uint32_t settle_chars() const noexcept { return settle_chars_; }
    /// settle_stable_us in characters (0: the delay alone).
    std::uint32_t stable_chars() const noexcept { return stable_chars_; }
    std::uint64_t characters_pushed() const noexcept { return pushed_; }

private:
    // Units of work_left(): a representative costs its characters and this
    // much more (its setup and its best cell); an exemplar centre about a
    // quarter of its coordinates (four lanes take four at a time).
    static constexpr std::size_t rep_overhead = 4;
    static constexpr std::size_t all_work = ~static_cast<std::size_t>(0);
    static constexpr std::size_t centre_work(const ModelView& m) noexcept { return (m.exemplar_dims() + 3u) / 4u; }

    // Cells of the representatives before r.
    std::size_t cells_before(std::size_t r) const noexcept {
        return r < model_->representative_count ? model_->representative_offsets[r]
                                                 : model_->total_representative_chars();
    }

    // The exemplars' part of each label's cost, relative to the nearest
    // label's, or to "no action"'s when the model has centres of it (learned
    // from unlabelled stretches), which then pays the same way; without them
    // "no action" pays nothing here.
    void fold_exemplars() noexcept {
        const ModelView& m = *model_;
        Update& u = update_;
        float nearest = u.none;
        for (std::size_t l = 0; l < m.label_count; ++l)
            if (exemplar_distances_[l] < nearest) nearest = exemplar_distances_[l];
        const float scale = config_.exemplar_weight / m.exemplar_scale;
        if (detail::is_finite(nearest)) {
            for (std::size_t l = 0; l < m.label_count; ++l) vote_costs_[l] += (exemplar_distances_[l] - nearest) * scale;
            if (detail::is_finite(u.none)) u.no_action_vote += (u.none - nearest) * scale;
        }
    }

    // The character's pose joins the window (the oldest leaves a full one),
    // and the window's directions add their part of each label's cost.
    void fold_window(const float* pose, const float* facing) noexcept {
        const ModelView& m = *model_;
        const std::size_t width = m.direction_record_floats(), D = m.pose_dim(), N = m.window_direction_chars;
        if (window_count_ == N) {
            for (std::size_t i = 0; i + width < N * width; ++i) window_[i] = window_[i + width];
            --window_count_;
        }
        float* record = window_ + window_count_ * width;
        for (std::size_t i = 0; i < D; ++i) record[i] = pose[i];
        record[D] = facing[0];
        record[D + 1] = facing[1];
        ++window_count_;
        window_direction_penalties(m, window_, window_count_, config_.direction_weight, histogram_, window_costs_);
        for (std::size_t l = 0; l < m.label_count; ++l) vote_costs_[l] += window_costs_[l];
    }

    // The character's update is in: the ring, the best explanation, the settled label.
    Progress complete() noexcept {
        Update& u = update_;
        ends_[slot(u.now)] = u.end;
        last_end_ = u.end_cost;
        best_ = u.best;
        margin_ = u.runner_up - u.best.cost;
        u.active = false;
        ++pushed_;
        just_settled_ = 0;
        if (stable_chars_ == 0) {
            if (pushed_ <= settle_chars_) return Progress::done;
            const std::uint64_t settled = pushed_ - 1 - settle_chars_;
            settled_[slot(settled)] = label_at(settled);
            settled_count_ = settled + 1;
            just_settled_ = 1;
            return Progress::settled;
        }
        // Early settling: the oldest unsettled characters settle while each is
        // settle_chars_ old or has kept its label for stable_chars_ characters.
        track_agreement();
        while (settled_count_ < pushed_) {
            const std::uint64_t i = settled_count_;
            const bool due = pushed_ - 1 - i >= settle_chars_;
            const bool agreed = static_cast<std::uint32_t>(pushed_) - agreed_since_[slot(i)] >= stable_chars_;
            if (!due && !agreed) break;
            settled_[slot(i)] = candidates_[slot(i)];
            ++settled_count_;
            ++just_settled_;
        }
        return just_settled_ > 0 ? Progress::settled : Progress::done;
    }

    // Traces the best explanation back over the unsettled characters (newest
    // first, a segment at a time) and notes, for each, the label it gives and
    // since when (pushed_ then) it has given that label. A few instructions a
    // character: one compare, and a store only where the label changed.
    void track_agreement() noexcept {
        const std::uint32_t newest = static_cast<std::uint32_t>(pushed_ - 1);
        const std::uint32_t now = static_cast<std::uint32_t>(pushed_);
        const std::uint32_t mask = static_cast<std::uint32_t>(ring_size_ - 1u);
        const std::uint32_t unsettled = static_cast<std::uint32_t>(pushed_ - settled_count_);  // at most the ring
        std::uint16_t rep = best_.rep;
        std::uint32_t start = best_.start;
        // The newest character's slot held an older one: it starts afresh.
        candidates_[newest & mask] = label_of(rep);
        agreed_since_[newest & mask] = now;
        std::uint32_t age = 1;  // the next character to note, by its age (0: the newest)
        // Each segment holds at least one character, so the ring bounds the walk.
        for (std::size_t segments = 0; age < unsettled && segments <= ring_size_; ++segments) {
            const std::uint32_t start_age = newest - start;  // the segment's oldest character
            const std::uint32_t stop = start_age < unsettled - 1u ? start_age + 1u : unsettled;
            const LabelId label = label_of(rep);
            for (; age < stop; ++age) {
                const std::uint32_t s = (newest - age) & mask;
                if (candidates_[s] != label) {
                    candidates_[s] = label;
                    agreed_since_[s] = now;
                }
            }
            const SegmentEnd& before = ends_[slot(start - 1u)];  // the segment before
            rep = before.rep;
            start = before.start;
        }
    }

    // Representatives [first, end_rep) of the character in progress: each one's
    // cells, and the candidates for the best explanation and the best one
    // ending here, taken in representative order whatever the slices.
    void update_representatives(std::size_t first, std::size_t end_rep) noexcept {
        const ModelView& m = *model_;
        Update& u = update_;
        const float* const column = u.column;
        const float shift = u.shift, entry = u.entry;
        const std::uint32_t now = u.now;
        // The candidates stay in update_ (read and written once per
        // representative): locals would be live across the cell loop and
        // take the registers a Cortex-M4 needs there.
        Hypothesis& best = u.best;
        float& runner_up = u.runner_up;
        SegmentEnd& end = u.end;
        float& end_cost = u.end_cost;
        for (std::size_t r = first; r < end_rep; ++r) {
            const Character* rep = m.representative_chars + m.representative_offsets[r];
            const std::size_t n = m.representative_length(r);
            const Cells cells = cells_ + m.representative_offsets[r];  // cell i is cells.cost(i − 1), cells.start(i − 1)
            // This representative's best cell (the first strict minimum, so
            // best below is the same cell a single pass over all cells finds).
            float rep_best = detail::infinity();
            std::uint32_t rep_from = now;
            const float vote = vote_costs_ == nullptr ? 0.0f : vote_costs_[m.representative_labels[r]];
            const float stay_penalty = config_.stay_penalty, skip_penalty = config_.skip_penalty;
            // Each choice is one comparison selecting both the cost and its start,
            // written so compilers emit selects, not jumps: the comparisons
            // depend on the data and would be mispredicted half the time.
            auto choose = [](float& value, std::uint32_t& from, float other,
                             std::uint32_t other_from) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
                const bool take = other < value;
                value = take ? other : value;
                from = take ? other_from : from;
            };
            auto finish_cell = [&](Cells cell, Character c, float value, std::uint32_t from) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
                value += column[c] + vote;
                cell.cost(0) = value;
                cell.start(0) = from;
                choose(rep_best, rep_from, value, from);
            };
            // Descending, so cells i−1 and i−2 still hold the previous step.
            // `top` is the highest cell (0-based) the scalar loop below still has to do.
            std::size_t top = n - 1;
            // With lanes, a representative of four or more cells is done in
            // blocks: its lowest four cells (`bottom`, whose moves into the
            // segment are lanes of their own) from the previous step first, as
            // the blocks above may overwrite cells 2 and 3; then blocks from the
            // top (eight with AVX2, then four) while a block's cells are all
            // ordinary (0-based index ≥ 2, so cells i−1 and i−2 exist); then at
            // most one ordinary cell in the scalar loop; then bottom is stored.
            // Only the blocks' best cost is kept; the cell it came from
            // (rep_from) is found afterwards, and only for a representative
            // that becomes the best.
            bool blocks = false;
#if ACTIONSTRING_DETAIL_LANES == 4
            BottomCells bottom{};
            if (n >= 4) {
                bottom = bottom_cells(cells, rep, column, shift, stay_penalty, skip_penalty, vote, entry, now);
#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
                rep_best = cell_blocks<8>(cells, rep, column, top, shift, stay_penalty, skip_penalty, vote, rep_best);
#endif
                rep_best = cell_blocks<4>(cells, rep, column, top, shift, stay_penalty, skip_penalty, vote, rep_best);
                blocks = true;
            }
#endif
            // The cells the blocks left (all of them without SIMD), walking
            // pointers: the previous step's cells i, i−1 (shifted) ride down
            // the loop in registers, so each cell loads one old value and the
            // loop's state fits a Cortex-M4's registers; cells 2 and 1, whose
            // moves start a segment, follow the loop. After blocks, the loop
            // stops above bottom's four cells.
            const std::size_t lowest_ordinary = blocks ? 4 : 2;
            float here = cells.cost(top) - shift;  // old cell i
            std::uint32_t here_from = cells.start(top);
            float below = top >= 1 ? cells.cost(top - 1) - shift : 0.0f;  // old cell i − 1
            std::uint32_t below_from = top >= 1 ? cells.start(top - 1) : 0u;
            if (top >= lowest_ordinary) {
                const Character* c = rep + top;
                const Character* const last = rep + (lowest_ordinary - 1);
                for (Cells cell = cells + top; c != last; cell.down(), --c) {
                    const Cells two_below = cell - 2;
                    const float further = two_below.cost(0) - shift;  // old cell i − 2
                    const std::uint32_t further_from = two_below.start(0);
                    float value = below;
                    std::uint32_t from = below_from;
                    choose(value, from, here + stay_penalty, here_from);
                    choose(value, from, further + skip_penalty, further_from);
                    finish_cell(cell, *c, value, from);
                    here = below, here_from = below_from;
                    below = further, below_from = further_from;
                }
            }
            if (!blocks) {
                if (n >= 2) {  // cell 2: advance from cell 1, stay, or skip in from the segment's entry
                    float value = below;
                    std::uint32_t from = below_from;
                    choose(value, from, here + stay_penalty, here_from);
                    choose(value, from, entry + skip_penalty, now);
                    finish_cell(cells + 1, rep[1], value, from);
                    here = below, here_from = below_from;
                }
                {  // cell 1: enter the segment, or stay
                    float value = entry;
                    std::uint32_t from = now;
                    choose(value, from, here + stay_penalty, here_from);
                    finish_cell(cells, rep[0], value, from);
                }
            }
#if ACTIONSTRING_DETAIL_LANES == 4
            if (blocks) {
                detail::store_lanes(cells.costs, bottom.cost);
                detail::store_lanes(cells.starts, bottom.start);
                const float bottom_best = detail::smallest_lane(bottom.cost);
                rep_best = bottom_best < rep_best ? bottom_best : rep_best;
                // The blocks' best is in rep_best, but the cell it came from was not
                // tracked: the first strict minimum in descending order is the highest
                // cell holding the minimum. Only the best representative needs it.
                if (rep_best < best.cost)
                    for (std::size_t i = n; i-- > 0;)
                        if (cells.cost(i) == rep_best) {
                            rep_from = cells.start(i);
                            break;
                        }
            }
#endif
            const bool other_label = m.representative_labels[r] != label_of(best.rep);
            if (rep_best < best.cost) {
                if (other_label) runner_up = best.cost;
                best = Hypothesis{rep_best, static_cast<std::uint16_t>(r), rep_from};
            } else if (other_label && rep_best < runner_up) {
                runner_up = rep_best;
            }
            if (cells.cost(n - 1) < end_cost) {
                end_cost = cells.cost(n - 1);
                end = SegmentEnd{static_cast<std::uint16_t>(r), cells.start(n - 1)};
            }
        }
    }

    // The settle delay in characters, rounded (settings already checked).
    static constexpr std::uint32_t settle_chars_for(const ModelView& model, const SegmenterConfig& config) noexcept {
        const std::int64_t period = model.string_period_us;
        return static_cast<std::uint32_t>((config.settle_delay_us + period / 2) / period);
    }
    // settle_stable_us in characters, rounded, at least one; 0 when it would
    // settle nothing before the delay does (settings already checked).
    static constexpr std::uint32_t stable_chars_for(const ModelView& model, const SegmenterConfig& config) noexcept {
        if (config.settle_stable_us <= 0) return 0;
        const std::int64_t period = model.string_period_us;
        const std::int64_t chars = (config.settle_stable_us + period / 2) / period;
        const std::uint32_t stable = chars < 1 ? 1u : static_cast<std::uint32_t>(chars);
        return stable < settle_chars_for(model, config) ? stable : 0u;
    }

    static constexpr std::uint16_t unknown_rep = 0xFFFF;

    struct Plan {
        std::size_t costs = 0, starts = 0, ends = 0, settled = 0, candidates = 0, agreed_since = 0, stable_bytes = 0,
                    votes = 0, votes_bytes = 0, exemplars = 0, exemplars_bytes = 0, feature = 0, column = 0, window = 0,
                    histogram = 0, window_costs = 0, window_bytes = 0, ring_size = 0, bytes = unsatisfiable_bytes;
    };
    static constexpr bool uses_votes(const ModelView& model, const SegmenterConfig& config) noexcept {
        return config.vote_weight > 0.0f && model.has_votes();
    }
    static constexpr bool uses_exemplars(const ModelView& model, const SegmenterConfig& config) noexcept {
        return config.exemplar_weight > 0.0f && model.has_exemplars();
    }
    static constexpr bool uses_window(const ModelView& model, const SegmenterConfig& config) noexcept {
        return config.direction_weight > 0.0f && model.has_window_directions();
    }
    static constexpr Plan plan(const ModelView& model, const SegmenterConfig& config) noexcept;

    struct Hypothesis {
        float cost = 0.0f;
        std::uint16_t rep = unknown_rep;
        std::uint32_t start = 0;  ///< Stream index (mod 2^32) of its segment's first character.
    };
    struct SegmentEnd {
        std::uint16_t rep = unknown_rep;
        std::uint32_t start = 0;
    };
    // The character in progress between begin() and its last advance().
    struct Update {
        bool active = false;
        bool exemplars = false;   // its exemplars' distances are still being measured
        bool candidates = false;  // best, runner_up, end and end_cost are set
        std::uint32_t now = 0;    // its stream index (mod 2^32)
        const float* column = nullptr;  // W(·, character)
        float shift = 0.0f, previous_end = 0.0f, entry = 0.0f;
        float no_action_vote = 0.0f;
        float none = 0.0f;  // the nearest centre of "no action" so far
        std::size_t next_centre = 0, next_rep = 0;
        Hypothesis best;  // the best explanation so far, ending anywhere in a representative
        // The best explanation whose newest character has another label than
        // best's (for live_margin()): kept beside best as each candidate comes.
        float runner_up = 0.0f;
        SegmentEnd end;  // the best one ending exactly here (a representative's last cell)
        float end_cost = 0.0f;
    };

    // A representative's cells from a position on: each cell's cost (relative
    // to the previous step's best) and the index where its segment started.
    // The layout is the target's: with SIMD, costs and starts in two arrays so
    // four neighbouring cells load as one vector; without, each cost beside its
    // start so one pointer walks both (a Cortex-M4 has few registers to spare).
    // Either way two words per cell.
#if ACTIONSTRING_DETAIL_LANES == 4
    struct Cells {
        float* costs;
        std::uint32_t* starts;
        float& cost(std::size_t i) const noexcept { return costs[i]; }
        std::uint32_t& start(std::size_t i) const noexcept { return starts[i]; }
        Cells operator+(std::size_t k) const noexcept { return Cells{costs + k, starts + k}; }
        Cells operator-(std::size_t k) const noexcept { return Cells{costs - k, starts - k}; }
        void down() noexcept { --costs, --starts; }
    };
    static Cells cells_in(void* storage, const Plan& p) noexcept {
        return Cells{detail::storage_at<float>(storage, p.costs), detail::storage_at<std::uint32_t>(storage, p.starts)};
    }
#else
    struct Cells {
        struct Cell {
            float cost;
            std::uint32_t start;
        };
        Cell* cells;
        float& cost(std::size_t i) const noexcept { return cells[i].cost; }
        std::uint32_t& start(std::size_t i) const noexcept { return cells[i].start; }
        Cells operator+(std::size_t k) const noexcept { return Cells{cells + k}; }
        Cells operator-(std::size_t k) const noexcept { return Cells{cells - k}; }
        void down() noexcept { --cells; }
    };
    static Cells cells_in(void* storage, const Plan& p) noexcept {
        return Cells{detail::storage_at<Cells::Cell>(storage, p.costs)};
    }
#endif

#if ACTIONSTRING_DETAIL_LANES == 4
    // A block's choices, lane by lane as choose() in push(): from the advance
    // already in (value, from), to stay if strictly cheaper, then to skip if
    // strictly cheaper. minimum(a, b) is exactly less(a, b) ? a : b (MINPS), so
    // each choice's cost takes one instruction and the mask picks the start.
    template <class V>
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static void choose_lanes(V& value, V& from, V stay, V stay_from, V skip,
                                                           V skip_from) noexcept {
        const auto take_stay = detail::less(stay, value);
        value = detail::minimum(stay, value);
        from = detail::select(take_stay, stay_from, from);
        const auto take_skip = detail::less(skip, value);
        value = detail::minimum(skip, value);
        from = detail::select(take_skip, skip_from, from);
    }

    struct BottomCells {
        detail::Lanes cost, start;
    };
    // Cells 0 … 3 of a representative of at least four, the same choices as
    // the scalar code in push() lane by lane: cell 0 enters the segment (the
    // entry's cost in the lane of "cell i − 1") or stays, and cannot skip (+∞
    // never wins); cell 1 advances from cell 0, stays, or skips in from the
    // entry; cells 2 and 3 are ordinary. Reads only the previous step's cells
    // 0 … 3; push() stores the result.
    static BottomCells bottom_cells(Cells cells, const Character* rep, const float* column, float shift,
                                    float stay_penalty, float skip_penalty, float vote, float entry,
                                    std::uint32_t now) noexcept {
        using detail::Lanes;
        const Lanes old = detail::load_lanes(cells.costs) - detail::broadcast(shift);  // old cell i, shifted
        const Lanes old_from = detail::load_lanes(cells.starts);
        const Lanes now_l = detail::broadcast_bits(now);
        Lanes value = detail::lanes_up1(old, detail::broadcast(entry));  // old cell i − 1; the entry for cell 0
        Lanes from = detail::lanes_up1(old_from, now_l);
        // Skips from old cell i − 2; for cells 0 and 1 from +∞ and the entry.
        const Lanes skip = detail::lanes_up2(old, detail::lanes_of(detail::infinity(), entry, 0.0f, 0.0f)) +
                           detail::broadcast(skip_penalty);
        choose_lanes(value, from, old + detail::broadcast(stay_penalty), old_from, skip,
                     detail::lanes_up2(old_from, now_l));
        value = value + (detail::LaneOps<4>::gather(column, rep) + detail::broadcast(vote));
        return BottomCells{value, from};
    }

    // Cells top, top − 1, … in blocks of L while a block's lowest cell has
    // index ≥ 2, the same recurrence as the scalar loop in push(), lane by lane
    // (choose_lanes). Lowers `top` past the blocks done and returns the smaller
    // of `best` and their cells' costs.
    template <std::size_t L>
    static float cell_blocks(Cells cells, const Character* rep, const float* column, std::size_t& top, float shift,
                             float stay_penalty, float skip_penalty, float vote, float best) noexcept {
        using Ops = detail::LaneOps<L>;
        using V = typename Ops::V;
        if (top < L + 1) return best;
        float* const costs = cells.costs;
        std::uint32_t* const starts = cells.starts;
        const V shift_l = Ops::broadcast(shift), stay_l = Ops::broadcast(stay_penalty),
                skip_l = Ops::broadcast(skip_penalty), vote_l = Ops::broadcast(vote);
        V best_l = Ops::broadcast(best);
        for (; top >= L + 1; top -= L) {
            const std::size_t low = top - (L - 1);  // the block is cells low … top
            V value = Ops::load(costs + low - 1) - shift_l;
            V from = Ops::load(starts + low - 1);
            choose_lanes(value, from, Ops::load(costs + low) - shift_l + stay_l, Ops::load(starts + low),
                         Ops::load(costs + low - 2) - shift_l + skip_l, Ops::load(starts + low - 2));
            value = value + (Ops::gather(column, rep + low) + vote_l);
            detail::store_lanes(costs + low, value);
            detail::store_lanes(starts + low, from);
            best_l = detail::minimum(value, best_l);
        }
        return detail::smallest_lane(best_l);
    }
#endif

    // The ring slot of a character index: index mod 2^32 mod ring_size_, a mask
    // as ring_size_ is a power of two (no 64-bit division on a 32-bit core).
    std::size_t slot(std::uint64_t index) const noexcept {
        return static_cast<std::size_t>(static_cast<std::uint32_t>(index) & static_cast<std::uint32_t>(ring_size_ - 1u));
    }

    LabelId label_of(std::uint16_t rep) const noexcept {
        return rep == unknown_rep ? unknown_label : model_->representative_labels[rep];
    }

    // Walks the best explanation back from the newest character. Ages are
    // compared modulo 2^32, so the walk is exact on streams of any length.
    LabelId label_at(std::uint64_t index) const noexcept {
        const std::uint32_t newest = static_cast<std::uint32_t>(pushed_ - 1);
        const std::uint32_t target_age = static_cast<std::uint32_t>(pushed_ - 1 - index);
        std::uint16_t rep = best_.rep;
        std::uint32_t start = best_.start;
        for (std::size_t guard = 0; guard <= ring_size_; ++guard) {
            const std::uint32_t start_age = newest - start;
            if (start_age >= target_age) return label_of(rep);
            const std::uint32_t previous = start - 1u;  // the end of the segment before
            const SegmentEnd& end = ends_[slot(previous)];
            rep = end.rep;
            start = end.start;
        }
        return unknown_label;  // not reached: each step moves at least one character back
    }

    const ModelView* model_ = nullptr;
    SegmenterConfig config_;
    std::uint32_t settle_chars_ = 0;
    std::uint64_t pushed_ = 0;
    std::uint64_t settled_count_ = 0;  // characters settled (they settle in order)
    std::uint32_t just_settled_ = 0;   // by the last character done
    std::uint32_t stable_chars_ = 0;   // settle_stable_us in characters; 0 = the delay alone
    float last_end_ = 0.0f;
    float margin_ = 0.0f;
    Hypothesis best_;
    // A power of two above settle_chars_, so that slot = index mod 2^32 mod
    // ring_size_ stays consistent when the 32-bit index wraps.
    std::size_t ring_size_ = 0;
    Cells cells_{};                     // one per representative character
    SegmentEnd* ends_ = nullptr;       // ring_size_: the best explanation ending at each character
    LabelId* settled_ = nullptr;       // ring_size_: the settled labels
    // ring_size_ each, with settle_stable_us only: each unsettled character's
    // label in the best explanation, and the pushed_ (mod 2^32) since which
    // every best explanation has given it.
    LabelId* candidates_ = nullptr;
    std::uint32_t* agreed_since_ = nullptr;
    float* vote_costs_ = nullptr;  // label_count: the newest character's cost per label (votes, exemplars or window on)
    float* exemplar_distances_ = nullptr;  // label_count: its exemplar distances (exemplars on only)
    bool use_votes_ = false;
    float* column_ = nullptr;          // K: W(·, newest character), when W is not symmetric
    bool w_symmetric_ = true;
    float* feature_ = nullptr;         // feature_dim: the character's feature, kept for advance() (exemplars on only)
    float* window_ = nullptr;          // window_direction_chars records, oldest first (window directions on only)
    float* histogram_ = nullptr;       // window_direction_size(): the window's histograms
    float* window_costs_ = nullptr;    // label_count: what the window's directions add
    std::size_t window_count_ = 0;     // records in window_
    Update update_;
};

constexpr ActionSegmenter::Plan ActionSegmenter::plan(const ModelView& model, const SegmenterConfig& config) noexcept {
    Plan p;
    // Settings check() refuses have no size; the ring needs a string period.
    if (model.string_period_us == 0 || !(config.settle_delay_us >= 0) || config.settle_delay_us > max_settle_delay_us ||
        !(config.settle_stable_us >= 0) || config.settle_stable_us > max_settle_delay_us)
        return p;
    p.ring_size = detail::next_power_of_two(std::size_t{settle_chars_for(model, config)} + 1u);
    detail::StorageLayout layout;
#if ACTIONSTRING_DETAIL_LANES == 4
    p.costs = layout.add<float>(model.total_representative_chars());
    p.starts = layout.add<std::uint32_t>(model.total_representative_chars());
#else
    p.costs = layout.add<Cells::Cell>(model.total_representative_chars());
#endif
    p.ends = layout.add<SegmentEnd>(p.ring_size);
    p.settled = layout.add<LabelId>(p.ring_size);
    if (stable_chars_for(model, config) != 0) {
        p.candidates = layout.add<LabelId>(p.ring_size);
        p.agreed_since = layout.add<std::uint32_t>(p.ring_size);
        p.stable_bytes = p.ring_size * (sizeof(LabelId) + sizeof(std::uint32_t));
    }
    p.column = layout.add<float>(model.character_count);
    // Per label, the newest character's cost: its votes', its exemplars', or both.
    if (ActionSegmenter::uses_votes(model, config) || ActionSegmenter::uses_exemplars(model, config) ||
        ActionSegmenter::uses_window(model, config)) {
        p.votes = layout.add<float>(model.label_count);
        p.votes_bytes = std::size_t{model.label_count} * sizeof(float);
    }
    if (ActionSegmenter::uses_exemplars(model, config)) {
        p.exemplars = layout.add<float>(model.label_count);
        p.exemplars_bytes = std::size_t{model.label_count} * sizeof(float);
        p.feature = layout.add<float>(model.feature_dim);
    }
    // The window's records, its histograms and their costs.
    if (ActionSegmenter::uses_window(model, config)) {
        const std::size_t records = std::size_t{model.window_direction_chars} * model.direction_record_floats();
        p.window = layout.add<float>(records);
        p.histogram = layout.add<float>(model.window_direction_size());
        p.window_costs = layout.add<float>(model.label_count);
        p.window_bytes = (records + model.window_direction_size() + model.label_count) * sizeof(float);
    }
    p.bytes = layout.bytes();
    return p;
}

}  // namespace actionstring
