// actionstring — stages 1–5 together: timestamped frames in, characters out.
//
// normalise → (only when a string tick takes its character from the frame)
// project → GMM posterior → tree descent. Ticks fall at a fixed rate in time
// (sampler.hpp); the posterior is skipped for frames no tick lands nearest to,
// so most frames cost one normalisation. The trainer turns clips into strings
// with this same class.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/gmm.hpp"
#include "actionstring/model.hpp"
#include "actionstring/motion.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/projection.hpp"
#include "actionstring/sampler.hpp"
#include "actionstring/status.hpp"
#include "actionstring/tree.hpp"

namespace actionstring {

/// Characters one frame appends to the string: `from_previous` copies of
/// `previous`, then `from_current` copies of `current`.
struct EncodedFrame {
    /// ok or stream_restarted when the frame was accepted, otherwise why it was
    /// rejected (non_finite_input, tracking_lost, degenerate_pose,
    /// pose_out_of_range, time_went_backwards, not_initialized,
    /// invalid_argument). A rejected frame changes nothing.
    Status status = Status::ok;
    Character previous = 0;
    std::uint32_t from_previous = 0;
    Character current = 0;
    std::uint32_t from_current = 0;

    std::uint32_t count() const noexcept { return from_previous + from_current; }
    bool accepted() const noexcept { return status == Status::ok || status == Status::stream_restarted; }
};

/// Frame-to-character encoder. Storage fixed by `Cap` (capacity.hpp); needs
/// only the feature tables of the model. Keeps a pointer to the ModelView
/// given to init(): it must outlive the encoder (or the next init()).
template <class Cap>
class StringEncoder {
public:
    /// @param max_gap_us      a longer gap between accepted frames restarts the stream
    /// @param max_backward_us a frame this much earlier than the last one or less
    ///                        is rejected; further back the stream restarts
    /// @return ok, invalid_model (tables, or precision factors that could
    ///         overflow float), model_exceeds_capacity, or invalid_argument
    ///         (times StringSampler::settings_ok() refuses for the model's period)
    Status init(const ModelView& model, std::int64_t max_gap_us, std::int64_t max_backward_us) noexcept {
        model_ = nullptr;
        const Status status = validate_feature_tables(model);
        if (status != Status::ok) return status;
        if (!Cap::fits_features(model)) return Status::model_exceeds_capacity;
        if (model.has_gmm() && !gmm_is_overflow_safe(model, max_pose_coordinate)) return Status::invalid_model;
        if (!StringSampler::settings_ok(model.string_period_us, max_gap_us, max_backward_us))
            return Status::invalid_argument;
        model_ = &model;
        sampler_.configure(model.string_period_us, max_gap_us, max_backward_us);
        reset();
        return Status::ok;
    }

    /// Starts another stream from scratch.
    void reset() noexcept {
        sampler_.reset();
        motion_.reset();
        has_previous_ = false;
        last_ = 0;
    }

    /// Encodes one frame.
    /// @param time_us   capture time in microseconds (any origin, non-decreasing;
    ///                  equal times are one instant and the later frame wins)
    /// @param positions joint_count × 3 floats, xyz per joint in metres; read
    ///                  only during the call
    EncodedFrame push_frame(std::int64_t time_us, const float* positions) noexcept {
        EncodedFrame out;
        if (model_ == nullptr) {
            out.status = Status::not_initialized;
            return out;
        }
        const std::size_t current = has_previous_ ? 1u - previous_ : 0u;
        out.status = normalize_pose(*model_, positions, poses_[current], skeleton_);
        if (out.status != Status::ok) return out;
        const SamplePlan plan = sampler_.advance(time_us);
        out.status = plan.status;
        if (plan.status == Status::time_went_backwards) return out;
        if (model_->has_motion()) {
            if (plan.status == Status::stream_restarted) motion_.reset();
            motion_.update(*model_, time_us, poses_[current]);
        }
        ready_[current] = false;
        if (plan.from_previous > 0) {
            out.previous = character(previous_);
            out.from_previous = plan.from_previous;
        }
        if (plan.from_current > 0) {
            out.current = character(current);
            out.from_current = plan.from_current;
        }
        previous_ = current;
        has_previous_ = true;
        return out;
    }

    /// Time of tick k (character k) of the current stream.
    std::int64_t tick_time_us(std::uint64_t tick) const noexcept { return sampler_.tick_time_us(tick); }
    /// The GMM posterior of the last frame whose character was computed
    /// (component_count floats, owned by the encoder, valid until the next
    /// push_frame(); meaningless for a model without a GMM).
    const float* last_posterior() const noexcept { return posterior_; }
    bool initialized() const noexcept { return model_ != nullptr; }

private:
    Character character(std::size_t slot) noexcept {
        if (ready_[slot]) return characters_[slot];
        const float* feature = poses_[slot];
        if (model_->has_projection()) {
            project_pose(*model_, poses_[slot], feature_);
            feature = feature_;
        }
        // Cannot fail: normalize_pose bounded the pose and init() checked that
        // no bounded pose overflows the GMM. Should it ever, repeat the last
        // character rather than invent one.
        if (!model_->has_gmm()) last_ = descend_tree(*model_, feature);
        else if (gmm_posterior<Cap::max_feature_dim>(*model_, feature, posterior_) == Status::ok)
            last_ = descend_tree(*model_, posterior_);
        characters_[slot] = last_;
        ready_[slot] = true;
        return last_;
    }

    const ModelView* model_ = nullptr;
    StringSampler sampler_;
    float poses_[2][Cap::max_input_dim] = {};  // pose, then with motion its velocity
    MotionRing<Cap> motion_;
    float skeleton_[3 * Cap::max_joints] = {};  // the rebuilt skeleton (bone-length scaling)
    Character characters_[2] = {};
    bool ready_[2] = {};
    std::size_t previous_ = 0;
    bool has_previous_ = false;
    Character last_ = 0;
    float feature_[Cap::max_feature_dim] = {};
    float posterior_[Cap::max_components] = {};
};

}  // namespace actionstring
