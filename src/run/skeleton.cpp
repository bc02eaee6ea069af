// Matching a file's skeleton to the model's.
#include "run/skeleton.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "io/text.hpp"
#include "model/model_data.hpp"

namespace actionstring {
namespace host {
namespace {

bool has_joint(const ModelView& model, const char* name) {
    if (!model.joint_names.present()) return false;
    for (std::size_t j = 0; j < model.joint_count; ++j)
        if (std::string(model.joint_names[j]) == name) return true;
    return false;
}

// A joint name without its namespace ("mixamorig:Hips" → "Hips", "Armature|Hips" → "Hips").
std::string_view base_name(std::string_view name) {
    const std::size_t cut = name.find_last_of(":|");
    return cut == std::string_view::npos ? name : name.substr(cut + 1);
}

// Index of the clip's joint called `name`: an exact match, else the only
// case-insensitive one, else the only one with the same name without its
// namespace; −1 when there is none, −2 when it is ambiguous.
int find_joint(const Clip& clip, const std::string& name) {
    const int exact = clip.joint_index(name);
    if (exact >= 0) return exact;
    for (const bool without_namespace : {false, true}) {
        int found = -1;
        for (std::size_t j = 0; j < clip.joint_count(); ++j) {
            const bool same = without_namespace ? iequals(base_name(clip.joint_names[j]), base_name(name))
                                                : iequals(clip.joint_names[j], name);
            if (!same) continue;
            if (found >= 0) return -2;
            found = static_cast<int>(j);
        }
        if (found >= 0) return found;
    }
    return -1;
}

// The clip's joints `source[k]` become joint k, named names[k]; a parent not
// kept gives way to its nearest kept ancestor.
void gather_joints(Clip& clip, const std::vector<std::size_t>& source, const std::vector<std::string>& names) {
    const std::size_t from = clip.joint_count(), J = source.size();
    std::vector<float> positions(clip.frame_count() * J * 3);
    for (std::size_t f = 0; f < clip.frame_count(); ++f)
        for (std::size_t j = 0; j < J; ++j)
            for (std::size_t k = 0; k < 3; ++k) positions[(f * J + j) * 3 + k] = clip.positions[(f * from + source[j]) * 3 + k];
    std::vector<int> parents;
    if (clip.parents.size() == from) {
        std::vector<int> kept_index(from, -1);
        for (std::size_t j = 0; j < J; ++j) kept_index[source[j]] = static_cast<int>(j);
        for (std::size_t j = 0; j < J; ++j) {
            int parent = clip.parents[source[j]];
            // Up the original tree to the first kept joint (bounded: a tree has no cycles, but a file may).
            for (std::size_t guard = 0; parent >= 0 && kept_index[static_cast<std::size_t>(parent)] < 0 && guard < from;
                 ++guard)
                parent = clip.parents[static_cast<std::size_t>(parent)];
            parents.push_back(parent < 0 ? -1 : kept_index[static_cast<std::size_t>(parent)]);
        }
    }
    clip.positions = std::move(positions);
    clip.parents = std::move(parents);
    clip.joint_names = names;
}

// Where each of `names` is in the clip; throws ReadError for names it lacks
// or matches twice, saying what was expected.
std::vector<std::size_t> locate_joints(const Clip& clip, const std::vector<std::string>& names,
                                       const std::string& expected) {
    std::vector<std::size_t> source(names.size());
    std::string missing, ambiguous;
    std::size_t missing_count = 0;
    for (std::size_t j = 0; j < names.size(); ++j) {
        const int index = find_joint(clip, names[j]);
        if (index == -2) ambiguous += (ambiguous.empty() ? "" : ", ") + names[j];
        if (index < 0) {
            if (index == -1 && ++missing_count <= 6) missing += (missing.empty() ? "" : ", ") + names[j];
            continue;
        }
        source[j] = static_cast<std::size_t>(index);
    }
    if (!ambiguous.empty())
        throw ReadError(clip.source, 0, "joints " + ambiguous + " match more than one joint of the file (names differ only in case)");
    if (missing_count > 0)
        throw ReadError(clip.source, 0,
                        std::to_string(clip.joint_count()) + " joints, " + expected + ": " +
                            std::to_string(missing_count) + " of them are not in the file (" + missing +
                            (missing_count > 6 ? ", …" : "") + ")");
    return source;
}

// The body joints of the engine rigs: the root, then the hips (the roles), then the rest.
struct RigBody {
    const char* rig;
    std::vector<const char*> joints;  // joints[0..2]: root, left hip, right hip; all must be present
    std::size_t optional_from;        // joints from this index on may be missing (rig versions differ)
};

const std::vector<RigBody>& rig_bodies() {
    static const std::vector<RigBody> rigs{
        {"CC_Base rig",
         {"CC_Base_Hip", "CC_Base_L_Thigh", "CC_Base_R_Thigh", "CC_Base_Pelvis", "CC_Base_L_Calf", "CC_Base_L_Foot",
          "CC_Base_L_ToeBase", "CC_Base_R_Calf", "CC_Base_R_Foot", "CC_Base_R_ToeBase", "CC_Base_Waist",
          "CC_Base_Spine01", "CC_Base_Spine02", "CC_Base_NeckTwist01", "CC_Base_Head", "CC_Base_L_Clavicle",
          "CC_Base_L_Upperarm", "CC_Base_L_Forearm", "CC_Base_L_Hand", "CC_Base_R_Clavicle", "CC_Base_R_Upperarm",
          "CC_Base_R_Forearm", "CC_Base_R_Hand"},
         3},
        {"Mixamo rig",
         {"Hips", "LeftUpLeg", "RightUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "RightLeg", "RightFoot",
          "RightToeBase", "Spine", "Spine1", "Spine2", "Neck", "Head", "LeftShoulder", "LeftArm", "LeftForeArm",
          "LeftHand", "RightShoulder", "RightArm", "RightForeArm", "RightHand"},
         3},
        {"Unreal mannequin",
         {"pelvis", "thigh_l", "thigh_r", "calf_l", "foot_l", "ball_l", "calf_r", "foot_r", "ball_r", "spine_01",
          "spine_02", "spine_03", "spine_04", "spine_05", "neck_01", "head", "clavicle_l", "upperarm_l",
          "lowerarm_l", "hand_l", "clavicle_r", "upperarm_r", "lowerarm_r", "hand_r"},
         3},
        {"Unity humanoid",
         {"Hips", "LeftUpperLeg", "RightUpperLeg", "LeftLowerLeg", "LeftFoot", "LeftToes", "RightLowerLeg",
          "RightFoot", "RightToes", "Spine", "Chest", "UpperChest", "Neck", "Head", "LeftShoulder", "LeftUpperArm",
          "LeftLowerArm", "LeftHand", "RightShoulder", "RightUpperArm", "RightLowerArm", "RightHand"},
         3},
    };
    return rigs;
}

std::string expectation(const ModelView& model) {
    const std::string rig = rig_name(model);
    return std::to_string(model.joint_count) + " joints" + (rig.empty() ? "" : " (" + rig + ")");
}

}  // namespace

std::string rig_name(const ModelView& model) {
    if (has_joint(model, "lhipjoint") && has_joint(model, "lfemur")) return "HDM05/CMU ASF";
    if (has_joint(model, "HipCenter") && has_joint(model, "ShoulderCenter")) return "Kinect v1";
    if (has_joint(model, "SpineBase") && has_joint(model, "SpineShoulder")) return "Kinect v2";
    // The engine rigs by their root and hips, with or without a namespace prefix.
    if (!model.joint_names.present()) return {};
    auto has = [&](const char* name) {
        for (std::size_t j = 0; j < model.joint_count; ++j)
            if (iequals(base_name(model.joint_names[j]), name)) return true;
        return false;
    };
    for (const RigBody& body : rig_bodies())
        if (has(body.joints[0]) && has(body.joints[1]) && has(body.joints[2])) return body.rig;
    return {};
}

void conform_to_model(const ModelView& model, Clip& clip) {
    const std::size_t J = model.joint_count;
    if (!model.joint_names.present()) {
        if (clip.joint_count() != J)
            throw ReadError(clip.source, 0,
                            std::to_string(clip.joint_count()) + " joints, the model expects " + expectation(model));
        return;
    }
    bool same_order = clip.joint_count() == J;
    for (std::size_t j = 0; same_order && j < J; ++j) same_order = clip.joint_names[j] == model.joint_names[j];
    if (same_order) return;

    const std::vector<std::string> names = name_strings(model.joint_names, J);
    // Same joints in another order, or extra joints: gather the model's joints in its order.
    gather_joints(clip, locate_joints(clip, names, "the model expects " + expectation(model)), names);
    clip.roles = JointRoles{model.root_joint, model.left_hip_joint, model.right_hip_joint};
    flag_lost_frames(clip);
}

std::vector<std::string> body_joints(const Clip& clip, std::string* rig) {
    for (const RigBody& body : rig_bodies()) {
        std::vector<std::string> names;
        for (std::size_t k = 0; k < body.joints.size(); ++k) {
            const int index = find_joint(clip, body.joints[k]);
            if (index >= 0) {
                names.push_back(clip.joint_names[static_cast<std::size_t>(index)]);
            } else if (k < body.optional_from) {
                names.clear();
                break;
            }
        }
        // A rig is recognised by its root and hips and most of its body.
        if (names.size() >= body.optional_from && names.size() * 4 >= body.joints.size() * 3) {
            if (rig != nullptr) *rig = body.rig;
            return names;
        }
    }
    if (rig != nullptr) rig->clear();
    return {};
}

void keep_joints(Clip& clip, const std::vector<std::string>& names) {
    const std::vector<std::size_t> source = locate_joints(clip, names, "training uses " + std::to_string(names.size()) + " pose joints");
    auto role = [&](int old_index, const char* what) {
        if (old_index < 0) return -1;
        for (std::size_t k = 0; k < source.size(); ++k)
            if (source[k] == static_cast<std::size_t>(old_index)) return static_cast<int>(k);
        throw ReadError(clip.source, 0,
                        std::string("the ") + what + " joint " +
                            quoted(clip.joint_names[static_cast<std::size_t>(old_index)]) + " is not among the pose joints");
    };
    const JointRoles roles{role(clip.roles.root, "root"), role(clip.roles.left_hip, "left hip"),
                           role(clip.roles.right_hip, "right hip")};
    std::vector<std::string> kept;
    for (const std::size_t j : source) kept.push_back(clip.joint_names[j]);
    gather_joints(clip, source, kept);
    clip.roles = roles;
    flag_lost_frames(clip);
}

std::string select_pose_joints(std::vector<LabelledClip>& clips, const std::vector<std::string>& pose_joints) {
    if (clips.empty()) return {};
    const Clip& first = clips.front().clip;
    for (const LabelledClip& c : clips)
        if (c.clip.up_axis != first.up_axis)
            throw std::invalid_argument(c.clip.source + ": its up axis differs from " + first.source +
                                        "'s; train on files of one orientation");
    std::string rig;
    std::vector<std::string> names = pose_joints.empty() ? body_joints(first, &rig) : pose_joints;
    if (names.empty()) return {};
    // The roles come first and are always kept: the pose is measured from them.
    if (!pose_joints.empty() && first.roles.complete()) {
        std::vector<std::string> with_roles;
        for (const int role : {first.roles.root, first.roles.left_hip, first.roles.right_hip}) {
            const std::string& name = first.joint_names[static_cast<std::size_t>(role)];
            bool listed = false;
            for (const std::string& n : names) listed = listed || find_joint(first, n) == role;
            if (!listed && std::find(with_roles.begin(), with_roles.end(), name) == with_roles.end())
                with_roles.push_back(name);
        }
        names.insert(names.begin(), with_roles.begin(), with_roles.end());
    }
    const std::size_t before = first.joint_count();
    for (LabelledClip& c : clips) keep_joints(c.clip, names);
    return (rig.empty() ? std::string("pose joints") : rig) + ": " + std::to_string(names.size()) + " of " +
           std::to_string(before) + " joints";
}

void conform_to_model(const ModelView& model, std::vector<LabelledClip>& clips) {
    for (LabelledClip& c : clips) conform_to_model(model, c.clip);
}

void require_joint_count(const ModelView& model, std::size_t joints, const std::string& source) {
    if (joints != model.joint_count)
        throw std::invalid_argument(source + ": " + std::to_string(joints) + " joints, the model expects " +
                                    expectation(model) + " (conform_to_model() maps joints by name)");
}

std::vector<bool> torso_bones(const std::vector<int>& parents, const JointRoles& roles) {
    const std::size_t J = parents.size();
    if (!roles.complete() || static_cast<std::size_t>(roles.root) >= J ||
        static_cast<std::size_t>(roles.left_hip) >= J || static_cast<std::size_t>(roles.right_hip) >= J)
        return {};
    std::vector<bool> torso(J, false), hip_path(J, false);
    const auto root = static_cast<std::size_t>(roles.root);
    // The hips: every bone from a hip up to the root (at most J steps, whatever the parents say).
    for (const int hip : {roles.left_hip, roles.right_hip}) {
        std::size_t j = static_cast<std::size_t>(hip);
        for (std::size_t steps = 0; j != root && steps < J; ++steps) {
            hip_path[j] = true;
            const int parent = parents[j];
            if (parent < 0 || static_cast<std::size_t>(parent) >= J) break;
            torso[j] = true;
            j = static_cast<std::size_t>(parent);
        }
    }
    std::vector<std::vector<std::size_t>> children(J);
    for (std::size_t j = 0; j < J; ++j)
        if (parents[j] >= 0 && static_cast<std::size_t>(parents[j]) < J)
            children[static_cast<std::size_t>(parents[j])].push_back(j);
    // The spine: each other child of the root, up through single children to the chest.
    for (std::size_t c : children[root]) {
        if (hip_path[c]) continue;
        std::size_t j = c;
        torso[j] = true;
        for (std::size_t steps = 0; children[j].size() == 1 && steps < J; ++steps) {
            j = children[j].front();
            torso[j] = true;
        }
        if (children[j].size() >= 2)
            for (std::size_t k : children[j]) torso[k] = true;
    }
    return torso;
}

}  // namespace host
}  // namespace actionstring
