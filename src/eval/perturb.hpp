// actionstring host library — evaluated clips as another sensor or person
// would give them: the shifts `actionstring eval --perturb` applies.
#pragma once

#include <cstdint>
#include <string>

#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// One known way in which recordings differ from the shared datasets'. The
/// evaluated clips (never the training clips) are changed this way, so a
/// model's accuracy under the shift can be read beside the baselines' on the
/// same changed clips. Each field at its default changes nothing.
///
/// Applied in this order: resampling, mirroring, tilt, scale, noise,
/// timestamp jitter, dropped frames.
struct Perturbation {
    /// The performance done with the other side of the body (a left-handed
    /// performer where the training ones were right-handed): each clip
    /// mirrored as training's `mirror` setting mirrors (train/augment.hpp).
    /// It keeps the clip's label, so it measures only data whose classes are
    /// not lateral (not HDM05's grabHighR, depositFloorR, …).
    bool mirror = false;
    /// Degrees by which the performer is seen tilted: a sensor mounted higher
    /// or lower, pitched to keep them in view. Every tracked frame turns by
    /// this angle (right-handed) about the horizontal line through the clip's
    /// mean root position along its mean horizontal hip direction (right −
    /// left), so a performer facing the sensor turns about the sensor's own
    /// horizontal axis. The model's facing normalisation turns about the up
    /// axis only, so this is a shift it does not undo.
    double tilt_deg = 0.0;
    /// Every position times this, about the sensor's origin: a smaller or
    /// larger person (0.7 is a child of 1.2 m beside an adult of 1.75 m).
    double scale = 1.0;
    /// Standard deviation of Gaussian noise added to each coordinate of each
    /// tracked frame, metres (sensor jitter; Kinect v1 is about 0.01).
    double noise_m = 0.0;
    /// Probability that a frame other than the first and last is missing
    /// (dropped frames; the timestamps keep their gaps).
    double drop = 0.0;
    /// Resample to this frame rate by linear interpolation between frames
    /// (another sensor's rate); 0 keeps the clip's frames. A resampled frame
    /// next to a lost one is lost.
    double rate_hz = 0.0;
    /// Each timestamp moved by a uniform amount within ± this many seconds,
    /// then kept in order (a clock with jitter).
    double jitter_s = 0.0;
    /// Seeds the noise, jitter and drops; each clip also mixes in its own index.
    std::uint64_t seed = 1;

    /// Whether any field changes a clip.
    bool any() const noexcept;
    /// The fields that change something, e.g. "scale 0.7, noise 0.01 m"; "none".
    std::string describe() const;
};

/// Reads "name=value,…" with the names scale, mirror (0 or 1), tilt (degrees),
/// noise (metres), drop, rate (Hz), jitter (seconds) and seed. Throws std::invalid_argument naming the item
/// and what was expected when one is unknown, repeated, not a number or out
/// of range.
Perturbation parse_perturbation(const std::string& spec);

/// Changes `clip` as `p` says. `index` tells clips apart (their list order),
/// so each gets its own noise; the same p, index and clip give the same result.
void perturb_clip(Clip& clip, const Perturbation& p, std::uint64_t index);

}  // namespace host
}  // namespace actionstring
