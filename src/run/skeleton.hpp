// actionstring host library — matching a file's skeleton to the one a model
// was trained on, before any frame reaches the runtime.
#pragma once

#include <string>
#include <vector>

#include "actionstring/model.hpp"
#include "io/clip.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// A short name for the rig a model's joints come from ("HDM05/CMU ASF",
/// "Kinect v1", "Kinect v2", "CC_Base rig"), or "" when none is recognised.
std::string rig_name(const ModelView& model);

/// Puts the clip's frames in the model's joint order. A clip with the model's
/// joints in its order is left as it is; one with the same joints in another
/// order, or with extra joints, is mapped by name (exact, else
/// case-insensitive, when each name matches one joint only). Anything else is
/// refused with a ReadError naming the file, the joint counts, the model's rig
/// and the joints it misses. A model without joint names needs the same joint count.
void conform_to_model(const ModelView& model, Clip& clip);
void conform_to_model(const ModelView& model, std::vector<LabelledClip>& clips);

/// Throws std::invalid_argument unless a frame of `joints` joints is what the
/// model reads (every host function that streams frames checks this first).
void require_joint_count(const ModelView& model, std::size_t joints, const std::string& source);

}  // namespace host
}  // namespace actionstring
