// Clip helpers: joint roles and lost frames.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/clip.hpp"

#include "actionstring/normalize.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {

int Clip::joint_index(std::string_view name) const noexcept {
    for (std::size_t j = 0; j < joint_names.size(); ++j)
        if (joint_names[j] == name) return static_cast<int>(j);
    return -1;
}

// A joint name as exports spell it differently: lower case, without '_', '-',
// '.' or spaces, and without a namespace ("mixamorig:Hips", "Armature|Hips").
std::string joint_spelling_key(std::string_view name) {
    const std::size_t cut = name.find_last_of(":|");
    if (cut != std::string_view::npos) name = name.substr(cut + 1);
    std::string key;
    for (const char c : name)
        if (c != '_' && c != '-' && c != '.' && c != ' ')
            key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return key;
}

int joint_by_spelling(const Clip& clip, std::string_view name) {
    const std::string key = joint_spelling_key(name);
    int found = -1;
    for (std::size_t j = 0; j < clip.joint_names.size(); ++j)
        if (joint_spelling_key(clip.joint_names[j]) == key) {
            if (found >= 0) return -2;
            found = static_cast<int>(j);
        }
    return found;
}

double metres_per_unit(std::string_view unit) {
    if (unit == "m") return 1.0;
    if (unit == "dm") return 0.1;
    if (unit == "cm") return 0.01;
    if (unit == "mm") return 0.001;
    if (unit == "in") return 0.0254;
    throw std::invalid_argument("expected a length unit: m, dm, cm, mm or in, got '" + std::string(unit) + "'");
}

double metres_per_unit_for_height(double height) {
    if (height < 3.0) return 1.0;
    if (height < 30.0) return 0.1;      // decimetres: unusual, but keeps the figure human
    if (height < 110.0) return 0.0254;  // inches (a 1.0–2.8 m person is 40–110 in)
    if (height < 300.0) return 0.01;    // centimetres
    return 0.001;                       // millimetres
}

double median_body_height(const Clip& clip, int up_axis) {
    const std::size_t up = static_cast<std::size_t>(up_axis), J = clip.joint_count();
    std::vector<double> heights;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const float* p = clip.frame(f);
        if (std::all_of(p, p + 3 * J, [](float v) { return v == 0.0f; })) continue;  // lost: says nothing
        double low = p[up], high = p[up];
        for (std::size_t j = 1; j < J; ++j) {
            low = std::min(low, static_cast<double>(p[3 * j + up]));
            high = std::max(high, static_cast<double>(p[3 * j + up]));
        }
        heights.push_back(high - low);
    }
    if (heights.empty()) return 0.0;
    std::nth_element(heights.begin(), heights.begin() + static_cast<long>(heights.size() / 2), heights.end());
    return heights[heights.size() / 2];
}

void check_tree(const std::vector<int>& parents, std::size_t joints) {
    if (parents.size() != joints)
        throw std::invalid_argument("parents: " + std::to_string(parents.size()) + " parents for " +
                                    std::to_string(joints) + " joints (one per joint, -1 at a root)");
    for (std::size_t j = 0; j < joints; ++j) {
        // Up from every joint: a root must come within `joints` steps, or the parents form a cycle.
        int up = static_cast<int>(j);
        for (std::size_t steps = 0; up >= 0 && steps <= joints; ++steps) {
            const int parent = parents[static_cast<std::size_t>(up)];
            if (parent < -1 || parent >= static_cast<int>(joints))
                throw std::invalid_argument("parents: joint " + std::to_string(up) + "'s parent " +
                                            std::to_string(parent) + " is not -1 or a joint index below " +
                                            std::to_string(joints));
            up = parent;
        }
        if (up >= 0) throw std::invalid_argument("parents: joint " + std::to_string(j) + " is in a cycle, not a tree");
    }
}

std::vector<int> parents_from_names(const Clip& clip, const std::vector<std::string>& names) {
    const std::size_t joints = clip.joint_count();
    if (names.size() != joints)
        throw std::invalid_argument("parents: " + std::to_string(names.size()) + " names for " +
                                    std::to_string(joints) +
                                    " joints (one per joint in the file's order, - for a root)");
    std::vector<int> parents;
    for (std::size_t j = 0; j < joints; ++j) {
        if (names[j] == "-") {
            parents.push_back(-1);
            continue;
        }
        int found = clip.joint_index(names[j]);
        if (found < 0) found = joint_by_spelling(clip, names[j]);
        if (found < 0)
            throw std::invalid_argument(
                "parents: '" + names[j] + "' (the parent of " + clip.joint_names[j] + ") " +
                (found == -2 ? "matches two joints of the file" : "is not a joint of the file"));
        parents.push_back(found);
    }
    check_tree(parents, joints);
    return parents;
}

std::vector<std::string> parse_parent_names(std::string_view text) {
    std::vector<std::string> names;
    for (const std::string_view field : split_fields(text, ',')) names.emplace_back(trim(field));
    if (names.empty() || (names.size() == 1 && names[0].empty()))
        throw std::invalid_argument("expected one parent name per joint (- for a root), comma-separated");
    return names;
}

namespace {

// Built-in role names, tried in order: HDM05/CMU ASF, Kinect v1, Kinect v2,
// Azure Kinect, the CC_Base rig, Mixamo, the Unreal mannequin, Unity's
// humanoid, MediaPipe Pose (no pelvis: the left hip stands in as the root,
// which only moves the origin).
struct RoleCandidates {
    const char* root;
    const char* left_hip;
    const char* right_hip;
};
constexpr RoleCandidates kBuiltInRoles[] = {
    {"root", "lhipjoint", "rhipjoint"},
    {"HipCenter", "HipLeft", "HipRight"},
    {"SpineBase", "HipLeft", "HipRight"},
    {"Pelvis", "HipLeft", "HipRight"},
    {"CC_Base_Hip", "CC_Base_L_Thigh", "CC_Base_R_Thigh"},
    {"Hips", "LeftUpLeg", "RightUpLeg"},       // Mixamo (often with a "mixamorig:" prefix)
    {"pelvis", "thigh_l", "thigh_r"},          // the Unreal mannequin
    {"Hips", "LeftUpperLeg", "RightUpperLeg"}, // Unity's humanoid bone names
    {"LeftHip", "LeftHip", "RightHip"},
};

}  // namespace

void assign_roles(Clip& clip, const RoleNames& names) {
    if (!names.empty()) {
        auto find = [&](const std::string& joint, const char* role) {
            const int index = clip.joint_index(joint);
            if (index < 0)
                throw ReadError(clip.source, 0,
                                std::string("the ") + role + " joint " + quoted(joint) + " is not in the file");
            return index;
        };
        clip.roles.root = names.root.empty() ? -1 : find(names.root, "root");
        clip.roles.left_hip = names.left_hip.empty() ? -1 : find(names.left_hip, "left hip");
        clip.roles.right_hip = names.right_hip.empty() ? -1 : find(names.right_hip, "right hip");
        return;
    }
    // Exact names first, then the same names as exports spell them.
    for (const RoleCandidates& candidates : kBuiltInRoles) {
        const JointRoles roles{clip.joint_index(candidates.root), clip.joint_index(candidates.left_hip),
                               clip.joint_index(candidates.right_hip)};
        if (roles.complete()) {
            clip.roles = roles;
            return;
        }
    }
    for (const RoleCandidates& candidates : kBuiltInRoles) {
        const JointRoles roles{joint_by_spelling(clip, candidates.root), joint_by_spelling(clip, candidates.left_hip),
                               joint_by_spelling(clip, candidates.right_hip)};
        if (roles.complete()) {
            clip.roles = roles;
            return;
        }
    }
    clip.roles = JointRoles{};
}

void require_finite_positions(const Clip& clip, double max_abs_metres) {
    const std::size_t joints = clip.joint_count();
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const float* p = clip.frame(f);
        for (std::size_t k = 0; k < joints * 3; ++k)
            if (!(std::fabs(static_cast<double>(p[k])) <= max_abs_metres))  // NaN fails too
                throw ReadError(clip.source, 0,
                                "frame " + std::to_string(f + 1) + ", joint " + quoted(clip.joint_names[k / 3]) +
                                    ": position " + std::to_string(p[k]) +
                                    " m is not finite or beyond 1e6 m (check the file's units and angles)");
    }
}

void parse_up_direction(std::string_view text, float up[3]) {
    const std::vector<std::string_view> parts = split_fields(text, ',');
    float read[3] = {0.0f, 0.0f, 0.0f};
    bool numbers = parts.size() == 3;
    for (std::size_t a = 0; a < 3 && numbers; ++a) {
        const std::string item(trim(parts[a]));
        char* stop = nullptr;
        const double v = item.empty() ? 0.0 : std::strtod(item.c_str(), &stop);
        numbers = !item.empty() && stop == item.c_str() + item.size() && std::fabs(v) <= 1e6;
        read[a] = static_cast<float>(v);
    }
    if (!numbers)
        throw std::invalid_argument("expected the sensor's up direction as X,Y,Z (three numbers), got '" +
                                    std::string(text) + "'");
    float turn[9];
    const bool none = read[0] == 0.0f && read[1] == 0.0f && read[2] == 0.0f;
    if (!none && up_rotation(read, 1, turn) != Status::ok)
        throw std::invalid_argument("the up direction '" + std::string(text) +
                                    "' is not a direction (finite, longer than 1e-6; 0,0,0 for none)");
    for (int a = 0; a < 3; ++a) up[a] = read[a];
}

void turn_upright(Clip& clip, const float up[3]) {
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f) return;
    float r[9];
    if (up_rotation(up, clip.up_axis, r) != Status::ok)
        throw ReadError(clip.source, 0,
                        "the sensor's up direction (" + std::to_string(up[0]) + ", " + std::to_string(up[1]) + ", " +
                            std::to_string(up[2]) + ") is not a direction: three finite numbers, not all near 0");
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        float* p = clip.frame(f);
        for (std::size_t j = 0; j < clip.joint_count(); ++j, p += 3) {
            const float x = p[0], y = p[1], z = p[2];
            for (int i = 0; i < 3; ++i) p[i] = r[3 * i] * x + r[3 * i + 1] * y + r[3 * i + 2] * z;
        }
    }
}

void flag_lost_frames(Clip& clip) {
    const std::size_t values = clip.joint_count() * 3;
    clip.lost.assign(clip.frame_count(), 0);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const float* p = clip.frame(f);
        clip.lost[f] = std::all_of(p, p + values, [](float v) { return v == 0.0f; }) ? 1 : 0;
    }
}

}  // namespace host
}  // namespace actionstring
