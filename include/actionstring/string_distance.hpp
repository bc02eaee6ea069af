// actionstring — batch string distance (design.md §1.6, paper §4.2 eqs. 6–7).
//
// The plain reference: the whole (n+1) × (m+1) matrix, filled row by row. The
// incremental matcher (matcher.hpp) must reproduce its results bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/detail/dp.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// How a distance is computed.
struct MatchOptions {
    MatchVariant variant = MatchVariant::whole;
    LengthNormalization normalization = LengthNormalization::none;
};

/// Cells the batch distance needs for strings of lengths n and m.
constexpr std::size_t string_distance_cells(std::size_t n, std::size_t m) noexcept { return (n + 1) * (m + 1); }

/// Distance between a query string and a reference string.
///
/// As in the paper, A1 is the shorter string and indexes the rows; on equal
/// lengths A1 is the query. Costs are W[A1(i)][A2(j)]. Under
/// MatchVariant::subsequence A1 is matched whole against any contiguous part
/// of A2. LengthNormalization::query divides by the query's length whichever
/// string is A1.
///
/// @param workspace  string_distance_cells(n, m) cells (caller-owned, scratch)
/// @param distance   receives the distance on Status::ok
/// @return ok, or invalid_argument for empty strings, null pointers, a
///         character outside W, or strings too long for path lengths
inline Status string_distance(const Character* query, std::size_t query_length, const Character* reference,
                              std::size_t reference_length, CharacterWeights weights, MatchOptions options,
                              detail::Cell* workspace, float* distance) noexcept {
    if (query == nullptr || reference == nullptr || workspace == nullptr || distance == nullptr ||
        weights.values == nullptr || query_length == 0 || reference_length == 0 ||
        query_length + reference_length > 0xFFFFu)
        return Status::invalid_argument;
    for (std::size_t i = 0; i < query_length; ++i)
        if (query[i] >= weights.character_count) return Status::invalid_argument;
    for (std::size_t j = 0; j < reference_length; ++j)
        if (reference[j] >= weights.character_count) return Status::invalid_argument;

    const bool query_is_a1 = query_length <= reference_length;
    const Character* a1 = query_is_a1 ? query : reference;
    const Character* a2 = query_is_a1 ? reference : query;
    const std::size_t n = query_is_a1 ? query_length : reference_length;
    const std::size_t m = query_is_a1 ? reference_length : query_length;
    const std::size_t stride = m + 1;
    auto at = [&](std::size_t i, std::size_t j) -> detail::Cell& { return workspace[i * stride + j]; };

    at(0, 0) = detail::dp_origin();
    for (std::size_t j = 1; j <= m; ++j) at(0, j) = detail::dp_row0(options.variant);
    for (std::size_t i = 1; i <= n; ++i) {
        at(i, 0) = detail::dp_col0(options.variant, weights(a1[i - 1], a2[0]));
        for (std::size_t j = 1; j <= m; ++j)
            at(i, j) = detail::dp_step(at(i - 1, j - 1), at(i - 1, j), at(i, j - 1), weights(a1[i - 1], a2[j - 1]));
    }

    const auto query_len = static_cast<std::uint32_t>(query_length);
    if (options.variant != MatchVariant::subsequence) {
        *distance = detail::dp_score(at(n, m), options.normalization, query_len);
        return Status::ok;
    }
    float best = detail::infinity();
    for (std::size_t j = 1; j <= m; ++j) {
        const float score = detail::dp_score(at(n, j), options.normalization, query_len);
        if (score < best) best = score;
    }
    *distance = best;
    return Status::ok;
}

}  // namespace actionstring
