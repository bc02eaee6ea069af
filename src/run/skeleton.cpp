// Matching a file's skeleton to the model's.
#include "run/skeleton.hpp"

#include <stdexcept>

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

// Index of the clip's joint called `name`: an exact match, else the only
// case-insensitive one; −1 when there is none, −2 when it is ambiguous.
int find_joint(const Clip& clip, const std::string& name) {
    const int exact = clip.joint_index(name);
    if (exact >= 0) return exact;
    int found = -1;
    for (std::size_t j = 0; j < clip.joint_count(); ++j)
        if (iequals(clip.joint_names[j], name)) {
            if (found >= 0) return -2;
            found = static_cast<int>(j);
        }
    return found;
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
    if (has_joint(model, "CC_Base_Hip")) return "CC_Base rig";
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

    std::vector<std::size_t> source(J);
    std::string missing, ambiguous;
    std::size_t missing_count = 0;
    for (std::size_t j = 0; j < J; ++j) {
        const int index = find_joint(clip, model.joint_names[j]);
        if (index == -2) ambiguous += (ambiguous.empty() ? "" : ", ") + std::string(model.joint_names[j]);
        if (index < 0) {
            if (index == -1 && ++missing_count <= 6) missing += (missing.empty() ? "" : ", ") + std::string(model.joint_names[j]);
            continue;
        }
        source[j] = static_cast<std::size_t>(index);
    }
    if (!ambiguous.empty())
        throw ReadError(clip.source, 0, "joints " + ambiguous + " match more than one joint of the file (names differ only in case)");
    if (missing_count > 0)
        throw ReadError(clip.source, 0,
                        std::to_string(clip.joint_count()) + " joints, the model expects " + expectation(model) + ": " +
                            std::to_string(missing_count) + " of its joints are not in the file (" + missing +
                            (missing_count > 6 ? ", …" : "") + ")");
    // Same joints in another order, or extra joints: gather the model's joints in its order.
    const std::size_t from = clip.joint_count();
    std::vector<float> positions(clip.frame_count() * J * 3);
    for (std::size_t f = 0; f < clip.frame_count(); ++f)
        for (std::size_t j = 0; j < J; ++j)
            for (std::size_t k = 0; k < 3; ++k) positions[(f * J + j) * 3 + k] = clip.positions[(f * from + source[j]) * 3 + k];
    std::vector<int> parents;
    if (!clip.parents.empty()) {
        std::vector<int> model_index(from, -1);
        for (std::size_t j = 0; j < J; ++j) model_index[source[j]] = static_cast<int>(j);
        for (std::size_t j = 0; j < J; ++j) {
            const int parent = clip.parents[source[j]];
            parents.push_back(parent < 0 ? -1 : model_index[static_cast<std::size_t>(parent)]);
        }
    }
    clip.positions = std::move(positions);
    clip.parents = std::move(parents);
    clip.joint_names = name_strings(model.joint_names, J);
    clip.roles = JointRoles{model.root_joint, model.left_hip_joint, model.right_hip_joint};
    flag_lost_frames(clip);
}

void conform_to_model(const ModelView& model, std::vector<LabelledClip>& clips) {
    for (LabelledClip& c : clips) conform_to_model(model, c.clip);
}

void require_joint_count(const ModelView& model, std::size_t joints, const std::string& source) {
    if (joints != model.joint_count)
        throw std::invalid_argument(source + ": " + std::to_string(joints) + " joints, the model expects " +
                                    expectation(model) + " (conform_to_model() maps joints by name)");
}

}  // namespace host
}  // namespace actionstring
