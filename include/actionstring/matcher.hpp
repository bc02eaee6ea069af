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
// by cell with the windows side by side ("lanes"): one pass over a
// representative advances all windows, each lane doing exactly the batch
// computation's operations, independent of the others. The lane count is the
// compile-time Cap::max_windows so the lanes sit in SIMD registers; lanes the
// model does not use compute values nobody reads (a generated capacity has none).
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/capacity.hpp"
#include "actionstring/detail/dp.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Sliding-window matcher state with storage fixed by `Cap` (see capacity.hpp).
/// Holds a pointer to the ModelView passed to init(): that object and its
/// tables must outlive the matcher (or the next init()).
template <class Cap>
class WindowMatcher {
public:
    /// Binds the matcher to a model's matching tables (W, representatives,
    /// window settings; the rest may be empty) and clears it. Returns
    /// invalid_model, model_exceeds_capacity or ok; on failure the matcher
    /// stays unusable.
    Status init(const ModelView& model) noexcept {
        model_ = nullptr;
        const Status status = validate_matching_tables(model);
        if (status != Status::ok) return status;
        if (!Cap::fits_matching(model)) return Status::model_exceeds_capacity;
        for (std::size_t r = 0; r < model.representative_count; ++r)
            if (model.representative_length(r) + model.window_chars > 0xFFFFu) return Status::model_exceeds_capacity;
        model_ = &model;
        lanes_ = model.max_open_windows();
        track_paths_ = model.normalization == LengthNormalization::path;
        reset();
        return Status::ok;
    }

    /// Forgets every window and character; the model stays bound.
    void reset() noexcept {
        pushed_ = 0;
        completed_start_ = 0;
        has_completed_ = false;
        for (auto& window : windows_) window = Window{};
    }

    bool initialized() const noexcept { return model_ != nullptr; }

    /// Feeds the next character of the stream. Returns true when a window
    /// completed with it; its distances are then in completed_distances().
    /// Work: (total representative characters + R) × open windows cells.
    bool push(Character character) noexcept {
        if (model_ == nullptr || character >= model_->character_count) return false;
        const ModelView& m = *model_;
        if (pushed_ % m.step_chars == 0) open_window(static_cast<std::size_t>((pushed_ / m.step_chars) % lanes_));
        if (track_paths_) advance<true>(character);
        else advance<false>(character);
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
    static constexpr std::size_t max_lanes = Cap::max_windows;
    static constexpr std::size_t path_cells = Cap::path_lengths ? Cap::cells_per_window : 1;
    static constexpr std::size_t path_lanes = Cap::path_lengths ? Cap::max_windows : 1;

    struct Window {
        bool open = false;
        std::uint64_t start = 0;
        std::uint32_t filled = 0;
    };

    bool window_is_a1(std::size_t r) const noexcept { return model_->window_chars <= model_->representative_length(r); }
    std::size_t first_cell(std::size_t r) const noexcept { return model_->representative_offsets[r] + r; }

    // Path lengths exist only when the capacity provides them; the modulo
    // folds to 0 otherwise and is never reached with tracking on.
    detail::Cell load(std::size_t cell, std::size_t lane) const noexcept {
        return detail::Cell{costs_[cell][lane], paths_[cell % path_cells][lane % path_lanes]};
    }
    void store(std::size_t cell, std::size_t lane, detail::Cell value) noexcept {
        costs_[cell][lane] = value.cost;
        paths_[cell % path_cells][lane % path_lanes] = static_cast<std::uint16_t>(value.path);
    }

    void open_window(std::size_t lane) noexcept {
        const ModelView& m = *model_;
        windows_[lane] = Window{true, pushed_, 0};
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            best_[r][lane] = detail::infinity();
            if (!window_is_a1(r)) continue;  // a column needs the window's first character
            const std::size_t base = first_cell(r);
            store(base, lane, detail::dp_origin());
            for (std::size_t j = 1; j <= m.representative_length(r); ++j)
                store(base + j, lane, detail::dp_row0(m.variant));
        }
    }

    template <bool Paths>
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
            if (window_is_a1(r)) advance_row<Paths>(base, rep, len, c, w);
            else advance_column<Paths>(r, base, rep, len, c, w);
        }
    }

    // The incoming character is row i of a window that is A1; the stored row holds D[i−1][·].
    template <bool Paths>
    void advance_row(std::size_t base, const Character* rep, std::size_t len, Character c,
                     CharacterWeights w) noexcept {
        constexpr std::size_t lanes = max_lanes;
        const detail::Cell boundary = detail::dp_col0(model_->variant, w(c, rep[0]));
        if (Paths) {
            detail::Cell diagonal[max_lanes], left[max_lanes];
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
        float diagonal[max_lanes], left[max_lanes];
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            diagonal[lane] = costs_[base][lane];
            left[lane] = boundary.cost;
            costs_[base][lane] = boundary.cost;
        }
        for (std::size_t j = 1; j <= len; ++j) {
            const float weight = w(c, rep[j - 1]);
            float* cells = costs_[base + j];
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                const float above = cells[lane];
                left[lane] = detail::dp_step_cost(diagonal[lane], above, left[lane], weight);
                diagonal[lane] = above;
                cells[lane] = left[lane];
            }
        }
    }

    // The incoming character is column j of a window that is A2; the stored column holds D[·][j−1].
    template <bool Paths>
    void advance_column(std::size_t r, std::size_t base, const Character* rep, std::size_t len, Character c,
                        CharacterWeights w) noexcept {
        constexpr std::size_t lanes = max_lanes;
        const ModelView& m = *model_;
        const detail::Cell boundary = detail::dp_row0(m.variant);
        const bool subsequence = m.variant == MatchVariant::subsequence;
        if (Paths) {
            detail::Cell diagonal[max_lanes], above[max_lanes];
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
        float diagonal[max_lanes], above[max_lanes];
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            diagonal[lane] = costs_[base][lane];
            above[lane] = boundary.cost;
            costs_[base][lane] = boundary.cost;
        }
        for (std::size_t i = 1; i <= len; ++i) {
            const float weight = w(rep[i - 1], c);
            float* cells = costs_[base + i];
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
        if (score < best_[r][lane]) best_[r][lane] = score;
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
                completed_[r] = best_[r][lane];
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
    Window windows_[max_lanes] = {};
    float costs_[Cap::cells_per_window][max_lanes] = {};
    std::uint16_t paths_[path_cells][path_lanes] = {};
    float best_[Cap::max_representatives][max_lanes] = {};
    float completed_[Cap::max_representatives] = {};
};

}  // namespace actionstring
