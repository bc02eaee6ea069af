// actionstring host library — the skeletons of depth-camera SDKs (Kinect v1,
// Kinect v2, Azure Kinect): their joints and bone trees. Files and arrays that
// name joints but carry no tree (Kinect text, joint CSV, numpy arrays) take
// theirs from here, so the bone-length normalisation can use them.
#pragma once

#include <string>
#include <vector>

namespace actionstring {
namespace host {

/// Kinect v1 joints in the SDK's order (UTKinect files, SDK exports).
const std::vector<std::string>& kinect_v1_joint_names();
/// Kinect v2 joints in the SDK's order (NTU RGB+D's too).
const std::vector<std::string>& kinect_v2_joint_names();
/// Azure Kinect body tracking joints in the SDK's order (k4abt_joint_id_t).
const std::vector<std::string>& azure_kinect_joint_names();

/// The parent of each joint of `names` in the first SDK skeleton (Kinect v1,
/// Kinect v2, Azure Kinect) that has every one of them and its own root,
/// matched as exports spell them (joint_spelling_key(): HipLeft, HIP_LEFT,
/// hip_left), in any order; −1 at the root. A joint whose SDK parent is not
/// among `names` hangs from its nearest ancestor that is (a file without
/// hands or feet). Empty when no SDK skeleton has them all, or one name is
/// given twice: a tree is never guessed.
std::vector<int> sdk_parents(const std::vector<std::string>& names);

}  // namespace host
}  // namespace actionstring
