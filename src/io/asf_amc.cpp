// ASF/AMC (Acclaim) reader with forward kinematics.
//
// Conventions (as in the CMU and HDM05 databases): an `axis ax ay az ORDER`
// line gives the bone's local frame C = R_last · … · R_first (the first axis
// of ORDER applied first); a frame's bone rotation M is composed the same way
// from the bone's `dof` channels in their listed order; the bone's global
// rotation is G = G_parent · C · M · C⁻¹ and its far end sits at
// p_parent + length · G · direction. Lengths are in inches divided by the
// `:units length` value, so metres = value × 0.0254 / length.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "io/formats.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {
namespace {

constexpr double kPi = 3.14159265358979323846;

int dof_code(std::string_view token) {
    static const char* const names[] = {"rx", "ry", "rz", "tx", "ty", "tz", "l"};
    for (int i = 0; i < 7; ++i)
        if (iequals(token, names[i])) return i;
    return -1;
}

Eigen::Matrix3d axis_rotation(int axis, double radians) {
    return Eigen::AngleAxisd(radians, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

// Rotation for angles given per axis (x, y, z) applied in `order` (e.g. "XYZ": x first).
Eigen::Matrix3d euler(const LineScanner& scanner, std::string_view order, const double angles[3], double to_radians) {
    if (order.size() != 3) scanner.fail("expected a rotation order such as XYZ, got " + quoted(order));
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    bool seen[3] = {false, false, false};
    for (char c : order) {
        const int axis = c == 'X' || c == 'x' ? 0 : c == 'Y' || c == 'y' ? 1 : c == 'Z' || c == 'z' ? 2 : -1;
        if (axis < 0 || seen[axis])
            scanner.fail("expected a rotation order of X, Y and Z once each, got " + quoted(order));
        seen[axis] = true;
        m = axis_rotation(axis, angles[axis] * to_radians) * m;
    }
    return m;
}

Eigen::Vector3d parse_vector(const LineScanner& scanner, const std::vector<std::string_view>& words, std::size_t first,
                             const char* what) {
    if (words.size() < first + 3) scanner.fail(std::string("expected three numbers for ") + what);
    return {parse_number(scanner, words[first], what), parse_number(scanner, words[first + 1], what),
            parse_number(scanner, words[first + 2], what)};
}

bool is_section(std::string_view line) { return !line.empty() && line.front() == ':'; }

}  // namespace

AsfSkeleton parse_asf(const std::string& name, std::string_view text) {
    LineScanner scanner(name, text);
    AsfSkeleton skeleton;
    skeleton.source = name;
    double length_unit = 1.0;
    std::string root_axis_order = "XYZ";
    Eigen::Vector3d root_orientation = Eigen::Vector3d::Zero();
    Eigen::Vector3d root_position = Eigen::Vector3d::Zero();
    std::unordered_map<std::string, int> index;
    struct PendingAxis {
        double angles[3];
        std::string order;
        std::size_t line;
    };
    std::vector<PendingAxis> bone_axes;
    bool saw_root = false, saw_hierarchy = false;

    std::string_view raw;
    std::string section;
    while (scanner.next_content(raw, '#')) {
        const std::string_view line = trim(raw);
        const std::vector<std::string_view> words = split_words(line);
        if (is_section(line)) {
            section = std::string(words[0]);
            if (section == ":root") saw_root = true;
            if (section == ":hierarchy") saw_hierarchy = true;
            // Single-line sections (:version 1.10, :name VICON) carry no data we need.
            continue;
        }
        if (section == ":units") {
            if (words.size() < 2) scanner.fail("expected 'mass|length|angle <value>' in :units");
            if (words[0] == "length") {
                length_unit = parse_number(scanner, words[1], "a length unit");
                // Metres per file unit = 0.0254 / length: keep it between a micrometre and a kilometre.
                if (!(length_unit >= 0.0254e-3 && length_unit <= 0.0254e6))
                    scanner.fail("expected a length unit between 2.54e-05 and 25400 (0.0254 / metres per unit), got " +
                                 quoted(words[1]));
            } else if (words[0] == "angle") {
                if (iequals(words[1], "deg")) skeleton.degrees = true;
                else if (iequals(words[1], "rad")) skeleton.degrees = false;
                else scanner.fail("expected 'deg' or 'rad' for the angle unit, got " + quoted(words[1]));
            }
        } else if (section == ":root") {
            if (words[0] == "order") {
                skeleton.root_order.clear();
                for (std::size_t i = 1; i < words.size(); ++i) {
                    const int code = dof_code(words[i]);
                    if (code < 0 || code == 6)
                        scanner.fail("expected a root channel (TX TY TZ RX RY RZ), got " + quoted(words[i]));
                    if (std::find(skeleton.root_order.begin(), skeleton.root_order.end(), code) !=
                        skeleton.root_order.end())
                        scanner.fail("root channel " + quoted(words[i]) + " appears twice");
                    skeleton.root_order.push_back(code);
                }
            } else if (words[0] == "axis") {
                if (words.size() != 2) scanner.fail("expected 'axis <order>' in :root");
                root_axis_order = std::string(words[1]);
            } else if (words[0] == "position") {
                root_position = parse_vector(scanner, words, 1, "the root position");
            } else if (words[0] == "orientation") {
                root_orientation = parse_vector(scanner, words, 1, "the root orientation");
            } else {
                scanner.fail("unexpected " + quoted(words[0]) + " in :root");
            }
        } else if (section == ":bonedata") {
            if (words[0] != "begin") scanner.fail("expected 'begin' of a bone in :bonedata, got " + quoted(words[0]));
            AsfBone bone;
            PendingAxis axis{{0, 0, 0}, "XYZ", scanner.line_number()};
            bool has_direction = false, has_length = false, in_limits = false;
            const std::size_t begin_line = scanner.line_number();
            for (;;) {
                if (!scanner.next_content(raw, '#')) scanner.fail_at(begin_line, "bone is missing its 'end'");
                const std::vector<std::string_view> w = split_words(trim(raw));
                if (w[0] == "end") break;
                if (in_limits && w[0].front() == '(') continue;
                in_limits = false;
                if (w[0] == "id" || w[0] == "bodymass" || w[0] == "cofmass") continue;
                if (w[0] == "name") {
                    if (w.size() != 2) scanner.fail("expected 'name <bone>'");
                    bone.name = std::string(w[1]);
                } else if (w[0] == "direction") {
                    bone.direction = parse_vector(scanner, w, 1, "a direction");
                    has_direction = true;
                } else if (w[0] == "length") {
                    if (w.size() != 2) scanner.fail("expected 'length <value>'");
                    bone.length = parse_number(scanner, w[1], "a bone length");
                    if (bone.length < 0) scanner.fail("expected a bone length ≥ 0");
                    has_length = true;
                } else if (w[0] == "axis") {
                    if (w.size() != 5) scanner.fail("expected 'axis <x> <y> <z> <order>'");
                    for (int a = 0; a < 3; ++a)
                        axis.angles[a] = parse_number(scanner, w[static_cast<std::size_t>(a) + 1], "an axis angle");
                    axis.order = std::string(w[4]);
                    axis.line = scanner.line_number();
                } else if (w[0] == "dof") {
                    for (std::size_t i = 1; i < w.size(); ++i) {
                        const int code = dof_code(w[i]);
                        if (code < 0) scanner.fail("expected a dof (rx ry rz tx ty tz l), got " + quoted(w[i]));
                        if (std::find(bone.dofs.begin(), bone.dofs.end(), code) != bone.dofs.end())
                            scanner.fail("dof " + quoted(w[i]) + " appears twice");
                        bone.dofs.push_back(code);
                    }
                } else if (w[0] == "limits") {
                    in_limits = true;
                } else {
                    scanner.fail("unexpected " + quoted(w[0]) + " in a bone");
                }
            }
            if (bone.name.empty()) scanner.fail_at(begin_line, "bone has no name");
            if (!has_direction || !has_length)
                scanner.fail_at(begin_line, "bone " + quoted(bone.name) + " lacks a direction or length");
            if (bone.name == "root" || index.count(bone.name))
                scanner.fail_at(begin_line, "duplicate bone name " + quoted(bone.name));
            const double norm = bone.direction.norm();
            if (!(norm > 1e-9) && bone.length > 0)
                scanner.fail_at(begin_line, "bone " + quoted(bone.name) + " has a zero direction");
            if (norm > 1e-9) bone.direction /= norm;
            index.emplace(bone.name, static_cast<int>(skeleton.bones.size()));
            skeleton.bones.push_back(std::move(bone));
            bone_axes.push_back(axis);
        } else if (section == ":hierarchy") {
            if (words[0] == "begin" || words[0] == "end") continue;
            int parent = -1;
            if (words[0] != "root") {
                const auto found = index.find(std::string(words[0]));
                if (found == index.end()) scanner.fail("unknown bone " + quoted(words[0]) + " in :hierarchy");
                parent = found->second;
            }
            for (std::size_t i = 1; i < words.size(); ++i) {
                const auto found = index.find(std::string(words[i]));
                if (found == index.end()) scanner.fail("unknown bone " + quoted(words[i]) + " in :hierarchy");
                AsfBone& child = skeleton.bones[static_cast<std::size_t>(found->second)];
                if (child.parent != -1 || found->second == parent)
                    scanner.fail("bone " + quoted(words[i]) + " is given a second parent");
                child.parent = parent == -1 ? -2 : parent;  // −2 marks "child of the root" until resolved
            }
        }
        // Other sections (:documentation, :version, :name, …) are skipped.
    }
    if (!saw_root) scanner.fail_at(0, "no :root section: is this an ASF file?");
    if (!saw_hierarchy) scanner.fail_at(0, "no :hierarchy section");
    if (skeleton.root_order.empty()) skeleton.root_order = {3, 4, 5, 0, 1, 2};

    // Rotations need the angle unit, which :units may give after a bone's axis.
    const double to_radians = skeleton.degrees ? kPi / 180.0 : 1.0;
    LineScanner axis_scanner(name, text);
    for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
        const PendingAxis& axis = bone_axes[b];
        try {
            skeleton.bones[b].axis = euler(axis_scanner, axis.order, axis.angles, to_radians);
        } catch (const ReadError&) {
            throw ReadError(name, axis.line,
                            "expected a rotation order of X, Y and Z once each, got " + quoted(axis.order));
        }
    }
    const double orientation[3] = {root_orientation.x(), root_orientation.y(), root_orientation.z()};
    skeleton.root_axis = euler(axis_scanner, root_axis_order, orientation, to_radians);
    skeleton.length_scale = 0.0254 / length_unit;
    skeleton.root_position = root_position * skeleton.length_scale;
    for (AsfBone& bone : skeleton.bones) bone.length *= skeleton.length_scale;

    // Parents before children: breadth-first from the root; anything left is unconnected.
    for (AsfBone& bone : skeleton.bones) {
        if (bone.parent == -1)
            throw ReadError(name, 0, "bone " + quoted(bone.name) + " is not connected to the root in :hierarchy");
        if (bone.parent == -2) bone.parent = -1;
    }
    std::vector<int> frontier;
    for (std::size_t b = 0; b < skeleton.bones.size(); ++b)
        if (skeleton.bones[b].parent == -1) frontier.push_back(static_cast<int>(b));
    while (!frontier.empty()) {
        std::vector<int> next;
        for (int b : frontier) {
            skeleton.evaluation_order.push_back(b);
            for (std::size_t c = 0; c < skeleton.bones.size(); ++c)
                if (skeleton.bones[c].parent == b) next.push_back(static_cast<int>(c));
        }
        frontier = std::move(next);
    }
    if (skeleton.evaluation_order.size() != skeleton.bones.size())
        throw ReadError(name, 0, "the :hierarchy has a cycle: some bones never reach the root");
    return skeleton;
}

Clip parse_amc(const std::string& name, std::string_view text, const AsfSkeleton& skeleton,
               const ReadOptions& options) {
    LineScanner scanner(name, text);
    const double rate = options.frame_rate_hz > 0 ? options.frame_rate_hz : 120.0;
    const std::size_t bone_count = skeleton.bones.size();
    Clip clip;
    clip.source = name;
    clip.up_axis = options.up_axis >= 0 ? options.up_axis : 1;
    clip.joint_names.push_back("root");
    clip.parents.push_back(-1);
    std::unordered_map<std::string, int> index;
    for (std::size_t b = 0; b < bone_count; ++b) {
        clip.joint_names.push_back(skeleton.bones[b].name);
        clip.parents.push_back(skeleton.bones[b].parent + 1);
        index.emplace(skeleton.bones[b].name, static_cast<int>(b));
    }
    const double length_scale = options.length_scale > 0 ? options.length_scale : skeleton.length_scale;
    const double scale_ratio = length_scale / skeleton.length_scale;
    bool degrees = skeleton.degrees;

    // Header: comments and :keywords up to the first frame number.
    std::string_view raw;
    while (scanner.next_content(raw, '#')) {
        const std::string_view line = trim(raw);
        if (line.front() != ':') {
            scanner.unread();
            break;
        }
        if (iequals(line, ":DEGREES")) degrees = true;
        else if (iequals(line, ":RADIANS")) degrees = false;
    }
    const double to_radians = degrees ? kPi / 180.0 : 1.0;

    std::vector<double> values(bone_count * 7), root_values(6);
    std::vector<std::size_t> seen_in_frame(bone_count, 0);
    std::vector<Eigen::Matrix3d> global(bone_count);
    std::vector<Eigen::Vector3d> joint(bone_count);
    long previous_frame = -1;
    std::size_t frame_line = 0;
    std::size_t frames = 0;
    bool root_seen = false;

    auto finish_frame = [&]() {
        if (!root_seen) scanner.fail_at(frame_line, "frame " + std::to_string(previous_frame) + " has no root line");
        for (std::size_t b = 0; b < bone_count; ++b)
            if (!skeleton.bones[b].dofs.empty() && seen_in_frame[b] != frames + 1)
                scanner.fail_at(frame_line, "frame " + std::to_string(previous_frame) + " has no line for bone " +
                                                quoted(skeleton.bones[b].name));
        // Root.
        Eigen::Vector3d translation = Eigen::Vector3d::Zero();
        Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
        for (std::size_t i = 0; i < skeleton.root_order.size(); ++i) {
            const int code = skeleton.root_order[i];
            if (code < 3) rotation = axis_rotation(code, root_values[i] * to_radians) * rotation;
            else translation[code - 3] = root_values[i];
        }
        const Eigen::Vector3d root_position = skeleton.root_position * scale_ratio + translation * length_scale;
        const Eigen::Matrix3d root_global = skeleton.root_axis * rotation * skeleton.root_axis.transpose();
        for (int b : skeleton.evaluation_order) {
            const AsfBone& bone = skeleton.bones[static_cast<std::size_t>(b)];
            Eigen::Matrix3d motion = Eigen::Matrix3d::Identity();
            Eigen::Vector3d offset = Eigen::Vector3d::Zero();
            double length = bone.length * scale_ratio;
            for (std::size_t i = 0; i < bone.dofs.size(); ++i) {
                const double v = values[static_cast<std::size_t>(b) * 7 + i];
                const int code = bone.dofs[i];
                if (code < 3) motion = axis_rotation(code, v * to_radians) * motion;
                else if (code < 6) offset[code - 3] = v * length_scale;
                else length += v * length_scale;
            }
            const Eigen::Matrix3d& parent_global =
                bone.parent < 0 ? root_global : global[static_cast<std::size_t>(bone.parent)];
            const Eigen::Vector3d& parent_position =
                bone.parent < 0 ? root_position : joint[static_cast<std::size_t>(bone.parent)];
            const Eigen::Matrix3d local = bone.axis * motion * bone.axis.transpose();
            global[static_cast<std::size_t>(b)] = parent_global * local;
            joint[static_cast<std::size_t>(b)] = parent_position + parent_global * (bone.axis * offset) +
                                                 length * (global[static_cast<std::size_t>(b)] * bone.direction);
        }
        for (int a = 0; a < 3; ++a) clip.positions.push_back(static_cast<float>(root_position[a]));
        for (std::size_t b = 0; b < bone_count; ++b)
            for (int a = 0; a < 3; ++a) clip.positions.push_back(static_cast<float>(joint[b][a]));
        clip.times.push_back(static_cast<double>(frames) / rate);
        ++frames;
        root_seen = false;
    };

    std::size_t fast_guess = 0;  // bones come in the same order every frame
    while (scanner.next_content(raw, '#')) {
        const std::vector<std::string_view> words = split_words(raw);
        if (words.size() == 1 && !words[0].empty() && words[0].front() >= '0' && words[0].front() <= '9') {
            const long number = parse_index(scanner, words[0], "a frame number");
            if (previous_frame >= 0) finish_frame();
            if (number <= previous_frame)
                scanner.fail("frame number " + std::to_string(number) + " does not follow " +
                             std::to_string(previous_frame));
            previous_frame = number;
            frame_line = scanner.line_number();
            fast_guess = 0;
            continue;
        }
        if (previous_frame < 0) scanner.fail("expected a frame number before bone values, got " + quoted(words[0]));
        if (words[0] == "root") {
            if (root_seen) scanner.fail("the root appears twice in frame " + std::to_string(previous_frame));
            if (words.size() != skeleton.root_order.size() + 1)
                scanner.fail("root has " + std::to_string(words.size() - 1) + " values, expected " +
                             std::to_string(skeleton.root_order.size()));
            for (std::size_t i = 1; i < words.size(); ++i)
                root_values[i - 1] = parse_number(scanner, words[i], "a root value");
            root_seen = true;
            continue;
        }
        int b = -1;
        if (fast_guess < bone_count && skeleton.bones[fast_guess].name == words[0]) {
            b = static_cast<int>(fast_guess);
        } else {
            const auto found = index.find(std::string(words[0]));
            if (found == index.end())
                scanner.fail("unknown bone " + quoted(words[0]) + " (not in " + skeleton.source + ")");
            b = found->second;
        }
        fast_guess = static_cast<std::size_t>(b) + 1;
        const AsfBone& bone = skeleton.bones[static_cast<std::size_t>(b)];
        if (words.size() != bone.dofs.size() + 1)
            scanner.fail("bone " + quoted(bone.name) + " has " + std::to_string(words.size() - 1) +
                         " values, expected " + std::to_string(bone.dofs.size()));
        if (seen_in_frame[static_cast<std::size_t>(b)] == frames + 1)
            scanner.fail("bone " + quoted(bone.name) + " appears twice in frame " + std::to_string(previous_frame));
        seen_in_frame[static_cast<std::size_t>(b)] = frames + 1;
        for (std::size_t i = 1; i < words.size(); ++i)
            values[static_cast<std::size_t>(b) * 7 + i - 1] = parse_number(scanner, words[i], "a bone value");
    }
    if (previous_frame < 0) scanner.fail_at(0, "no frames: expected a frame number line");
    finish_frame();
    flag_lost_frames(clip);
    assign_roles(clip, options.roles);
    require_finite_positions(clip);
    return clip;
}

}  // namespace host
}  // namespace actionstring
