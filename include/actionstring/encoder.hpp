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
#include "actionstring/storage.hpp"
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
    /// The features (feature_dim floats: the projected pose) `previous` and
    /// `current` were made from, null when not emitted. Owned by the encoder,
    /// valid until the next push_frame(); for exemplars.hpp.
    const float* previous_feature = nullptr;
    const float* current_feature = nullptr;

    std::uint32_t count() const noexcept { return from_previous + from_current; }
    bool accepted() const noexcept { return status == Status::ok || status == Status::stream_restarted; }
};

/// Stream timing of an encoder (AnnotatorConfig carries the same two).
struct EncoderConfig {
    /// A longer gap between accepted frames restarts the stream.
    std::int64_t max_gap_us = 1000000;
    /// A frame this much earlier than the last one or less is rejected;
    /// further back the stream restarts.
    std::int64_t max_backward_us = 100000;
};

/// Frame-to-character encoder; needs only the feature tables of the model.
/// Works in caller-owned storage of required_bytes(model) bytes (storage.hpp).
/// Keeps pointers to the ModelView given to init() and to the storage: both
/// must outlive the encoder (or its next init()).
class StringEncoder {
public:
    /// Bytes of storage init() needs for this model (constexpr when the model is).
    static constexpr std::size_t required_bytes(const ModelView& model, const EncoderConfig& = {}) noexcept {
        return plan(model).bytes;
    }

    /// @return ok, invalid_model (tables, or precision factors that could
    ///         overflow float), storage_too_small, or invalid_argument
    ///         (times StringSampler::settings_ok() refuses for the model's period)
    Status init(const ModelView& model, const EncoderConfig& config, void* storage, std::size_t bytes) noexcept {
        model_ = nullptr;
        const Status status = validate_feature_tables(model);
        if (status != Status::ok) return status;
        if (model.has_gmm() && !gmm_is_overflow_safe(model, max_pose_coordinate)) return Status::invalid_model;
        if (!StringSampler::settings_ok(model.string_period_us, config.max_gap_us, config.max_backward_us))
            return Status::invalid_argument;
        const Plan p = plan(model);
        if (!detail::storage_fits(storage, bytes, p.bytes)) return Status::storage_too_small;
        detail::clear_storage(storage, p.bytes);
        poses_[0] = detail::storage_at<float>(storage, p.poses);
        poses_[1] = poses_[0] + model.input_dim();
        skeleton_ = detail::storage_at<float>(storage, p.skeleton);
        features_[0] = detail::storage_at<float>(storage, p.feature);
        features_[1] = features_[0] + (model.has_projection() ? model.feature_dim : 0u);
        posterior_ = detail::storage_at<float>(storage, p.posterior);
        scratch_ = detail::storage_at<float>(storage, p.scratch);
        norms_ = detail::storage_at<float>(storage, p.norms);
        nonzero_ = detail::storage_at<std::uint16_t>(storage, p.nonzero);
        if (model.has_gmm()) tree_node_norms(model, norms_);  // the sparse descent's (tree.hpp)
        const Status motion = motion_.init(model, detail::storage_at<unsigned char>(storage, p.motion),
                                           MotionRing::required_bytes(model));
        if (motion != Status::ok) return motion;
        model_ = &model;
        sampler_.configure(model.string_period_us, config.max_gap_us, config.max_backward_us);
        reset();
        return Status::ok;
    }

    /// Starts another stream from scratch.
    void reset() noexcept {
        sampler_.reset();
        motion_.reset();
        has_previous_ = false;
        last_ = 0;
        most_probable_ = 0;
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
        out.status =
            normalize_pose(*model_, positions, poses_[current], uses_bones(model_->scale_mode) ? skeleton_ : nullptr);
        if (out.status != Status::ok) return out;
        const SamplePlan plan = sampler_.advance(time_us);
        out.status = plan.status;
        if (plan.status == Status::time_went_backwards) return out;
        ready_[current] = false;
        if (model_->has_motion()) {
            // The motion only of the frames whose character is due, and
            // before this frame's pose is kept (motion.hpp: the previous
            // frame's motion taken now, after its own keep(), is the same).
            if (plan.status == Status::stream_restarted) motion_.reset();
            times_[current] = time_us;
            if (plan.from_previous > 0 && !ready_[previous_])
                motion_.motion(*model_, times_[previous_], poses_[previous_]);
            if (plan.from_current > 0) motion_.motion(*model_, time_us, poses_[current]);
            motion_.keep(*model_, time_us, poses_[current]);
        }
        if (plan.from_previous > 0) {
            out.previous = character(previous_);
            out.from_previous = plan.from_previous;
            out.previous_feature = feature(previous_);
        }
        if (plan.from_current > 0) {
            out.current = character(current);
            out.from_current = plan.from_current;
            out.current_feature = feature(current);
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
    // The slot's feature: its projected pose, or without a projection the pose itself.
    const float* feature(std::size_t slot) const noexcept {
        return model_->has_projection() ? features_[slot] : poses_[slot];
    }

    Character character(std::size_t slot) noexcept {
        if (ready_[slot]) return characters_[slot];
        if (model_->has_projection()) project_pose(*model_, poses_[slot], features_[slot]);
        const float* feature = this->feature(slot);
        // Cannot fail: normalize_pose bounded the pose and init() checked that
        // no bounded pose overflows the GMM. Should it ever, repeat the last
        // character rather than invent one.
        if (!model_->has_gmm()) last_ = descend_tree(*model_, feature);
        else if (gmm_posterior(*model_, feature, posterior_, scratch_, nullptr, &most_probable_) == Status::ok)
            last_ = descend_tree_sparse(*model_, posterior_, norms_, nonzero_);
        characters_[slot] = last_;
        ready_[slot] = true;
        return last_;
    }

    struct Plan {
        std::size_t poses = 0, skeleton = 0, feature = 0, posterior = 0, scratch = 0, norms = 0, nonzero = 0, motion = 0,
                    bytes = 0;
    };
    static constexpr Plan plan(const ModelView& m) noexcept {
        detail::StorageLayout layout;
        Plan p;
        p.poses = layout.add<float>(2 * m.input_dim());  // this frame's and the last one's
        p.skeleton = layout.add<float>(uses_bones(m.scale_mode) ? 3u * m.joint_count : 0u);
        p.feature = layout.add<float>(m.has_projection() ? 2u * m.feature_dim : 0u);  // a slot's each
        p.posterior = layout.add<float>(m.component_count);
        p.scratch = layout.add<float>(gmm_scratch_floats(m));
        p.norms = layout.add<float>(m.has_gmm() ? tree_norm_floats(m) : 0u);  // the sparse descent is for posteriors
        p.nonzero = layout.add<std::uint16_t>(m.has_gmm() ? m.component_count : 0u);
        p.motion = layout.add<unsigned char>(MotionRing::required_bytes(m));
        p.bytes = layout.bytes();
        return p;
    }

    const ModelView* model_ = nullptr;
    StringSampler sampler_;
    float* poses_[2] = {};  // input_dim() floats each: the pose, then with motion its velocity and acceleration
    MotionRing motion_;
    float* skeleton_ = nullptr;  // the rebuilt skeleton (bone-length scaling)
    Character characters_[2] = {};
    bool ready_[2] = {};          // the slot's character (and its motion, if any) is computed
    std::int64_t times_[2] = {};  // the slot's frame time (for its motion)
    std::size_t previous_ = 0;
    bool has_previous_ = false;
    Character last_ = 0;
    std::size_t most_probable_ = 0;  // the last posterior's peak: where the next GMM pass starts
    float* features_[2] = {};     // with a projection: each slot's projected pose
    float* posterior_ = nullptr;  // component_count floats
    float* scratch_ = nullptr;    // the GMM's gmm_scratch_floats()
    float* norms_ = nullptr;      // with a GMM: the tree's node norms (tree_node_norms())
    std::uint16_t* nonzero_ = nullptr;  // with a GMM: the posterior's non-zero coordinates
};

}  // namespace actionstring
