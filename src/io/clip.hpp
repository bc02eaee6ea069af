// actionstring host library — the in-memory clip every reader produces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace actionstring {
namespace host {

/// A file that could not be read: names the file, the line (0 when the
/// problem is not tied to one) and what was expected.
class ReadError : public std::runtime_error {
public:
    ReadError(std::string file, std::size_t line, const std::string& what);
    const std::string& file() const noexcept { return file_; }
    std::size_t line() const noexcept { return line_; }

private:
    std::string file_;
    std::size_t line_;
};

/// Joints the runtime's pose normalisation needs (indices into Clip::joint_names, −1 unknown).
struct JointRoles {
    int root = -1;
    int left_hip = -1;
    int right_hip = -1;
    bool complete() const noexcept { return root >= 0 && left_hip >= 0 && right_hip >= 0; }
};

/// Joint names for the roles, overriding a format's built-in mapping. Empty: use the built-in one.
struct RoleNames {
    std::string root, left_hip, right_hip;
    bool empty() const noexcept { return root.empty() && left_hip.empty() && right_hip.empty(); }
};

/// One recording: joints, per-frame times and joint positions in metres.
struct Clip {
    std::string source;  ///< Where it came from, for messages.
    std::vector<std::string> joint_names;
    std::vector<int> parents;        ///< Parent joint per joint (−1 at a root); empty when the format has none.
    std::vector<double> times;       ///< Seconds, non-decreasing (equal times may repeat).
    std::vector<float> positions;    ///< frames × joints × xyz, metres.
    std::vector<std::uint8_t> lost;  ///< Per frame, 1 when tracking was lost (every joint at the origin).
    int up_axis = 1;                 ///< 0 = x, 1 = y, 2 = z.
    JointRoles roles;
    /// What the reader noticed and a user should know (columns ignored, a
    /// time unit detected, an implausible frame rate); tools print them.
    std::vector<std::string> notes;

    std::size_t joint_count() const noexcept { return joint_names.size(); }
    std::size_t frame_count() const noexcept { return times.size(); }
    const float* frame(std::size_t f) const noexcept { return positions.data() + f * joint_count() * 3; }
    float* frame(std::size_t f) noexcept { return positions.data() + f * joint_count() * 3; }
    /// Index of a joint by exact name, or −1.
    int joint_index(std::string_view name) const noexcept;
    /// Seconds from the first to the last frame.
    double duration() const noexcept { return times.empty() ? 0.0 : times.back() - times.front(); }
};

/// What a reader may be told about a file that the file itself does not say.
struct ReadOptions {
    /// Frames per second for formats without timing (AMC: 120, MSR Action3D: 15,
    /// UTKinect ids: 30). 0 keeps the format's default.
    double frame_rate_hz = 0.0;
    /// Metres per file unit. 0 keeps the format's own rule (ASF from :units,
    /// BVH and joint CSV guessed from the body's height, Kinect text in metres).
    double length_scale = 0.0;
    /// Vertical axis, or −1 for the format's rule (BVH: detected).
    int up_axis = -1;
    /// Seconds per unit of a joint CSV's time column; 0 reads the unit from
    /// the column's name, else from the frame spacing (a rate of 5 Hz–1 kHz).
    double time_unit_s = 0.0;
    /// A joint CSV's layout when no spelling rule fits: "time=COLUMN,JOINT=X:Y:Z,…"
    /// (header names, case-insensitive). Empty: the columns are recognised by name.
    std::string columns;
    /// Which body of a multi-body file (NTU RGB+D), counted from 0 in order of
    /// appearance; −1 takes the one that moves most.
    int body = -1;
    /// Overrides the built-in joint-role mapping.
    RoleNames roles;
    /// Each joint's parent by name, in the file's joint order, "-" for a root:
    /// the skeleton's tree for a file that gives none (a CSV of a rig no
    /// depth-camera SDK names), or instead of the file's. Empty: the file's
    /// own, else a depth-camera SDK's by the joint names (sdk_parents()).
    std::vector<std::string> parents;
    /// The sensor's up direction in the file's coordinates, when it is known
    /// and differs from the up axis (a Kinect mounted high or low, whose floor
    /// plane normal it reports): every frame is turned at reading so that it
    /// lies along the axis (turn_upright()), as AnnotatorConfig::up turns a
    /// device's frames. All zeros: as stored.
    float up[3] = {0.0f, 0.0f, 0.0f};
};

/// Metres per unit of a length unit's name: m, dm, cm, mm or in. Throws
/// std::invalid_argument saying what was expected.
double metres_per_unit(std::string_view unit);

/// Metres per file unit for a body `height` units tall along its up axis,
/// for files that do not state their unit (BVH, joint CSV): m below 3, dm
/// below 30, inches below 110 (a 1.0–2.8 m person), cm below 300, else mm.
double metres_per_unit_for_height(double height);

/// The body's median height along `up_axis` (the span from its lowest to its
/// highest joint) over the frames that are not all zeros (lost), in the
/// clip's units; 0 when every frame is lost.
double median_body_height(const Clip& clip, int up_axis);

/// Reads a sensor's up direction written as X,Y,Z (three numbers; 0,0,0 for
/// none) into `up`. Throws std::invalid_argument saying what was expected:
/// not three numbers, or not a direction (not finite, or shorter than 1e-6).
void parse_up_direction(std::string_view text, float up[3]);

/// Turns every frame of `clip` by the smallest rotation that puts `up` (the
/// sensor's up direction in the clip's coordinates) along clip.up_axis: the
/// runtime's up_rotation(), about the origin (a pose is made relative to its
/// root, so where it turns about changes nothing). Lost frames (all zeros)
/// stay lost. `up` all zeros: nothing changes. Throws ReadError naming the
/// clip's file when `up` is not a direction (not finite, or shorter than 1e-6).
void turn_upright(Clip& clip, const float up[3]);

/// A joint name as exports spell it differently, for matching: lower case,
/// without '_', '-', '.' or spaces, and without a namespace ("HIP_LEFT",
/// "hip-left" and "mixamorig:HipLeft" all give "hipleft").
std::string joint_spelling_key(std::string_view name);

/// Index of the joint spelled like `name` (joint_spelling_key(): HIP_LEFT,
/// hip_left, HipLeft), −1 when none is, −2 when two are.
int joint_by_spelling(const Clip& clip, std::string_view name);

/// Checks that `parents` (one per joint, −1 at a root) is a tree of `joints`
/// joints: throws std::invalid_argument saying what is wrong (a count that is
/// not the joints', an index out of range, a cycle).
void check_tree(const std::vector<int>& parents, std::size_t joints);

/// The parents `names` give (one per joint in the clip's order: a joint's
/// name, matched as exports spell it, or "-" for a root), checked by
/// check_tree(). Throws std::invalid_argument naming the name it cannot place.
std::vector<int> parents_from_names(const Clip& clip, const std::vector<std::string>& names);

/// "-,Hips,Spine,…" → one parent name per joint; throws std::invalid_argument
/// when it names none.
std::vector<std::string> parse_parent_names(std::string_view text);

/// Sets clip.roles from `names` when given, else from the built-in mappings
/// (HDM05/CMU ASF, Kinect v1 and v2, the CC_Base rig). Throws ReadError when a
/// named joint does not exist.
void assign_roles(Clip& clip, const RoleNames& names);

/// Throws ReadError naming the file, the frame and the joint when a position
/// is not finite or beyond `max_abs_metres` (every reader's last step: no
/// reader returns a position a pose could not be made from).
void require_finite_positions(const Clip& clip, double max_abs_metres = 1.0e6);

/// Marks frames whose joints are all exactly at the origin (lost tracking).
void flag_lost_frames(Clip& clip);

}  // namespace host
}  // namespace actionstring
