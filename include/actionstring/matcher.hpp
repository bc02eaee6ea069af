// actionstring — incremental sliding-window string matcher (DESIGN §2).
//
// Windows of window_chars characters start every step_chars characters. Each
// open window keeps, per representative, one DP row (when the window is the
// shorter string A1, its characters are rows) or one DP column (when the
// representative is A1, the window's characters are columns), and advances it
// by one cell line per character. A completed window's distances equal
// string_distance() on the same strings bit for bit.
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
    /// window settings; the rest may be empty) and clears it. Returns invalid_model,
    /// model_exceeds_capacity or ok; on failure the matcher stays unusable.
    Status init(const ModelView& model) noexcept {
        model_ = nullptr;
        const Status status = validate_matching_tables(model);
        if (status != Status::ok) return status;
        if (!Cap::fits_matching(model)) return Status::model_exceeds_capacity;
        for (std::size_t r = 0; r < model.representative_count; ++r)
            if (model.representative_length(r) + model.window_chars > 0xFFFFu)
                return Status::model_exceeds_capacity;
        model_ = &model;
        open_slots_ = model.max_open_windows();
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
    /// Work: open windows × (total representative characters + R) cells.
    bool push(Character character) noexcept {
        if (model_ == nullptr || character >= model_->character_count) return false;
        const ModelView& m = *model_;
        if (pushed_ % m.step_chars == 0) {
            const std::size_t slot = static_cast<std::size_t>((pushed_ / m.step_chars) % open_slots_);
            open_window(slot);
        }
        bool completed = false;
        for (std::size_t slot = 0; slot < open_slots_; ++slot) {
            Window& window = windows_[slot];
            if (!window.open) continue;
            advance(slot, character);
            if (++window.filled == m.window_chars) {
                finish(slot);
                window.open = false;
                completed_start_ = window.start;
                has_completed_ = true;
                completed = true;
            }
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

    static constexpr std::size_t path_slots = Cap::path_lengths ? Cap::max_windows : 1;
    static constexpr std::size_t path_cells = Cap::path_lengths ? Cap::cells_per_window : 1;

    bool window_is_a1(std::size_t r) const noexcept {
        return model_->window_chars <= model_->representative_length(r);
    }
    std::size_t first_cell(std::size_t r) const noexcept { return model_->representative_offsets[r] + r; }

    detail::Cell load(std::size_t slot, std::size_t cell) const noexcept {
        const std::uint32_t path = Cap::path_lengths ? paths_[slot % path_slots][cell % path_cells] : 0u;
        return detail::Cell{costs_[slot][cell], path};
    }
    void store(std::size_t slot, std::size_t cell, detail::Cell value) noexcept {
        costs_[slot][cell] = value.cost;
        if (Cap::path_lengths)
            paths_[slot % path_slots][cell % path_cells] = static_cast<std::uint16_t>(value.path);
    }

    void open_window(std::size_t slot) noexcept {
        const ModelView& m = *model_;
        windows_[slot] = Window{true, pushed_, 0};
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            best_[slot][r] = detail::infinity();
            if (!window_is_a1(r)) continue;  // a column needs the window's first character
            const std::size_t base = first_cell(r);
            store(slot, base, detail::dp_origin());
            for (std::size_t j = 1; j <= m.representative_length(r); ++j)
                store(slot, base + j, detail::dp_row0(m.variant));
        }
    }

    void advance(std::size_t slot, Character c) noexcept {
        const ModelView& m = *model_;
        const CharacterWeights w = character_weights(m);
        const bool first = windows_[slot].filled == 0;
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            const Character* rep = m.representative_chars + m.representative_offsets[r];
            const std::size_t len = m.representative_length(r);
            const std::size_t base = first_cell(r);
            if (window_is_a1(r)) {
                // The new character is row i; the stored row holds D[i−1][·].
                detail::Cell diagonal = load(slot, base);
                detail::Cell left = detail::dp_col0(m.variant, w(c, rep[0]));
                store(slot, base, left);
                for (std::size_t j = 1; j <= len; ++j) {
                    const detail::Cell above = load(slot, base + j);
                    left = detail::dp_step(diagonal, above, left, w(c, rep[j - 1]));
                    diagonal = above;
                    store(slot, base + j, left);
                }
            } else {
                // The new character is column j; the stored column holds D[·][j−1].
                if (first) {
                    store(slot, base, detail::dp_origin());
                    for (std::size_t i = 1; i <= len; ++i)
                        store(slot, base + i, detail::dp_col0(m.variant, w(rep[i - 1], c)));
                }
                detail::Cell diagonal = load(slot, base);
                detail::Cell above = detail::dp_row0(m.variant);
                store(slot, base, above);
                for (std::size_t i = 1; i <= len; ++i) {
                    const detail::Cell left = load(slot, base + i);
                    above = detail::dp_step(diagonal, above, left, w(rep[i - 1], c));
                    diagonal = left;
                    store(slot, base + i, above);
                }
                if (m.variant == MatchVariant::subsequence) {
                    const float score = detail::dp_score(above, m.normalization, m.window_chars);
                    if (score < best_[slot][r]) best_[slot][r] = score;
                }
            }
        }
    }

    void finish(std::size_t slot) noexcept {
        const ModelView& m = *model_;
        for (std::size_t r = 0; r < m.representative_count; ++r) {
            const std::size_t len = m.representative_length(r);
            const std::size_t base = first_cell(r);
            if (m.variant == MatchVariant::subsequence && window_is_a1(r)) {
                float best = detail::infinity();
                for (std::size_t j = 1; j <= len; ++j) {
                    const float score = detail::dp_score(load(slot, base + j), m.normalization, m.window_chars);
                    if (score < best) best = score;
                }
                completed_[r] = best;
            } else if (m.variant == MatchVariant::subsequence) {
                completed_[r] = best_[slot][r];
            } else {
                completed_[r] = detail::dp_score(load(slot, base + len), m.normalization, m.window_chars);
            }
        }
    }

    const ModelView* model_ = nullptr;
    std::size_t open_slots_ = 0;
    std::uint64_t pushed_ = 0;
    std::uint64_t completed_start_ = 0;
    bool has_completed_ = false;
    Window windows_[Cap::max_windows] = {};
    float costs_[Cap::max_windows][Cap::cells_per_window] = {};
    std::uint16_t paths_[path_slots][path_cells] = {};
    float best_[Cap::max_windows][Cap::max_representatives] = {};
    float completed_[Cap::max_representatives] = {};
};

}  // namespace actionstring
