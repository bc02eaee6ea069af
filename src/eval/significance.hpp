// actionstring host library — how sure a clip accuracy is: its 95% interval,
// and whether two methods scored on the same clips really differ.
//
// A validation list of 44 clips moves by 0.023 per clip, so "0.955 against
// 0.932" may be one clip of chance. The Wilson score interval states the
// range a method's accuracy on such people is likely in (it stays inside
// [0, 1] and is sound near 0 and 1, where the normal approximation is not).
// Two methods scored on the same clips are compared on the clips where they
// disagree (McNemar's test, exact: under "no difference" each such clip is
// a fair coin), which is far more sensitive than comparing two intervals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace actionstring {
namespace host {

/// A two-sided 95% interval of a proportion.
struct Interval {
    double low = 0.0, high = 1.0;
};

/// The 95% Wilson score interval of `successes` out of `trials`
/// ([0, 1] for no trials).
Interval wilson_interval(std::size_t successes, std::size_t trials);

/// The two-sided exact McNemar p-value of a paired comparison: `only_first`
/// items the first method gets right and the second wrong, `only_second`
/// the reverse. 1 when the two counts differ by at most one.
double mcnemar_exact_p(std::size_t only_first, std::size_t only_second);

/// A 95% percentile bootstrap interval of a ratio of sums, Σ numerator ÷
/// Σ denominator, over items drawn with replacement. For figures whose
/// trials are not independent (a stream's frames within one action, its
/// segments matched against each other) the items are the units that are
/// closer to it: each true action or stretch of no action, with what was
/// scored on it. `draws` resamples from `seed`, so the interval is
/// deterministic; a resample with a zero denominator scores 0. The two
/// vectors have one entry per item; [0, 1] when there is none. It speaks for
/// other actions of the same people: it cannot say how other people differ.
Interval bootstrap_ratio_interval(const std::vector<double>& numerator, const std::vector<double>& denominator,
                                  std::size_t draws = 2000, std::uint32_t seed = 1);

}  // namespace host
}  // namespace actionstring
