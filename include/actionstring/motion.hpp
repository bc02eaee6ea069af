// actionstring — stage 1b: the pose's motion (design.md §1.1).
//
// A static pose cannot tell raising an arm from lowering it. With motion, the
// input to the projection is the normalised pose followed by its velocity,
// weighted: w · (x(t) − x(t − a)) / a, where the earlier pose is the one in a
// short ring whose age a is nearest to the model's span (and at least half of
// it); and, with acceleration, by how much that velocity changed across the
// span, weighted: w' · ((x(t) − x(t − b)) / b − (x(t − b) − x(t − a)) / (a − b)),
// the velocity over the span's newer part minus that over its older part,
// where x(t − b) is the kept pose whose age b is nearest a / 2 (between a / 4
// and 3a / 4). That is the acceleration times about a / 2, in m/s like the
// velocity, so the two weights compare. The ring keeps a pose every span / 4
// of stream time, so motion is measured over time, not frames: frame rate,
// jitter and dropped frames leave it unchanged, and uneven ages are divided
// out exactly. Until the ring holds a pose old enough (a stream's first half
// span) the motion is 0. Each component is clamped to ±max_pose_coordinate,
// the bound the GMM's overflow check assumes for every input.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "actionstring/model.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"

namespace actionstring {

/// Poses the ring keeps: a pose every quarter span, so the one nearest the
/// span is always within reach.
constexpr std::size_t motion_ring_poses = 6;

/// The pose speed (metres per second: the mean over the normalised pose's
/// coordinates of how fast each moved since the previous frame) beyond which
/// a stream's pose is taken to have jumped rather than moved
/// (AnnotatorConfig::max_pose_speed). Within HDM05's clips the mean speed
/// stays under 1.2 m/s (99.9th percentile, frame to frame, at most 3.3);
/// joining one actor's clips moves it faster than 5 m/s in half of the
/// joinings, and a tracker that loses and finds the body does too. A jump is
/// a distance, so the speed it shows falls with the frame rate: joined clips
/// at 30 Hz move about a quarter as fast as at 120 Hz, and 8 m/s missed most
/// joinings there (HDM05's folds resampled to 30 Hz settled 0.05 fewer
/// frames). Chosen on the training subjects' online folds of every config in
/// models/ (models/README.md, "Jumps in a stream" and "The jump bound at any
/// frame rate"): at the lists' own rates 3 to 8 m/s tie, and at 15 and 30 Hz
/// 3 m/s keeps what 120 Hz gets.
constexpr float default_max_pose_speed = 3.0f;

/// How many times the stream's typical frame-to-frame change a jump must be
/// as well: a noisy sensor at a high frame rate (3 cm of noise at 120 Hz)
/// changes every frame fast, by about the same amount each frame, and none
/// of those frames is a jump. Twice lets noise through on the
/// training subjects' folds; three times does not.
constexpr float jump_over_typical = 3.0f;

/// Whether a stream's pose jumped from one frame to the next: the pose moved
/// faster than the bound (the mean over its coordinates of each one's change,
/// per second), and by more than jump_over_typical times the stream's typical
/// change per frame. Across a jump a difference is no motion, so the encoder
/// then starts the motion again (MotionRing::reset()), as at a stream's start,
/// and as each training clip started. The speed is judged over the longer of
/// the frame's interval and the stream's typical one (a running mean of its
/// intervals), so a frame that a jittery clock brought close to the last one
/// does not look fast. The mean over the coordinates, unlike the largest,
/// averages a noisy sensor's errors out and costs no branch per coordinate.
class JumpCheck {
public:
    /// The bound in metres per second (0: no pose ever jumps); forgets the stream.
    void configure(float max_speed) noexcept {
        max_speed_ = max_speed;
        reset();
    }
    /// Forgets the stream's typical interval and change (another stream, another clock).
    void reset() noexcept {
        interval_s_ = 0.0f;
        typical_ = 0.0f;
        seen_ = false;
    }

    /// Whether `pose` (D floats, `step_us` after `previous`) jumped from
    /// `previous`. Steps of 0 (one instant) judge nothing; the first step
    /// judged sets the typical change and is never a jump.
    bool jumped(std::int64_t step_us, const float* pose, const float* previous, std::size_t D) noexcept {
        if (step_us <= 0 || max_speed_ <= 0.0f || D == 0) return false;
        const float step_s = static_cast<float>(step_us) * 1.0e-6f;
        interval_s_ = interval_s_ == 0.0f ? step_s : interval_s_ + (step_s - interval_s_) * 0.125f;
        float change = 0.0f;
        for (std::size_t i = 0; i < D; ++i) change += std::fabs(pose[i] - previous[i]);
        change /= static_cast<float>(D);
        if (!seen_) {
            seen_ = true;
            typical_ = change;
            return false;
        }
        const float bound = max_speed_ * (step_s > interval_s_ ? step_s : interval_s_);
        const bool jump = change > bound && change > jump_over_typical * typical_;
        // The typical change follows the stream slowly (a jump does not move it).
        if (!jump) typical_ += (change - typical_) * 0.03125f;
        return jump;
    }

private:
    float max_speed_ = 0.0f;
    float interval_s_ = 0.0f;  // the typical interval, 0 until a step is seen
    float typical_ = 0.0f;     // the typical change per frame (mean over the coordinates)
    bool seen_ = false;        // a step was judged: typical_ is set
};

/// Recent poses of one stream, for its motion. Works in caller-owned
/// storage (storage.hpp) of required_bytes(model) bytes: none for a model
/// without motion.
class MotionRing {
public:
    static constexpr std::size_t required_bytes(const ModelView& model) noexcept { return plan(model).bytes; }

    /// Binds the storage for a model's pose length (the model must have
    /// motion for update() to be called). Returns storage_too_small or ok.
    Status init(const ModelView& model, void* storage, std::size_t bytes) noexcept {
        poses_ = nullptr;
        const Plan p = plan(model);
        if (p.bytes == 0) return Status::ok;
        if (!detail::storage_fits(storage, bytes, p.bytes)) return Status::storage_too_small;
        detail::clear_storage(storage, p.bytes);
        poses_ = detail::storage_at<float>(storage, p.poses);
        times_ = detail::storage_at<std::int64_t>(storage, p.times);
        pose_dim_ = model.pose_dim();
        reset();
        return Status::ok;
    }

    /// Forgets the stream (call when it restarts).
    void reset() noexcept {
        count_ = 0;
        next_ = 0;
    }

    /// Writes the motion of the pose in `input[0, D)` at `time_us` after it
    /// (D = model.pose_dim(); the velocity in `input[D, 2 D)` if the model has
    /// it, then the acceleration in the next D if the model has it), then
    /// keeps the pose if a quarter span has passed since the last one kept:
    /// motion() and keep() in one call. The model must have motion and be the
    /// one given to init().
    void update(const ModelView& model, std::int64_t time_us, float* input) noexcept {
        motion(model, time_us, input);
        keep(model, time_us, input);
    }

    /// Writes the motion of the pose in `input[0, D)` at `time_us` after it
    /// (as update()) from the poses kept so far; changes nothing kept.
    ///
    /// A frame's motion may be asked for after keep() of that frame (and of
    /// no later one) with the same result, bit for bit: the pose just kept is
    /// 0 s old, younger than half a span and than a quarter of the earliest
    /// pose's age, so it is never chosen; and the pose it replaced, the oldest
    /// of a full ring, never is either (poses are kept at least a quarter span
    /// apart, so the next oldest is at least a span old, younger, and so
    /// nearer to the span; the middle pose is younger than the earliest one
    /// used). The encoder relies on this to take the motion only of frames
    /// whose character is asked for.
    void motion(const ModelView& model, std::int64_t time_us, float* input) const noexcept {
        const std::size_t D = pose_dim_;
        const std::int64_t span = model.velocity_span_us;
        // The kept pose whose age is nearest the span, among those at least half a span old.
        const std::size_t earliest = nearest(time_us, span, span / 2, std::numeric_limits<std::int64_t>::max());
        float* out = input + D;
        if (model.has_velocity()) {
            if (earliest == motion_ring_poses) {
                zero(out, D);
            } else {
                const float* earlier = poses_ + earliest * D;
                const float per_second =
                    model.velocity_weight / (static_cast<float>(time_us - times_[earliest]) * 1.0e-6f);
                for (std::size_t i = 0; i < D; ++i) out[i] = bounded((input[i] - earlier[i]) * per_second);
            }
            out += D;
        }
        if (model.has_acceleration()) {
            // The middle pose: age nearest half the earliest's, between a quarter and three quarters of it.
            const std::int64_t a = earliest == motion_ring_poses ? 0 : time_us - times_[earliest];
            const std::size_t middle =
                earliest == motion_ring_poses ? motion_ring_poses : nearest(time_us, a / 2, a / 4, a - a / 4);
            if (middle == motion_ring_poses) {
                zero(out, D);
            } else {
                const std::int64_t b = time_us - times_[middle];
                const float* first = poses_ + earliest * D;
                const float* second = poses_ + middle * D;
                const float newer = model.acceleration_weight / (static_cast<float>(b) * 1.0e-6f);
                const float older = model.acceleration_weight / (static_cast<float>(a - b) * 1.0e-6f);
                for (std::size_t i = 0; i < D; ++i)
                    out[i] = bounded((input[i] - second[i]) * newer - (second[i] - first[i]) * older);
            }
        }
    }

    /// Keeps the pose in `input[0, D)` at `time_us` if a quarter span has
    /// passed since the last one kept (call it for every accepted frame).
    void keep(const ModelView& model, std::int64_t time_us, const float* input) noexcept {
        const std::size_t D = pose_dim_;
        const std::int64_t span = model.velocity_span_us;
        const std::size_t newest = next_ == 0 ? motion_ring_poses - 1 : next_ - 1;
        if (count_ == 0 || time_us - times_[newest] >= span / 4) {
            float* kept = poses_ + next_ * D;
            for (std::size_t i = 0; i < D; ++i) kept[i] = input[i];
            times_[next_] = time_us;
            next_ = next_ + 1 == motion_ring_poses ? 0 : next_ + 1;
            if (count_ < motion_ring_poses) ++count_;
        }
    }

private:
    // The kept pose whose age is nearest `target` among those aged from `low`
    // to `high` (the first such in ring order on a tie), or motion_ring_poses.
    std::size_t nearest(std::int64_t time_us, std::int64_t target, std::int64_t low, std::int64_t high) const noexcept {
        std::size_t best = motion_ring_poses;
        std::int64_t best_error = 0;
        for (std::size_t k = 0; k < count_; ++k) {
            const std::int64_t age = time_us - times_[k];
            if (age < low || age > high) continue;
            const std::int64_t error = age > target ? age - target : target - age;
            if (best == motion_ring_poses || error < best_error) best = k, best_error = error;
        }
        return best;
    }
    static void zero(float* out, std::size_t n) noexcept {
        for (std::size_t i = 0; i < n; ++i) out[i] = 0.0f;
    }
    // One comparison for the usual case, within the bound (a Cortex-M4 then
    // skips two compare-and-selects per value).
    static float bounded(float v) noexcept {
        if (!(std::fabs(v) <= max_pose_coordinate))
            v = v > max_pose_coordinate ? max_pose_coordinate : v < -max_pose_coordinate ? -max_pose_coordinate : v;
        return v;
    }

    struct Plan {
        std::size_t poses = 0, times = 0, bytes = 0;
    };
    static constexpr Plan plan(const ModelView& model) noexcept {
        Plan p;
        if (!model.has_motion()) return p;
        detail::StorageLayout layout;
        p.poses = layout.add<float>(motion_ring_poses * model.pose_dim());
        p.times = layout.add<std::int64_t>(motion_ring_poses);
        p.bytes = layout.bytes();
        return p;
    }

    float* poses_ = nullptr;  // motion_ring_poses × D
    std::int64_t* times_ = nullptr;
    std::size_t pose_dim_ = 0;
    std::size_t count_ = 0;
    std::size_t next_ = 0;
};

}  // namespace actionstring
