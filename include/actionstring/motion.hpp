// actionstring — stage 1b: the pose's velocity (design.md §1.1).
//
// A static pose cannot tell raising an arm from lowering it. With motion, the
// input to the projection is the normalised pose followed by its velocity,
// weighted: w · (x(t) − x(t − a)) / a, where the earlier pose is the one in a
// short ring whose age a is nearest to the model's span (and at least half of
// it). The ring keeps a pose every span / 4 of stream time, so the velocity is
// measured over time, not frames: frame rate, jitter and dropped frames leave
// it unchanged. Until the ring holds a pose old enough (a stream's first half
// span) the velocity is 0. Each component is clamped to ±max_pose_coordinate,
// the bound the GMM's overflow check assumes for every input.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/capacity.hpp"
#include "actionstring/model.hpp"
#include "actionstring/normalize.hpp"

namespace actionstring {

/// Recent poses of one stream, for the velocity. Storage fixed by `Cap`
/// (Cap::motion_ring poses; one when the limits have no motion).
template <class Cap>
class MotionRing {
public:
    /// Forgets the stream (call when it restarts).
    void reset() noexcept {
        count_ = 0;
        next_ = 0;
    }

    /// Writes the velocity of the pose in `input[0, D)` at `time_us` into
    /// `input[D, 2 D)` (D = model.pose_dim()), then keeps the pose if a
    /// quarter span has passed since the last one kept. The model must have
    /// motion and fit Cap (the encoder checked both).
    void update(const ModelView& model, std::int64_t time_us, float* input) noexcept {
        const std::size_t D = model.pose_dim();
        const std::int64_t span = model.velocity_span_us;
        // The kept pose whose age is nearest the span, among those at least half a span old.
        std::size_t best = Cap::motion_ring;
        std::int64_t best_error = 0;
        for (std::size_t k = 0; k < count_; ++k) {
            const std::int64_t age = time_us - times_[k];
            if (age < span / 2) continue;
            const std::int64_t error = age > span ? age - span : span - age;
            if (best == Cap::motion_ring || error < best_error) best = k, best_error = error;
        }
        float* velocity = input + D;
        if (best == Cap::motion_ring) {
            for (std::size_t i = 0; i < D; ++i) velocity[i] = 0.0f;
        } else {
            const float per_second = model.velocity_weight / (static_cast<float>(time_us - times_[best]) * 1.0e-6f);
            for (std::size_t i = 0; i < D; ++i) {
                const float v = (input[i] - poses_[best][i]) * per_second;
                velocity[i] = v > max_pose_coordinate    ? max_pose_coordinate
                              : v < -max_pose_coordinate ? -max_pose_coordinate
                                                         : v;
            }
        }
        const std::size_t newest = next_ == 0 ? Cap::motion_ring - 1 : next_ - 1;
        if (count_ == 0 || time_us - times_[newest] >= span / 4) {
            for (std::size_t i = 0; i < D; ++i) poses_[next_][i] = input[i];
            times_[next_] = time_us;
            next_ = next_ + 1 == Cap::motion_ring ? 0 : next_ + 1;
            if (count_ < Cap::motion_ring) ++count_;
        }
    }

private:
    float poses_[Cap::motion_ring][Cap::max_pose_dim] = {};
    std::int64_t times_[Cap::motion_ring] = {};
    std::size_t count_ = 0;
    std::size_t next_ = 0;
};

}  // namespace actionstring
