// actionstring host library — motion file formats (ASF/AMC, BVH, Kinect text,
// CSV). Each reader parses from memory (`name` is used in messages) so that
// fuzzers and tests can feed bytes directly; read_clip() opens a file and picks
// the reader by its extension. Every reader throws ReadError on malformed input, naming the
// file, the line and what was expected; none crashes, hangs or returns NaN.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/clip.hpp"
#include "io/sdk_skeletons.hpp"  // the SDKs' joint names and trees

namespace actionstring {
namespace host {

// ---- ASF/AMC (Acclaim; HDM05, CMU) ---------------------------------------------

/// One bone of an ASF skeleton; its joint is the bone's far end.
struct AsfBone {
    std::string name;
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< Unit vector, in the global rest frame.
    double length = 0;                                    ///< Metres.
    Eigen::Matrix3d axis = Eigen::Matrix3d::Identity();   ///< C: local frame from the `axis` angles.
    std::vector<int> dofs;  ///< Channels in file order: 0..2 = rx, ry, rz; 3..5 = tx, ty, tz; 6 = l.
    int parent = -1;        ///< Index into bones, or −1 for the root.
};

/// A parsed ASF file.
struct AsfSkeleton {
    std::string source;
    double length_scale = 0;  ///< Metres per ASF length unit.
    bool degrees = true;
    std::vector<int> root_order;  ///< Root channels in AMC order (same codes as AsfBone::dofs).
    Eigen::Matrix3d root_axis = Eigen::Matrix3d::Identity();
    Eigen::Vector3d root_position = Eigen::Vector3d::Zero();  ///< Metres.
    std::vector<AsfBone> bones;                               ///< In file order.
    std::vector<int> evaluation_order;                        ///< Bones with every parent before its children.
};

AsfSkeleton parse_asf(const std::string& name, std::string_view text);
/// Joint 0 is the root, joint 1 + b the far end of bone b. Rate default 120 Hz.
Clip parse_amc(const std::string& name, std::string_view text, const AsfSkeleton& skeleton,
               const ReadOptions& options = {});

// ---- BVH -------------------------------------------------------------------------

/// Any channel and rotation order per joint, End Sites, several roots.
/// Lengths default to a scale guessed from the body's median height over the
/// clip (m, cm, mm or inches) and the up axis to the mean direction from the
/// root to a joint named like a head (else the axis of the largest extent).
Clip parse_bvh(const std::string& name, std::string_view text, const ReadOptions& options = {});

// ---- Kinect skeleton text ----------------------------------------------------------

/// MSR Action3D's own order of the 20 Kinect v1 joints.
const std::vector<std::string>& msr_action3d_joint_names();

/// MSR Action3D skeletons: `x y z c` per line, 20 lines a frame, y up; no
/// timestamps (rate default 15 Hz). All-zero frames are kept and flagged lost.
Clip parse_msr_skeleton(const std::string& name, std::string_view text, const ReadOptions& options = {});
/// UTKinect joints: `frame_id` then 20 × (x y z) per line; ids are timestamps
/// of a 30 Hz camera (rate overridable), repeated ids kept, decreasing ids refused.
Clip parse_utkinect(const std::string& name, std::string_view text, const ReadOptions& options = {});
/// Generic CSV: a header row `timestamp,<Joint>_x,<Joint>_y,<Joint>_z,…` (also
/// `.x` or ` x` suffixes, any case); timestamps in seconds, positions in metres
/// unless told otherwise.
Clip parse_joint_csv(const std::string& name, std::string_view text, const ReadOptions& options = {});

/// A joint CSV's header, read once, and its rows read one at a time (what
/// parse_joint_csv() reads a file with, and `annotate --live` a stream with).
/// The header's rules are parse_joint_csv()'s; it throws ReadError naming
/// `name` and `line` when it holds no time column (and no frame rate is
/// given) or no joint.
class JointCsvLayout {
public:
    JointCsvLayout(const std::string& name, std::string_view header_line, std::size_t line, const ReadOptions& options);
    const std::vector<std::string>& joint_names() const noexcept { return joint_names_; }
    /// Columns ignored, a unit read from the time column's name.
    const std::vector<std::string>& notes() const noexcept { return notes_; }
    /// Index of the time column, or −1 (then the rows are taken at the given frame rate).
    int time_column() const noexcept { return time_column_; }
    /// Seconds per time unit: given, or stated by the column's name; 0 when neither.
    double time_unit_s() const noexcept { return time_unit_s_; }
    /// One row: its raw time (in the file's unit) and joint_names().size() × 3
    /// positions. A coordinate left empty or written as NaN (nan, NaN, null,
    /// None, NA) is a joint the tracker did not see: the row is then a lost
    /// frame, every position 0 as the readers and the runtime mark lost
    /// tracking, and `untracked` is set. False with `error` saying what was
    /// expected when the row is malformed (a bad or missing timestamp too).
    bool parse_row(std::string_view line, double& raw_time, float* positions, std::string& error,
                   bool& untracked) const;

private:
    void explicit_columns(const std::vector<std::string_view>& header, const ReadOptions& options);

    std::string name_;
    std::size_t line_ = 0;
    char delimiter_ = ',';
    std::size_t columns_ = 0;
    int time_column_ = -1;
    double time_unit_s_ = 0.0;
    std::vector<std::string> joint_names_;
    std::vector<std::array<int, 3>> axes_;
    std::vector<std::string> notes_;
};
/// NTU RGB+D .skeleton text (Kinect v2, 25 joints, 30 Hz, several bodies per
/// frame): the body ReadOptions::body names, else the one that moves most.
Clip parse_ntu_skeleton(const std::string& name, std::string_view text, const ReadOptions& options = {});

/// One labelled interval of a continuous recording (frame ids as in the joint file).
struct LabelInterval {
    std::string label;
    double start_frame = 0;
    double end_frame = 0;
    bool valid = true;  ///< False where the file says NaN.
};
/// UTKinect's actionLabel.txt: sequence name → intervals in file order.
std::vector<std::pair<std::string, std::vector<LabelInterval>>> parse_utkinect_labels(const std::string& name,
                                                                                      std::string_view text);

/// Reads any supported file by its extension (.amc needs `skeleton`, an ASF
/// path; .txt is told apart by its first line: 4 values → MSR Action3D,
/// 1 + 60 → UTKinect), then turns it upright when options.up is given
/// (turn_upright()). Throws ReadError.
Clip read_clip(const std::string& path, const ReadOptions& options = {}, const std::string& skeleton = {});

}  // namespace host
}  // namespace actionstring
