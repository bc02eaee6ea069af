// actionstring — status codes shared by every runtime stage.
#pragma once

#include <cstdint>

namespace actionstring {

/// Outcome of a runtime call. The runtime never throws; every stage reports
/// through one of these codes and leaves its state unchanged on failure unless
/// the code's description says otherwise.
enum class Status : std::uint8_t {
    ok = 0,
    /// The frame holds a non-finite coordinate (NaN or infinity).
    non_finite_input,
    /// The frame looks like lost tracking: every joint the model uses is at the origin.
    tracking_lost,
    /// Root and hips give no usable facing direction (hips coincide in the horizontal plane).
    degenerate_pose,
    /// The pose is so far from every key-pose that no posterior can be formed in float.
    pose_out_of_range,
    /// The frame's timestamp is earlier than the previous frame's.
    time_went_backwards,
    /// The frame arrived after a gap longer than the configured maximum; the stream restarted.
    stream_restarted,
    /// The model's tables are inconsistent (index out of range, non-finite value, bad size).
    invalid_model,
    /// The model needs more than the runtime can represent (a string longer
    /// than 16-bit warping-path lengths allow).
    model_exceeds_capacity,
    /// An argument is out of range (null pointer, wrong joint count, bad length).
    invalid_argument,
    /// The state object was used before a successful init().
    not_initialized,
    /// The storage given to init() is null, misaligned or smaller than
    /// required_bytes() for this model and these settings.
    storage_too_small,
};

/// Short, stable, human-readable name of a status code (static storage).
constexpr const char* status_name(Status status) noexcept {
    switch (status) {
        case Status::ok:
            return "ok";
        case Status::non_finite_input:
            return "non_finite_input";
        case Status::tracking_lost:
            return "tracking_lost";
        case Status::degenerate_pose:
            return "degenerate_pose";
        case Status::pose_out_of_range:
            return "pose_out_of_range";
        case Status::time_went_backwards:
            return "time_went_backwards";
        case Status::stream_restarted:
            return "stream_restarted";
        case Status::invalid_model:
            return "invalid_model";
        case Status::model_exceeds_capacity:
            return "model_exceeds_capacity";
        case Status::invalid_argument:
            return "invalid_argument";
        case Status::not_initialized:
            return "not_initialized";
        case Status::storage_too_small:
            return "storage_too_small";
    }
    return "unknown_status";
}

/// True for the codes that describe a single rejected frame rather than a
/// broken model or a programming error: the stream can go on after them.
constexpr bool is_frame_rejection(Status status) noexcept {
    return status == Status::non_finite_input || status == Status::tracking_lost || status == Status::degenerate_pose ||
           status == Status::pose_out_of_range || status == Status::time_went_backwards;
}

}  // namespace actionstring
