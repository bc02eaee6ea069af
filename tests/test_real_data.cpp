// Readers on the real datasets in ../shared/data (or $ACTIONSTRING_DATA);
// each case says SKIPPED on stderr and passes vacuously when its data is absent.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"
#include "run/classify.hpp"
#include "run/skeleton.hpp"
#include "train/pipeline.hpp"
#include "data_location.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

std::vector<std::string> lines_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

std::vector<double> numbers_after(const std::string& line, std::size_t skip_words) {
    std::istringstream in(line);
    std::string word;
    for (std::size_t i = 0; i < skip_words; ++i) in >> word;
    std::vector<double> values;
    double v;
    while (in >> v) values.push_back(v);
    return values;
}

// Largest change of any parent–child distance over the clip, in metres.
double bone_length_drift(const Clip& clip, const std::set<int>& skip = {}) {
    double worst = 0;
    for (std::size_t j = 0; j < clip.joint_count(); ++j) {
        const int parent = clip.parents[j];
        if (parent < 0 || skip.count(static_cast<int>(j))) continue;
        double low = 1e9, high = -1e9;
        for (std::size_t f = 0; f < clip.frame_count(); ++f) {
            const float* p = clip.frame(f);
            const Eigen::Vector3d a(p[3 * j], p[3 * j + 1], p[3 * j + 2]);
            const auto q = static_cast<std::size_t>(parent);
            const Eigen::Vector3d b(p[3 * q], p[3 * q + 1], p[3 * q + 2]);
            const double d = (a - b).norm();
            low = std::min(low, d);
            high = std::max(high, d);
        }
        worst = std::max(worst, high - low);
    }
    return worst;
}

double lowest(const Clip& clip, const std::vector<std::string>& joints) {
    double low = 1e9;
    for (const auto& name : joints) {
        const int j = clip.joint_index(name);
        REQUIRE(j >= 0);
        for (std::size_t f = 0; f < clip.frame_count(); ++f)
            low = std::min(low, static_cast<double>(clip.frame(
                                    f)[3 * static_cast<std::size_t>(j) + static_cast<std::size_t>(clip.up_axis)]));
    }
    return low;
}

Eigen::Matrix3d rotation_xyz_degrees(double rx, double ry, double rz) {
    const double k = 3.14159265358979323846 / 180.0;
    return (Eigen::AngleAxisd(rz * k, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(ry * k, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(rx * k, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

}  // namespace

TEST_CASE("HDM05: every listed clip reads, frame counts match, bones keep their length") {
    if (!test::have_data("hdm05/train.tsv")) return;
    std::size_t clips = 0, frames = 0;
    double worst_drift = 0;
    for (const char* list : {"hdm05/train.tsv", "hdm05/val.tsv"}) {
        for (const ClipListEntry& entry : read_clip_list(test::data_dir() + "/" + list)) {
            CAPTURE(entry.path);
            const Clip clip = read_clip(entry);
            // Frame count from the file itself: lines holding only a frame number.
            std::size_t counted = 0;
            for (const std::string& line : lines_of(entry.path))
                counted +=
                    !line.empty() && std::all_of(line.begin(), line.end(), [](char c) { return c >= '0' && c <= '9'; });
            CHECK(clip.frame_count() == counted);
            CHECK(clip.joint_count() == 31);
            CHECK(clip.roles.complete());
            CHECK(clip.up_axis == 1);
            CHECK(clip.times.back() == doctest::Approx(static_cast<double>(counted - 1) / 120.0));
            worst_drift = std::max(worst_drift, bone_length_drift(clip));
            ++clips;
            frames += clip.frame_count();
        }
    }
    CHECK(clips == 232);
    CHECK(frames > 50000);
    CHECK(worst_drift < 1e-5);
    MESSAGE("HDM05: " << clips << " clips, " << frames << " frames, worst bone-length drift " << worst_drift << " m");
}

TEST_CASE("HDM05: feet reach the floor and one joint matches a hand calculation") {
    if (!test::have_data("hdm05/train/squat1Reps/HDM_bd_squat1Reps_001_120.amc")) return;
    const std::string amc = test::data_dir() + "/hdm05/train/squat1Reps/HDM_bd_squat1Reps_001_120.amc";
    const std::string asf = test::data_dir() + "/hdm05/asf/HDM_bd.asf";
    const Clip clip = read_clip(amc, {}, asf);
    const double floor = lowest(clip, {"lfoot", "rfoot", "ltoes", "rtoes"});
    CHECK(floor > -0.03);
    CHECK(floor < 0.06);

    // By hand from the files: the root line of frame 1 and the lhipjoint bone of the ASF.
    std::vector<double> root, direction;
    double length = 0, unit = 0;
    for (const std::string& line : lines_of(amc))
        if (line.rfind("root ", 0) == 0) {
            root = numbers_after(line, 1);
            break;
        }
    const std::vector<std::string> asf_lines = lines_of(asf);
    for (std::size_t i = 0; i < asf_lines.size(); ++i) {
        if (asf_lines[i].find("length") != std::string::npos && unit == 0 && asf_lines[i].find("  length") == 0)
            unit = numbers_after(asf_lines[i], 1).at(0);
        if (asf_lines[i].find("name lhipjoint") != std::string::npos) {
            direction = numbers_after(asf_lines[i + 1], 1);
            length = numbers_after(asf_lines[i + 2], 1).at(0);
        }
    }
    REQUIRE(root.size() == 6);
    REQUIRE(direction.size() == 3);
    REQUIRE(unit > 0);
    const double metres = 0.0254 / unit;
    const Eigen::Vector3d root_position = Eigen::Vector3d(root[0], root[1], root[2]) * metres;
    Eigen::Vector3d dir(direction[0], direction[1], direction[2]);
    dir.normalize();
    // lhipjoint has no dofs and a zero axis: it turns with the root (root order RX RY RZ).
    const Eigen::Vector3d hip =
        root_position + length * metres * (rotation_xyz_degrees(root[3], root[4], root[5]) * dir);
    const float* f = clip.frame(0);
    for (int a = 0; a < 3; ++a) {
        CHECK(f[a] == doctest::Approx(root_position[a]).epsilon(1e-6));
        CHECK(f[3 + a] == doctest::Approx(hip[a]).epsilon(1e-5));
    }
}

TEST_CASE("MSR Action3D: every listed file reads; lost tracking is flagged, not dropped") {
    if (!test::have_data("msr-action3d/train.tsv")) return;
    std::size_t files = 0, lost_frames = 0;
    for (const char* list : {"msr-action3d/train.tsv", "msr-action3d/test.tsv"})
        for (const ClipListEntry& entry : read_clip_list(test::data_dir() + "/" + list)) {
            CAPTURE(entry.path);
            const Clip clip = read_clip(entry);
            std::size_t lines = 0;
            for (const std::string& line : lines_of(entry.path)) lines += !line.empty();
            CHECK(clip.frame_count() * 20 == lines);
            CHECK(clip.roles.complete());
            lost_frames += static_cast<std::size_t>(std::count(clip.lost.begin(), clip.lost.end(), 1));
            ++files;
        }
    CHECK(files == 557);
    const Clip all_zero = read_clip(test::data_dir() + "/msr-action3d/skeletons/a13_s09_e02_skeleton3D.txt");
    CHECK(static_cast<std::size_t>(std::count(all_zero.lost.begin(), all_zero.lost.end(), 1)) ==
          all_zero.frame_count());
    const Clip mostly_lost = read_clip(test::data_dir() + "/msr-action3d/skeletons/a13_s09_e03_skeleton3D.txt");
    CHECK(mostly_lost.frame_count() == 936);
    CHECK(std::count(mostly_lost.lost.begin(), mostly_lost.lost.end(), 1) == 740);
    MESSAGE("MSR Action3D: " << files << " files, " << lost_frames << " lost-tracking frames flagged");
}

TEST_CASE("UTKinect: sequences and their timelines read") {
    if (!test::have_data("utkinect/actionLabel.txt")) return;
    const std::string folder = test::data_dir() + "/utkinect";
    const auto labels = parse_utkinect_labels(folder + "/actionLabel.txt", read_file(folder + "/actionLabel.txt"));
    CHECK(labels.size() == 12);
    for (const auto& sequence : labels) {
        CAPTURE(sequence.first);
        const Clip clip = read_clip(folder + "/joints_" + sequence.first + ".txt");
        std::size_t lines = 0;
        for (const std::string& line : lines_of(folder + "/joints_" + sequence.first + ".txt")) lines += !line.empty();
        CHECK(clip.frame_count() == lines);
        CHECK(std::is_sorted(clip.times.begin(), clip.times.end()));
        CHECK(sequence.second.size() == 10);
        for (const LabelInterval& interval : sequence.second)
            if (interval.valid) {
                CHECK(interval.start_frame / 30.0 >= clip.times.front() - 1.0);
                CHECK(interval.end_frame / 30.0 <= clip.times.back() + 1.0);
            }
    }
}

TEST_CASE("BVH: the engine-rig files read, stand on the floor, and a joint matches a hand calculation") {
    if (!test::have_data("bvh/002_04.bvh")) return;
    for (const char* name : {"002_01.bvh", "002_04.bvh", "007_12.bvh"}) {
        CAPTURE(name);
        const Clip clip = read_clip(test::data_dir() + "/bvh/" + name);
        CHECK(clip.joint_count() >= 100);
        CHECK(clip.up_axis == 1);  // 002_01's extra root turns its Z-up hierarchy upright
        CHECK(clip.roles.complete());
        CHECK(bone_length_drift(clip) < 1e-5);
        const double floor =
            lowest(clip, {"CC_Base_L_ToeBase", "CC_Base_R_ToeBase", "CC_Base_L_Foot", "CC_Base_R_Foot"});
        CHECK(floor > -0.05);
        CHECK(floor < 0.12);
    }
    // 002_04, frame 1: the root CC_Base_Hip sits at OFFSET + its position channels, in centimetres.
    const std::string path = test::data_dir() + "/bvh/002_04.bvh";
    const std::vector<std::string> lines = lines_of(path);
    std::vector<double> offset, first_frame;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].find("ROOT CC_Base_Hip") != std::string::npos) offset = numbers_after(lines[i + 2], 1);
        if (lines[i].rfind("Frame Time:", 0) == 0) {
            first_frame = numbers_after(lines[i + 1], 0);
            break;
        }
    }
    REQUIRE(offset.size() == 3);
    REQUIRE(first_frame.size() > 3);
    const Clip clip = read_clip(path);
    for (int a = 0; a < 3; ++a)
        CHECK(clip.frame(0)[a] ==
              doctest::Approx(0.01 * (offset[static_cast<std::size_t>(a)] + first_frame[static_cast<std::size_t>(a)]))
                  .epsilon(1e-6));
}

TEST_CASE("BVH: CC_Base files of 100 and 101 joints train together on the rig's body joints") {
    if (!test::have_data("bvh/002_01.bvh")) return;
    std::vector<LabelledClip> clips;
    for (const char* name : {"002_01.bvh", "002_04.bvh", "007_12.bvh"})
        clips.push_back({read_clip(test::data_dir() + "/bvh/" + name), name, "cmu"});
    REQUIRE(clips[0].clip.joint_count() == 101);  // an extra root, RL_BoneRoot
    REQUIRE(clips[1].clip.joint_count() == 100);
    TrainingOptions options;
    options.components = 0;
    options.scale_mode = ScaleMode::bone_lengths;
    options.velocity_weight = 1.0;
    options.velocity_span_s = 0.4;
    options.keep_singletons = true;
    options.sigma = 0.1;
    TrainingReport report;
    const ModelData model = train_model(clips, options, &report);
    const ModelView view = model.view();
    CHECK(report.skeleton == "CC_Base rig: 23 of 101 joints");
    CHECK(view.joint_count == 23);
    CHECK(rig_name(view) == "CC_Base rig");
    // Each file, read again whole (100 or 101 joints), is mapped onto the model's joints and recognised.
    std::vector<LabelledClip> again;
    for (const LabelledClip& c : clips) again.push_back({read_clip(c.clip.source), c.label, c.subject});
    conform_to_model(view, again);
    CHECK(clip_accuracy(view, again) == 1.0);
}
