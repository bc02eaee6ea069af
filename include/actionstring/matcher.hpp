// actionstring — incremental sliding-window string matcher (design.md §2).
//
// Windows of window_chars characters start every step_chars characters. Each
// open window keeps, per representative, one DP row (when the window is the
// shorter string A1, its characters are rows) or one DP column (when the
// representative is A1, the window's characters are columns), and advances it
// by one line of cells per character. A completed window's distances equal
// string_distance() on the same strings bit for bit.
//
// Every open window receives the same character, so the state is stored cell
// by cell with the windows side by side ("lanes", ceil(window / step) of
// them): one pass over a representative advances all windows, each lane doing
// exactly the batch computation's operations, independent of the others, so
// the loop over lanes vectorises. A lane whose window is closed computes
// values nobody reads.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/detail/dp.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"

namespace actionstring {

/// Sliding-window matcher state. Works in caller-owned storage of
/// required_bytes(model) bytes (storage.hpp). Keeps pointers to the ModelView
/// passed to init() and to the storage: both must outlive the matcher (or its
/// next init()).
class WindowMatcher {
public:
    /// Bytes of storage init() needs for this model (constexpr when the model is).
    static constexpr std::size_t required_bytes(const ModelView& model) noexcept { return plan(model).bytes; }

    /// Binds the matcher to a model's matching tables (W, representatives,
    /// window settings; the rest may be empty) and clears it. Returns
    /// invalid_model, model_exceeds_capacity (a string too long for 16-bit
    /// path lengths), storage_too_small or ok; on failure the matcher stays unusable.
    Status init(const ModelView& model, void* storage, std::size_t bytes) noexcept {
        model_ = nullptr;
        const Status status = validate_matching_tables(model);
        if (status != Status::ok) return status;
        for (std::size_t r = 0; r < model.representative_count; ++r)
            if (model.representative_length(r) + model.window_chars > 0xFFFFu) return Status::model_exceeds_capacity;
        const Plan p = plan(model);
        if (!detail::storage_fits(storage, bytes, p.bytes)) return Status::storage_too_small;
        detail::clear_storage(storage, p.bytes);
        lanes_ = model.max_open_windows();
        track_paths_ = model.normalization == LengthNormalization::path;
        windows_ = detail::storage_at<Window>(storage, p.windows);
        costs_ = detail::storage_at<float>(storage, p.costs);
        paths_ = detail::storage_at<std::uint16_t>(storage, p.paths);
        best_ = detail::storage_at<float>(storage, p.best);
        completed_ = detail::storage_at<float>(storage, p.completed);
        lane_cells_ = detail::storage_at<detail::Cell>(storage, p.lane_cells);
        lane_costs_ = detail::storage_at<float>(storage, p.lane_costs);
        model_ = &model;
        reset();
        return Status::ok;
    }

    /// Forgets every window and character; the model stays bound.
    void reset() noexcept {
        pushed_ = 0;
        completed_start_ = 0;
        has_completed_ = false;
        for (std::size_t lane = 0; lane < lanes_; ++lane) windows_[lane] = Window{};
    }

    bool initialized() const noexcept { return model_ != nullptr; }

    /// Feeds the next character of the stream. Returns true when a window
    /// completed with it; its distances are then in completed_distances().
    /// Work: (total representative characters + R) × open windows cells.
    bool push(Character character) noexcept {
        if (model_ == nullptr || character >= model_->character_count) return false;
        const ModelView& m = *model_;
        if (pushed_ % m.step_chars == 0) open_window(static_cast<std::size_t>((pushed_ / m.step_chars) % lanes_));
        // The lane count as a compile-time constant for the usual windows
        // (4 or 8 steps), so the lanes sit in SIMD registers; any other
        // count takes the same code with a run-time count.
        if (track_paths_) advance<true, 0>(character);
        else if (lanes_ == 4) advance<false, 4>(character);
        else if (lanes_ == 8) advance<false, 8>(character);
        else advance<false, 0>(character);
        bool completed = false;
        for (std::size_t lane = 0; lane < lanes_; ++lane) {
            Window& window = windows_[lane];
            if (!window.open || ++window.filled != m.window_chars) continue;
            finish(lane);
            window.open = false;
            completed_start_ = window.start;
            has_completed_ = true;
            completed = true;
        }
        ++pushed_;
        return completed;
    }

    /// Distances of the most recently completed window to each representative
    /// (representative_count floats, owned by the matcher, valid until the
    /// next push() or reset()).
    const float* completed_distances() const noexcept { return completed_; }
    bool has_completed_window() const noexcept { return has_completed_; }
    /// Index in the stream of the first character of the last completed window.
    std::uint64_t completed_window_start() const noexcept { return completed_start_; }
    /// Characters pushed since the last reset.
    std::uint64_t characters_pushed() const noexcept { return pushed_; }

private:
    struct Window {
        bool open = false;
        std::uint64_t start = 0;
        std::uint32_t filled = 0;
    };

    // The state: per lane a window; per cell (one row or column of
    // length(rep) + 1 per representative) and lane a cost, and with path
    // normalisation a path length; per representative and lane the best
    // subsequence end; one completed distance per representative; and a
    // line of scratch per lane for the recurrences.
    struct Plan {
        std::size_t windows = 0, costs = 0, paths = 0, best = 0, completed = 0, lane_cells = 0, lane_costs = 0,
                    bytes = 0;
    };
    static constexpr Plan plan(const ModelView& m) noexcept {
        const std::size_t lanes = m.max_open_windows();
        const std::size_t cells = static_cast<std::size_t>(m.total_representative_chars()) + m.representative_count;
        const bool paths = m.normalization == LengthNormalization::path;
        // Saturating products: a hostile model's counts cannot wrap to a small block.
        const auto times = [](std::size_t a, std::size_t b) {
            return b != 0 && a > unsatisfiable_bytes / b ? unsatisfiable_bytes : a * b;
        };
        detail::StorageLayout layout;
        Plan p;
        p.windows = layout.add<Window>(lanes);
        p.costs = layout.add<float>(times(cells, lanes));
        p.paths = layout.add<std::uint16_t>(paths ? times(cells, lanes) : 0u);
        p.best = layout.add<float>(times(m.representative_count, lanes));
        p.completed = layout.add<float>(m.representative_count);
        p.lane_cells = layout.add<detail::Cell>(times(2, lanes));
        p.lane_costs = layout.add<float>(times(2, lanes));
        p.bytes = layout.bytes();
        return p;
    }

    bool window_is_a1(std::size_t r) const noexcept { return model_->window_chars <= model_->representative_length(r); }
    std::size_t first_cell(std::size_t r) const noexcept { return model_->representative_offsets[r] + r; }

    // Path lengths exist only with path normalisation; without it they read as 0 and are not stored.
    detail::Cell load(std::size_t cell, std::size_t lane) const noexcept {
        const std::size_t at = cell * lanes_ + lane;
        return detail::Cell{costs_[at], track_paths_ ? paths_[at] : 0u};
    }
    void store(std::size_t cell, std::size_t lane, detail::Cell value) noexcept {
        const std::size_t at = cell * lanes_ + lane;
        costs_[at] = value.cost;
        if (track_paths_) paths_[at] = static_cast<std::uint16_t>(value.path);
    }

    void open_window(std::size_t lane) noexcept {
        const ModelView& m = *model_;
        windows_[lane] = Window{true, pushed_, 0};
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            best_[r * lanes_ + lane] = detail::infinity();
            if (!window_is_a1(r)) continue;  // a column needs the window's first character
            const std::size_t base = first_cell(r);
            store(base, lane, detail::dp_origin());
            for (std::size_t j = 1; j <= m.representative_length(r); ++j)
                store(base + j, lane, detail::dp_row0(m.variant));
        }
    }

    template <bool Paths, std::size_t Lanes>
    void advance(Character c) noexcept {
        const ModelView& m = *model_;
        const CharacterWeights w = character_weights(m);
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            const Character* rep = m.representative_chars + m.representative_offsets[r];
            const std::size_t len = m.representative_length(r);
            const std::size_t base = first_cell(r);
            if (!window_is_a1(r)) {
                // Column 0 depends on the window's first character.
                for (std::size_t lane = 0; lane < lanes_; ++lane) {
                    if (!windows_[lane].open || windows_[lane].filled != 0) continue;
                    store(base, lane, detail::dp_origin());
                    for (std::size_t i = 1; i <= len; ++i)
                        store(base + i, lane, detail::dp_col0(m.variant, w(rep[i - 1], c)));
                }
            }
            if (window_is_a1(r)) advance_row<Paths, Lanes>(base, rep, len, c, w);
            else advance_column<Paths, Lanes>(r, base, rep, len, c, w);
        }
    }

    // The incoming character is row i of a window that is A1; the stored row holds D[i−1][·].
    template <bool Paths, std::size_t Lanes>
    void advance_row(std::size_t base, const Character* rep, std::size_t len, Character c,
                     CharacterWeights w) noexcept {
        const std::size_t lanes = Lanes != 0 ? Lanes : lanes_;
        const detail::Cell boundary = detail::dp_col0(model_->variant, w(c, rep[0]));
        if (Paths) {
            detail::Cell* diagonal = lane_cells_;
            detail::Cell* left = lane_cells_ + lanes;
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                diagonal[lane] = load(base, lane);
                left[lane] = boundary;
                store(base, lane, boundary);
            }
            for (std::size_t j = 1; j <= len; ++j) {
                const float weight = w(c, rep[j - 1]);
                for (std::size_t lane = 0; lane < lanes; ++lane) {
                    const detail::Cell above = load(base + j, lane);
                    left[lane] = detail::dp_step(diagonal[lane], above, left[lane], weight);
                    diagonal[lane] = above;
                    store(base + j, lane, left[lane]);
                }
            }
            return;
        }
        // Local arrays when the lane count is known: they cannot alias the
        // cells, so the compiler keeps them in registers.
        float local_diagonal[Lanes != 0 ? Lanes : 1], local_left[Lanes != 0 ? Lanes : 1];
        float* diagonal = Lanes != 0 ? local_diagonal : lane_costs_;
        float* left = Lanes != 0 ? local_left : lane_costs_ + lanes;
        float* first = costs_ + base * lanes;
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            diagonal[lane] = first[lane];
            left[lane] = boundary.cost;
            first[lane] = boundary.cost;
        }
        for (std::size_t j = 1; j <= len; ++j) {
            const float weight = w(c, rep[j - 1]);
            float* cells = costs_ + (base + j) * lanes;
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                const float above = cells[lane];
                left[lane] = detail::dp_step_cost(diagonal[lane], above, left[lane], weight);
                diagonal[lane] = above;
                cells[lane] = left[lane];
            }
        }
    }

    // The incoming character is column j of a window that is A2; the stored column holds D[·][j−1].
    template <bool Paths, std::size_t Lanes>
    void advance_column(std::size_t r, std::size_t base, const Character* rep, std::size_t len, Character c,
                        CharacterWeights w) noexcept {
        const std::size_t lanes = Lanes != 0 ? Lanes : lanes_;
        const ModelView& m = *model_;
        const detail::Cell boundary = detail::dp_row0(m.variant);
        const bool subsequence = m.variant == MatchVariant::subsequence;
        if (Paths) {
            detail::Cell* diagonal = lane_cells_;
            detail::Cell* above = lane_cells_ + lanes;
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                diagonal[lane] = load(base, lane);
                above[lane] = boundary;
                store(base, lane, boundary);
            }
            for (std::size_t i = 1; i <= len; ++i) {
                const float weight = w(rep[i - 1], c);
                for (std::size_t lane = 0; lane < lanes; ++lane) {
                    const detail::Cell left = load(base + i, lane);
                    above[lane] = detail::dp_step(diagonal[lane], above[lane], left, weight);
                    diagonal[lane] = left;
                    store(base + i, lane, above[lane]);
                }
            }
            if (subsequence)
                for (std::size_t lane = 0; lane < lanes; ++lane) track_best(r, lane, above[lane]);
            return;
        }
        float local_diagonal[Lanes != 0 ? Lanes : 1], local_above[Lanes != 0 ? Lanes : 1];
        float* diagonal = Lanes != 0 ? local_diagonal : lane_costs_;
        float* above = Lanes != 0 ? local_above : lane_costs_ + lanes;
        float* first = costs_ + base * lanes;
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            diagonal[lane] = first[lane];
            above[lane] = boundary.cost;
            first[lane] = boundary.cost;
        }
        for (std::size_t i = 1; i <= len; ++i) {
            const float weight = w(rep[i - 1], c);
            float* cells = costs_ + (base + i) * lanes;
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                const float left = cells[lane];
                above[lane] = detail::dp_step_cost(diagonal[lane], above[lane], left, weight);
                diagonal[lane] = left;
                cells[lane] = above[lane];
            }
        }
        if (subsequence)
            for (std::size_t lane = 0; lane < lanes; ++lane) track_best(r, lane, detail::Cell{above[lane], 0u});
    }

    // Subsequence with the representative as A1: the best end over the window's columns so far.
    void track_best(std::size_t r, std::size_t lane, detail::Cell last_row) noexcept {
        const float score = detail::dp_score(last_row, model_->normalization, model_->window_chars);
        float& best = best_[r * lanes_ + lane];
        if (score < best) best = score;
    }

    void finish(std::size_t lane) noexcept {
        const ModelView& m = *model_;
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            const std::size_t len = m.representative_length(r);
            const std::size_t base = first_cell(r);
            if (m.variant == MatchVariant::subsequence && window_is_a1(r)) {
                float best = detail::infinity();
                for (std::size_t j = 1; j <= len; ++j) {
                    const float score = detail::dp_score(load(base + j, lane), m.normalization, m.window_chars);
                    if (score < best) best = score;
                }
                completed_[r] = best;
            } else if (m.variant == MatchVariant::subsequence) {
                completed_[r] = best_[r * lanes_ + lane];
            } else {
                completed_[r] = detail::dp_score(load(base + len, lane), m.normalization, m.window_chars);
            }
        }
    }

    const ModelView* model_ = nullptr;
    std::size_t lanes_ = 0;
    bool track_paths_ = false;
    std::uint64_t pushed_ = 0;
    std::uint64_t completed_start_ = 0;
    bool has_completed_ = false;
    Window* windows_ = nullptr;           // lanes_
    float* costs_ = nullptr;              // cells × lanes_, lane fastest
    std::uint16_t* paths_ = nullptr;      // the same, with path normalisation only
    float* best_ = nullptr;               // R × lanes_
    float* completed_ = nullptr;          // R
    detail::Cell* lane_cells_ = nullptr;  // 2 × lanes_ scratch (with paths)
    float* lane_costs_ = nullptr;         // 2 × lanes_ scratch (costs only)
};

}  // namespace actionstring
