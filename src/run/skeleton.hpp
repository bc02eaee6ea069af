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

/// The body joints of an engine rig this library knows (the CC_Base rig,
/// Mixamo, the Unreal mannequin, Unity's humanoid bone names): the file's own
/// names of the joints that carry the body's pose (hips, spine, neck, head,
/// shoulders to hands, legs to toes; no fingers, twist, face or helper bones),
/// the root first. Sets `rig` to the rig's name when given. Empty for any other
/// skeleton (HDM05/CMU ASF, Kinect: small enough that every joint is kept).
std::vector<std::string> body_joints(const Clip& clip, std::string* rig = nullptr);

/// Keeps only the named joints of the clip, in that order (names matched as
/// conform_to_model() matches them, a namespace prefix such as "mixamorig:"
/// aside). Each kept joint's parent becomes its nearest kept ancestor, and the
/// root and hip roles follow their joints. Throws ReadError naming the file
/// and the joints it lacks, or a role joint not kept.
void keep_joints(Clip& clip, const std::vector<std::string>& names);

/// Puts every training clip on one skeleton before training: the joints
/// named in `pose_joints` (the root and hips added when missing), else the
/// first clip's body_joints() when it is an engine rig, else every joint as
/// it is. Files of one rig that differ only by extra joints (an extra root,
/// fingers, twist bones) then train together. Clips must share their up axis.
/// Returns a note for the user ("CC_Base rig: 23 of 100 joints"), or "".
std::string select_pose_joints(std::vector<LabelledClip>& clips, const std::vector<std::string>& pose_joints);

/// The torso's bones of a skeleton, by the joint each ends at (ScaleMode::torso):
/// those on the path from each hip role up to the root; from each other child
/// of the root, the chain of single children up to the first joint with two or
/// more (the chest); and the bones from the chest to its children (neck and
/// shoulders or clavicles). Needs `parents` (one per joint, −1 at a root) and
/// the roles; empty when they are incomplete.
std::vector<bool> torso_bones(const std::vector<int>& parents, const JointRoles& roles);

/// Throws std::invalid_argument unless a frame of `joints` joints is what the
/// model reads (every host function that streams frames checks this first).
void require_joint_count(const ModelView& model, std::size_t joints, const std::string& source);

}  // namespace host
}  // namespace actionstring
