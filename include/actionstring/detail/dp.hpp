// actionstring — the cell rule of the string distance DP (paper eq. 7), shared
// by the batch reference and the incremental matcher so both resolve ties alike.
#pragma once

#include <cstdint>

#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {
namespace detail {

/// Accumulated cost of a DP cell and the length of the warping path reaching it.
struct Cell {
    float cost;
    std::uint32_t path;
};

/// D[i][j] = min(D[i−1][j−1], D[i−1][j], D[i][j−1]) + w. On equal costs the
/// diagonal wins, then the cell above (i−1, j), then the one to the left.
inline Cell dp_step(Cell diagonal, Cell above, Cell left, float weight) noexcept {
    Cell best = diagonal;
    if (above.cost < best.cost) best = above;
    if (left.cost < best.cost) best = left;
    return Cell{best.cost + weight, best.path + 1u};
}

/// The cost of dp_step() alone, with the same comparisons in the same order
/// (so equal values, signed zeros included, resolve identically), written as
/// selects so that a loop over independent lanes vectorises.
inline float dp_step_cost(float diagonal, float above, float left, float weight) noexcept {
    float best = diagonal;
    best = above < best ? above : best;
    best = left < best ? left : best;
    return best + weight;
}

/// D[0][0] for every variant.
constexpr Cell dp_origin() noexcept { return Cell{0.0f, 0u}; }

/// D[0][j], j ≥ 1: 0 under the paper's boundaries and subsequence (the start is unconstrained), blocked for whole.
inline Cell dp_row0(MatchVariant variant) noexcept {
    return variant == MatchVariant::whole ? Cell{infinity(), 0u} : Cell{0.0f, 0u};
}

/// D[i][0], i ≥ 1: W[A1(i)][A2(1)] for the paper's boundaries (one aligned
/// pair), blocked otherwise.
inline Cell dp_col0(MatchVariant variant, float weight_with_first_of_a2) noexcept {
    return variant == MatchVariant::paper ? Cell{weight_with_first_of_a2, 1u} : Cell{infinity(), 0u};
}

/// Final score of a cell after the chosen length normalisation.
inline float dp_score(Cell cell, LengthNormalization normalization, std::uint32_t query_length) noexcept {
    switch (normalization) {
        case LengthNormalization::path:
            return cell.cost / static_cast<float>(cell.path);
        case LengthNormalization::query:
            return cell.cost / static_cast<float>(query_length);
        case LengthNormalization::none:
            break;
    }
    return cell.cost;
}

}  // namespace detail
}  // namespace actionstring
