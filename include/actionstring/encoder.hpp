// actionstring — stages 1–5 together: timestamped frames in, characters out.
//
// normalise → (only when a string tick takes its character from the frame)
// project → GMM posterior → tree descent. Ticks fall at a fixed rate in time
// (sampler.hpp); the posterior is skipped for frames no tick lands nearest to,
// so most frames cost one normalisation. The trainer turns clips into strings
// with this same class. With EncoderConfig::deferred the same stages can run
// later, a little at a time, on a copy of the pose (accept_frame(), defer(),
// advance_deferred()): what AnnotatorConfig::spread_work uses.
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
    /// The normalised poses those features were projected from (input_dim()
    /// floats: the pose, then with motion its velocity and acceleration), and
    /// the facing turn each was taken out of ({cos, sin}, normalize_pose()),
    /// null when not emitted; valid until the next push_frame(); for the
    /// clip's motion directions (descriptor.hpp).
    const float* previous_pose = nullptr;
    const float* current_pose = nullptr;
    const float* previous_facing = nullptr;
    const float* current_facing = nullptr;
    /// The frame's pose jumped (EncoderConfig::max_pose_speed): its motion,
    /// and the motion of the frames after it, start again from it.
    bool motion_restarted = false;
    /// Which stretch of unbroken motion each emitted pose belongs to: the
    /// count of the stream's jumps before it (mod 2^32). Two characters whose
    /// epochs differ have a jump between them: a step from one to the other
    /// is no movement (the segmenter's window of directions starts again).
    std::uint32_t previous_epoch = 0;
    std::uint32_t current_epoch = 0;

    std::uint32_t count() const noexcept { return from_previous + from_current; }
    bool accepted() const noexcept { return status == Status::ok || status == Status::stream_restarted; }
};

/// A character whose deferred encoding is done (StringEncoder::ready_character()):
/// `count` ticks take it, and it was made from `feature` (feature_dim floats,
/// owned by the encoder, valid until pop_character()).
struct DeferredCharacter {
    Character character = 0;
    std::uint32_t count = 0;
    const float* feature = nullptr;
    const float* pose = nullptr;    ///< the pose it was projected from (input_dim() floats), as long as `feature`
    const float* facing = nullptr;  ///< that pose's facing turn ({cos, sin}), as long as `feature`
    std::uint32_t epoch = 0;        ///< that pose's stretch of unbroken motion (EncodedFrame::current_epoch)
};

/// Stream timing of an encoder (AnnotatorConfig carries the same two), and
/// whether it may defer its characters' work.
struct EncoderConfig {
    /// A longer gap between accepted frames restarts the stream.
    std::int64_t max_gap_us = 1000000;
    /// A frame this much earlier than the last one or less is rejected;
    /// further back the stream restarts.
    std::int64_t max_backward_us = 100000;
    /// Room to queue the poses of one frame's ticks (defer()), so their
    /// characters can be computed over later frames; two poses, each with its
    /// feature, more storage. push_frame() alone does not need it.
    bool deferred = false;
    /// The sensor's up direction in the positions' coordinates, when it is
    /// known and differs from the model's up axis (a Kinect's floor plane
    /// normal, gravity from an IMU): every frame is turned to put it along
    /// the axis (up_rotation()). All zero: the positions' up is the model's.
    float up[3] = {0.0f, 0.0f, 0.0f};
    /// A pose that moved faster than this since the previous frame (the
    /// mean over the normalised pose's coordinates, in metres per second),
    /// and by much more than the stream's frames typically move, jumped: the
    /// tracker lost and found the body, swapped two people, or clips were
    /// joined. The motion then starts again from that frame, as at a
    /// stream's start, instead of differencing across the jump (motion.hpp,
    /// JumpCheck, which says how it is judged). 0 (the default here, for a
    /// clip taken as recorded, as training takes its clips): never. A
    /// stream's annotator sets default_max_pose_speed (AnnotatorConfig).
    /// Only for models with motion. Negative or NaN: init() refuses it.
    float max_pose_speed = 0.0f;
};

/// Frame-to-character encoder; needs only the feature tables of the model.
/// Works in caller-owned storage of required_bytes(model) bytes (storage.hpp).
/// Keeps pointers to the ModelView given to init() and to the storage: both
/// must outlive the encoder (or its next init()).
class StringEncoder {
public:
    /// Bytes of storage init() needs for this model (constexpr when the model is).
    static constexpr std::size_t required_bytes(const ModelView& model, const EncoderConfig& config = {}) noexcept {
        return plan(model, config.deferred).bytes;
    }

    /// @return ok, invalid_model (tables, or precision factors that could
    ///         overflow float), storage_too_small, or invalid_argument
    ///         (times StringSampler::settings_ok() refuses for the model's
    ///         period, an up direction up_rotation() refuses, or a negative
    ///         or NaN max_pose_speed)
    Status init(const ModelView& model, const EncoderConfig& config, void* storage, std::size_t bytes) noexcept {
        model_ = nullptr;
        const Status status = validate_feature_tables(model);
        if (status != Status::ok) return status;
        turned_ = config.up[0] != 0.0f || config.up[1] != 0.0f || config.up[2] != 0.0f;
        if (turned_) {
            if (up_rotation(config.up, model.up_axis, rotation_) != Status::ok) return Status::invalid_argument;
            // The identity turns nothing; skipping it keeps the unturned path's work.
            turned_ = false;
            for (int i = 0; i < 9; ++i) turned_ = turned_ || rotation_[i] != (i % 4 == 0 ? 1.0f : 0.0f);
        }
        if (model.has_gmm() && !gmm_is_overflow_safe(model, max_pose_coordinate)) return Status::invalid_model;
        if (!StringSampler::settings_ok(model.string_period_us, config.max_gap_us, config.max_backward_us))
            return Status::invalid_argument;
        if (!(config.max_pose_speed >= 0.0f)) return Status::invalid_argument;
        jump_.configure(config.max_pose_speed);
        const Plan p = plan(model, config.deferred);
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
        deferred_ = config.deferred;
        stage_work_ = stage_work(model);
        for (std::size_t e = 0; e < 2; ++e) {
            queue_poses_[e] = detail::storage_at<float>(storage, p.queue_poses) + e * model.input_dim();
            queue_features_[e] = detail::storage_at<float>(storage, p.queue_features) +
                                 e * (model.has_projection() ? model.feature_dim : 0u);
            if (!model.has_projection()) queue_features_[e] = queue_poses_[e];  // the pose is the feature
        }
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
        jump_.reset();
        has_previous_ = false;
        last_ = 0;
        most_probable_ = 0;
        queued_ = 0;
        head_ = 0;
    }

    /// Encodes one frame. Refused (invalid_argument, nothing changed) while
    /// deferred characters are queued: finish and pop them first.
    /// @param time_us   capture time in microseconds (any origin, non-decreasing;
    ///                  equal times are one instant and the later frame wins)
    /// @param positions joint_count × 3 floats, xyz per joint in metres; read
    ///                  only during the call
    EncodedFrame push_frame(std::int64_t time_us, const float* positions) noexcept {
        if (queued_ != 0) {  // its stages would overwrite the queued character's posterior
            EncodedFrame refused;
            refused.status = Status::invalid_argument;
            return refused;
        }
        EncodedFrame out = accept_frame(time_us, positions);
        if (!out.accepted()) return out;
        // previous_ is this frame's slot now, the previous frame's the other.
        if (out.from_previous > 0) {
            out.previous = character(1u - previous_);
            out.previous_feature = feature(1u - previous_);
            out.previous_pose = poses_[1u - previous_];
            out.previous_facing = facings_[1u - previous_];
            out.previous_epoch = epochs_[1u - previous_];
        }
        if (out.from_current > 0) {
            out.current = character(previous_);
            out.current_feature = feature(previous_);
            out.current_pose = poses_[previous_];
            out.current_facing = facings_[previous_];
            out.current_epoch = epochs_[previous_];
        }
        return out;
    }

    /// Takes a frame as push_frame() does (normalisation, ticks, motion) but
    /// computes no character: `previous`, `current` and their features stay
    /// unset. defer() then queues the ticks' poses, which stay valid until
    /// the next frame.
    EncodedFrame accept_frame(std::int64_t time_us, const float* positions) noexcept {
        EncodedFrame out;
        if (model_ == nullptr) {
            out.status = Status::not_initialized;
            return out;
        }
        const std::size_t current = has_previous_ ? 1u - previous_ : 0u;
        out.status =
            normalize_pose(*model_, positions, poses_[current], uses_bones(model_->scale_mode) ? skeleton_ : nullptr,
                           turned_ ? rotation_ : nullptr, facings_[current]);
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
            // A restart's gap is no frame interval: the check and its typical interval skip it.
            if (plan.status != Status::stream_restarted && has_previous_ &&
                jump_.jumped(time_us - times_[previous_], poses_[current], poses_[previous_], model_->pose_dim())) {
                motion_.reset();
                out.motion_restarted = true;
                ++epoch_;
            }
            if (plan.from_current > 0) motion_.motion(*model_, time_us, poses_[current]);
            motion_.keep(*model_, time_us, poses_[current]);
        }
        epochs_[current] = epoch_;
        out.from_previous = plan.from_previous;
        out.from_current = plan.from_current;
        previous_ = current;
        has_previous_ = true;
        return out;
    }

    // Deferred characters (EncoderConfig::deferred). A character's work is
    // staged: the projection, the GMM a block of components at a time, the
    // posterior, the tree; so a caller can do a little in each frame. The
    // stages are the ones push_frame() runs, in the same order, on a copy of
    // the pose: the characters have the same bits.

    /// Queues the ticks of the frame accept_frame() just took, in order (the
    /// earlier pose first). The queue must be empty (finish and pop what it
    /// holds first): it has room for one frame's two poses.
    /// @return ok, not_initialized, invalid_argument (not deferred, a frame
    ///         that was not accepted) or storage_too_small (the queue is not empty)
    Status defer(const EncodedFrame& frame) noexcept {
        if (model_ == nullptr) return Status::not_initialized;
        if (!deferred_ || !frame.accepted()) return Status::invalid_argument;
        if (queued_ != 0) return Status::storage_too_small;
        head_ = 0;
        if (frame.from_previous > 0) queue(1u - previous_, frame.from_previous);
        if (frame.from_current > 0) queue(previous_, frame.from_current);
        return Status::ok;
    }

    /// Characters queued and not popped yet.
    std::size_t deferred_count() const noexcept { return queued_; }

    /// The work left of every queued character, in the segmenter's units
    /// (about one representative character's update, ActionSegmenter::work_left()).
    std::size_t deferred_work_left() const noexcept {
        std::size_t work = 0;
        for (std::size_t e = 0; e < queued_; ++e) work += work_left(entries_[(head_ + e) % 2]);
        return work;
    }

    /// Does about `work` units of the oldest queued character's stages (at
    /// least one stage or block, so every call moves on). Returns whether
    /// it is ready (ready_character()).
    bool advance_deferred(std::size_t work) noexcept {
        if (queued_ == 0) return false;
        Entry& e = entries_[head_];
        const std::size_t slot = head_;
        std::size_t budget = work == 0 ? 1u : work;
        auto spend = [&budget](std::size_t units) { budget = units >= budget ? 0u : budget - units; };
        while (e.stage != Stage::ready) {
            if (budget == 0) return false;
            switch (e.stage) {
                case Stage::project:
                    if (model_->has_projection()) {
                        // Four columns of the projection at a time.
                        const std::size_t n = model_->input_dim(), per = project_group_work();
                        const std::size_t groups = budget / per + (budget % per != 0 ? 1u : 0u);
                        const std::size_t last = (n - e.next_column) / 4 <= groups ? n : e.next_column + 4 * groups;
                        project_pose_columns(*model_, queue_poses_[slot], queue_features_[slot], e.next_column, last);
                        spend((last - e.next_column + 3) / 4 * per);
                        e.next_column = last;
                        if (last < n) break;
                    } else {
                        spend(1);  // the pose is the feature
                    }
                    if (!model_->has_gmm()) {
                        e.stage = Stage::descend;
                        break;
                    }
                    gmm_pass_begin(*model_, e.gmm, most_probable_);
                    e.stage = Stage::gmm;
                    break;
                case Stage::gmm: {
                    const std::size_t per = gmm_block_work();
                    const std::size_t blocks = budget / per + (budget % per != 0 ? 1u : 0u);
                    const std::size_t before = gmm_pass_blocks_left(*model_, e.gmm);
                    if (!gmm_pass_advance(*model_, e.gmm, queue_features_[slot], posterior_, scratch_, blocks))
                        e.stage = Stage::posterior;
                    spend((before - gmm_pass_blocks_left(*model_, e.gmm)) * per);
                    break;
                }
                case Stage::posterior:
                    // As character(): should it ever fail, the last character again.
                    e.stage = gmm_pass_finish(*model_, e.gmm, posterior_, nullptr, &most_probable_) == Status::ok
                                  ? Stage::descend
                                  : Stage::ready;
                    if (e.stage == Stage::ready) e.character = last_;
                    spend(posterior_work());
                    break;
                case Stage::descend:
                    last_ = model_->has_gmm() ? descend_tree_sparse(*model_, posterior_, norms_, nonzero_)
                                              : descend_tree(*model_, queue_features_[slot]);
                    e.character = last_;
                    e.stage = Stage::ready;
                    spend(descend_work());
                    break;
                case Stage::ready:
                    break;
            }
        }
        return true;
    }

    /// The oldest queued character once advance_deferred() has finished it,
    /// else null. Valid until pop_character().
    const DeferredCharacter* ready_character() noexcept {
        if (queued_ == 0 || entries_[head_].stage != Stage::ready) return nullptr;
        ready_out_ = DeferredCharacter{entries_[head_].character, entries_[head_].count, queue_features_[head_],
                                       queue_poses_[head_],       queue_facings_[head_], queue_epochs_[head_]};
        return &ready_out_;
    }

    /// Drops the oldest queued character (once ready_character() gave it).
    void pop_character() noexcept {
        if (queued_ == 0) return;
        head_ = (head_ + 1) % 2;
        --queued_;
    }

    /// Time of tick k (character k) of the current stream.
    std::int64_t tick_time_us(std::uint64_t tick) const noexcept { return sampler_.tick_time_us(tick); }
    /// The GMM posterior of the last frame whose character was computed
    /// (component_count floats, owned by the encoder, valid until the next
    /// push_frame() or advance_deferred(), which builds the next one in place;
    /// meaningless for a model without a GMM).
    const float* last_posterior() const noexcept { return posterior_; }
    bool initialized() const noexcept { return model_ != nullptr; }

private:
    // The slot's feature: its projected pose, or without a projection the pose itself.
    const float* feature(std::size_t slot) const noexcept {
        return model_->has_projection() ? features_[slot] : poses_[slot];
    }

    // A queued character's stages: the projection, the GMM's blocks, the posterior, the tree.
    enum class Stage : std::uint8_t { project, gmm, posterior, descend, ready };
    struct Entry {
        Stage stage = Stage::project;
        std::size_t next_column = 0;  // the projection's next pose coordinate
        std::uint32_t count = 0;
        Character character = 0;
        GmmPass gmm;
    };

    // Queues a slot's pose (ticks at this frame: the queue is in order).
    void queue(std::size_t slot, std::uint32_t count) noexcept {
        const std::size_t e = (head_ + queued_) % 2;
        const std::size_t n = model_->input_dim();
        for (std::size_t i = 0; i < n; ++i) queue_poses_[e][i] = poses_[slot][i];
        queue_facings_[e][0] = facings_[slot][0];
        queue_facings_[e][1] = facings_[slot][1];
        queue_epochs_[e] = epochs_[slot];
        entries_[e] = Entry{};
        entries_[e].count = count;
        ready_[slot] = true;  // its motion is taken (accept_frame())
        ++queued_;
    }

    // Each stage's work in the segmenter's units (about one representative
    // character's update), from the operations it does: the estimates only
    // share a frame's budget out, the results do not depend on them. On a
    // core without SIMD (a Cortex-M4) a cell costs about four multiply-adds;
    // with SIMD the lanes make the arithmetic cheaper than a cell, whose
    // recurrence waits on its neighbours: on the host's bench
    // (bench/frame_latency.cpp) a GMM block's multiply-adds ran about four
    // times faster per unit than the segmenter's cells. Of 4, 8 and 16
    // multiply-adds per unit there, 16 let the frames that emit a character
    // of a 250-representative model take too much (p99 over every frame 3.1
    // against 2.7 µs); all three gave about 2.2 µs at J = 40. So eight.
#if ACTIONSTRING_DETAIL_LANES >= 4
    static constexpr std::size_t per_unit = 8;  // multiply-adds per unit
#else
    static constexpr std::size_t per_unit = 4;
#endif
    // The estimates depend on the model alone: taken once, at init().
    struct StageWork {
        std::size_t project_group = 0;  // four columns of the projection
        std::size_t gmm_block = 0;      // four components
        std::size_t posterior = 0;      // an exp, a sum and a product per component: about sixteen multiply-adds
        std::size_t descend = 0;        // per level two distances over the tree's dimension, or their sparse difference
    };
    static StageWork stage_work(const ModelView& m) noexcept {
        StageWork w;
        const std::size_t d = m.feature_dim;
        w.project_group = 4u * d / per_unit + 1u;
        w.gmm_block = 4u * (m.covariance == Covariance::diagonal ? d : d * (d + 1u) / 2u + d) / per_unit + 1u;
        w.posterior = 16u * m.component_count / per_unit + 1u;
        std::size_t depth = 1;
        while ((std::size_t{1} << depth) < m.node_count) ++depth;
        w.descend = depth * (4u * m.tree_dim() / per_unit + 2u);
        return w;
    }
    std::size_t project_group_work() const noexcept { return stage_work_.project_group; }
    std::size_t project_work(std::size_t next_column) const noexcept {
        return model_->has_projection() ? (model_->input_dim() - next_column + 3u) / 4u * project_group_work() : 1u;
    }
    std::size_t gmm_block_work() const noexcept { return stage_work_.gmm_block; }
    std::size_t posterior_work() const noexcept { return stage_work_.posterior; }
    std::size_t descend_work() const noexcept { return stage_work_.descend; }
    std::size_t work_left(const Entry& e) const noexcept {
        switch (e.stage) {
            case Stage::project:
                return project_work(e.next_column) +
                       (model_->has_gmm()
                            ? gmm_pass_blocks_left(*model_, GmmPass{}) * gmm_block_work() + posterior_work()
                            : 0u) +
                       descend_work();
            case Stage::gmm:
                return gmm_pass_blocks_left(*model_, e.gmm) * gmm_block_work() + posterior_work() + descend_work();
            case Stage::posterior:
                return posterior_work() + descend_work();
            case Stage::descend:
                return descend_work();
            case Stage::ready:
                return 0;
        }
        return 0;
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
        std::size_t poses = 0, skeleton = 0, feature = 0, posterior = 0, scratch = 0, norms = 0, nonzero = 0,
                    motion = 0, queue_poses = 0, queue_features = 0, bytes = 0;
    };
    static constexpr Plan plan(const ModelView& m, bool deferred) noexcept {
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
        p.queue_poses = layout.add<float>(deferred ? 2u * m.input_dim() : 0u);  // deferred: two poses queued
        p.queue_features = layout.add<float>(deferred && m.has_projection() ? 2u * m.feature_dim : 0u);
        p.bytes = layout.bytes();
        return p;
    }

    const ModelView* model_ = nullptr;
    StringSampler sampler_;
    float* poses_[2] = {};  // input_dim() floats each: the pose, then with motion its velocity and acceleration
    float facings_[2][2] = {};        // each slot's facing turn, {cos, sin}
    float queue_facings_[2][2] = {};  // deferred: the queued poses' facing turns
    std::uint32_t queue_epochs_[2] = {};  // deferred: the queued poses' epochs
    std::uint32_t epochs_[2] = {};        // each pose slot's stretch of unbroken motion
    std::uint32_t epoch_ = 0;             // the jumps seen so far (the newest pose's epoch)
    MotionRing motion_;
    float* skeleton_ = nullptr;  // the rebuilt skeleton (bone-length scaling)
    float rotation_[9] = {};     // EncoderConfig::up's turn (up_rotation()), used when turned_
    bool turned_ = false;
    Character characters_[2] = {};
    bool ready_[2] = {};          // the slot's character (and its motion, if any) is computed
    std::int64_t times_[2] = {};  // the slot's frame time (for its motion)
    JumpCheck jump_;              // EncoderConfig::max_pose_speed
    std::size_t previous_ = 0;
    bool has_previous_ = false;
    Character last_ = 0;
    std::size_t most_probable_ = 0;  // the last posterior's peak: where the next GMM pass starts
    float* features_[2] = {};     // with a projection: each slot's projected pose
    float* posterior_ = nullptr;  // component_count floats
    float* scratch_ = nullptr;    // the GMM's gmm_scratch_floats()
    float* norms_ = nullptr;      // with a GMM: the tree's node norms (tree_node_norms())
    std::uint16_t* nonzero_ = nullptr;  // with a GMM: the posterior's non-zero coordinates
    // Deferred characters: a queue of up to two, in storage (poses and features) and here.
    bool deferred_ = false;
    float* queue_poses_[2] = {};
    float* queue_features_[2] = {};  // the projected poses; without a projection, the poses
    Entry entries_[2] = {};
    std::size_t head_ = 0, queued_ = 0;
    StageWork stage_work_;
    DeferredCharacter ready_out_;
};

}  // namespace actionstring
