// The Wilson interval, the exact McNemar test and the bootstrap of a ratio.
#include "eval/significance.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace actionstring {
namespace host {

namespace {
constexpr double z95 = 1.959963984540054;  // the standard normal's 97.5th percentile
}

Interval wilson_interval(std::size_t successes, std::size_t trials) {
    if (trials == 0) return {};
    const double n = static_cast<double>(trials);
    const double p = static_cast<double>(std::min(successes, trials)) / n;
    const double z2 = z95 * z95;
    const double denominator = 1.0 + z2 / n;
    const double centre = (p + z2 / (2.0 * n)) / denominator;
    const double half = z95 * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n)) / denominator;
    // At 0 and at every trial an end is exactly 0 or 1 (centre and half agree
    // there); say so rather than leave it to rounding.
    const bool none = successes == 0, all = successes >= trials;
    return {none ? 0.0 : std::max(0.0, centre - half), all ? 1.0 : std::min(1.0, centre + half)};
}

double mcnemar_exact_p(std::size_t only_first, std::size_t only_second) {
    const std::size_t n = only_first + only_second;
    const std::size_t k = std::min(only_first, only_second);
    // With the smaller count at least (n − 1) / 2 the tail holds half the
    // mass or more, so p is 1 exactly (rather than 1 less rounding).
    if (2 * k + 1 >= n) return 1.0;
    // P(X ≤ k) for X ~ Binomial(n, 1/2), term by term in logarithms so that
    // thousands of disagreements neither overflow nor underflow to nonsense.
    const double log_half_n = -static_cast<double>(n) * std::log(2.0);
    const double log_n_factorial = std::lgamma(static_cast<double>(n) + 1.0);
    double tail = 0.0;
    for (std::size_t i = 0; i <= k; ++i)
        tail += std::exp(log_n_factorial - std::lgamma(static_cast<double>(i) + 1.0) -
                         std::lgamma(static_cast<double>(n - i) + 1.0) + log_half_n);
    return std::min(1.0, 2.0 * tail);
}

Interval bootstrap_ratio_interval(const std::vector<double>& numerator, const std::vector<double>& denominator,
                                  std::size_t draws, std::uint32_t seed) {
    const std::size_t n = std::min(numerator.size(), denominator.size());
    if (n == 0 || draws == 0) return {};
    // mt19937's outputs are fixed by the standard (its distributions are not),
    // so the draws, and the interval, are the same on every platform.
    std::mt19937 engine(seed);
    std::vector<double> ratios(draws);
    for (double& ratio : ratios) {
        double top = 0.0, bottom = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const auto pick = static_cast<std::size_t>((static_cast<std::uint64_t>(engine()) * n) >> 32);
            top += numerator[pick];
            bottom += denominator[pick];
        }
        ratio = bottom > 0.0 ? top / bottom : 0.0;
    }
    std::sort(ratios.begin(), ratios.end());
    const double last = static_cast<double>(draws - 1);
    return {ratios[static_cast<std::size_t>(std::lround(0.025 * last))],
            ratios[static_cast<std::size_t>(std::lround(0.975 * last))]};
}

}  // namespace host
}  // namespace actionstring
