// actionstring host library — the runtime's per-frame stages run over a whole
// host clip: its action string, and its normalised poses at a fixed rate.
#pragma once

#include <cstddef>
#include <vector>

#include "actionstring/model.hpp"
#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// The action string of a clip under a trained model (the runtime's encoder,
/// frame by frame with the clip's timestamps). Throws std::invalid_argument
/// when the encoder refuses the model.
std::vector<Character> clip_string(const ModelView& model, const Clip& clip);

/// A clip's action string and, when asked for, the feature each character
/// was made from (EncodedFrame's previous_feature / current_feature).
struct EncodedClip {
    std::vector<Character> string;
    std::vector<float> features;  ///< feature_dim floats per character, or empty
    std::vector<float> records;   ///< direction_record_floats() per character (its pose and facing), or empty
};

/// clip_string() with, when `with_features`, the characters' features, and
/// when `with_records` their poses and facings (EncodedFrame's previous_pose
/// and previous_facing …: what the motion directions read, descriptor.hpp).
EncodedClip encode_clip(const ModelView& model, const Clip& clip, bool with_features, bool with_records = false);

/// Appends to `poses` the clip's normalised poses nearest to every tick of a
/// clock at `rate_hz`, picked by the runtime's own sampler: model.input_dim()
/// floats each (with motion, the pose then its velocity, from the runtime's
/// own MotionRing run over every frame). Returns the frames normalisation rejected.
std::size_t sample_poses(const ModelView& model, const Clip& clip, double rate_hz, std::vector<float>& poses);

}  // namespace host
}  // namespace actionstring
