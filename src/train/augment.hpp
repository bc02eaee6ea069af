// actionstring host library — training augmentation: the same performance
// done with the other side of the body.
#pragma once

#include <string>
#include <vector>

#include "io/clip.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// For each joint, the index of its counterpart on the other side of the body
/// (itself for a joint on the midline), by name: "Left"/"Right" anywhere
/// (Kinect, Mixamo, engine rigs), "_L_"/"_R_" (CC_Base), a trailing "_l"/"_r"
/// (the Unreal mannequin), or a leading "l"/"r"
/// (HDM05/CMU ASF: lfemur, rfemur). A name is paired only when its
/// counterpart exists, so "lowerback" stays itself.
std::vector<int> mirror_pairs(const std::vector<std::string>& joint_names);

/// The clip mirrored: positions reflected across a vertical plane (the first
/// horizontal axis negated) and every left joint swapped with its right
/// counterpart, so a right-handed throw becomes a left-handed one. Mirroring
/// twice gives the clip back exactly.
Clip mirror_clip(const Clip& clip);

/// The clips followed by their mirrored copies (same labels and subjects).
std::vector<LabelledClip> with_mirrored(const std::vector<LabelledClip>& clips);

}  // namespace host
}  // namespace actionstring
