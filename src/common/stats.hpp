// actionstring host library — order statistics.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace actionstring {
namespace host {

/// The element at rank ⌊size/2⌋ (the upper median); 0 for no values.
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

/// The q-quantile of sorted values by rank ⌊q·size⌋ (clamped); 0 for no values.
inline double sorted_quantile(const std::vector<double>& sorted, double q) {
    if (sorted.empty()) return 0.0;
    const auto rank = static_cast<std::size_t>(q * static_cast<double>(sorted.size()));
    return sorted[std::min(sorted.size() - 1, rank)];
}

}  // namespace host
}  // namespace actionstring
