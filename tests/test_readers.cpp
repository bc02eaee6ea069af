// Readers on small hand-written files: formats, conventions and every kind of bad input.
#include <doctest/doctest.h>

#include <fstream>

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"

using namespace actionstring::host;

namespace {

// A two-bone ASF: a hip joint straight down-left, then a femur with an axis and dofs.
const char* const kAsf =
    "# test skeleton\n"
    ":version 1.10\n"
    ":name test\n"
    ":units\n  mass 1.0\n  length 0.45\n  angle deg\n"
    ":documentation\n  anything here\n"
    ":root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n   position 0 0 0\n   orientation 0 0 0\n"
    ":bonedata\n"
    "  begin\n     id 1\n     name lhipjoint\n     direction 1 0 0\n     length 4.5\n     axis 0 0 0 XYZ\n  end\n"
    "  begin\n     id 2\n     name lfemur\n     direction 0 -1 0\n     length 9\n     axis 0 0 90 XYZ\n"
    "    dof rx ry rz\n    limits (-160.0 20.0)\n           (-70.0 70.0)\n           (-60.0 70.0)\n  end\n"
    "  begin\n     id 3\n     name rhipjoint\n     direction -1 0 0\n     length 4.5\n     axis 0 0 0 XYZ\n  end\n"
    ":hierarchy\n  begin\n    root lhipjoint rhipjoint\n    lhipjoint lfemur\n  end\n";

std::string amc(const std::string& frames) { return "#!OML:ASF \xFC test\r\n:FULLY-SPECIFIED\r\n:DEGREES\n" + frames; }

void check_error(const std::function<void()>& read, std::size_t line, const std::string& fragment) {
    try {
        read();
        FAIL("no ReadError; expected one at line " << line << " mentioning '" << fragment << "'");
    } catch (const ReadError& error) {
        const std::string message = error.what();
        CAPTURE(message);
        CHECK(error.line() == line);
        CHECK(message.find(fragment) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("ASF units, axes and hierarchy") {
    const AsfSkeleton s = parse_asf("t.asf", kAsf);
    REQUIRE(s.bones.size() == 3);
    CHECK(s.length_scale == doctest::Approx(0.0254 / 0.45));
    CHECK(s.bones[0].length == doctest::Approx(4.5 * 0.0254 / 0.45));  // 0.254 m
    CHECK(s.bones[1].parent == 0);
    CHECK(s.bones[2].parent == -1);
    CHECK(s.bones[1].dofs == std::vector<int>{0, 1, 2});
    // axis 0 0 90: C turns x into y.
    CHECK((s.bones[1].axis * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
}

TEST_CASE("AMC forward kinematics, worked by hand") {
    const AsfSkeleton s = parse_asf("t.asf", kAsf);
    // Frame 1: root at (45, 90, 0) units and turned 90° about y; the femur's rx = 90°
    // is a turn about C·x = global y, which leaves a bone pointing down pointing down.
    const Clip clip =
        parse_amc("t.amc", amc("1\r\nroot 45 90 0 0 90 0\nlfemur 90 0 0\n2\nroot 0 0 0 0 0 0\nlfemur 0 0 90\n"), s);
    REQUIRE(clip.frame_count() == 2);
    REQUIRE(clip.joint_count() == 4);
    CHECK(clip.times[1] == doctest::Approx(1.0 / 120.0));
    const double u = 0.0254 / 0.45;
    const float* f0 = clip.frame(0);
    CHECK(f0[0] == doctest::Approx(45 * u));
    CHECK(f0[1] == doctest::Approx(90 * u));
    // Root yaw 90° (about y) maps +x to −z: lhipjoint (1, 0, 0) × 4.5 ends at root + (0, 0, −4.5).
    CHECK(f0[3] == doctest::Approx(45 * u).epsilon(1e-6));
    CHECK(f0[5] == doctest::Approx(-4.5 * u).epsilon(1e-6));
    // Femur: motion rx = 90° in the bone frame C (x_C = global y), i.e. a turn about global y,
    // which leaves a bone pointing down (0, −1, 0) unchanged: knee 9 units below the hip.
    CHECK(f0[6] == doctest::Approx(f0[3]).epsilon(1e-6));
    CHECK(f0[7] == doctest::Approx(f0[4] - 9 * u).epsilon(1e-6));
    CHECK(f0[8] == doctest::Approx(f0[5]).epsilon(1e-6));
    // Frame 2: rz = 90° in the bone frame; z_C = global z, so down (0, −1, 0) turns to +x.
    const float* f1 = clip.frame(1);
    CHECK(f1[3] == doctest::Approx(4.5 * u));
    CHECK(f1[6] == doctest::Approx(f1[3] + 9 * u).epsilon(1e-6));
    CHECK(f1[7] == doctest::Approx(f1[4]).scale(1.0).epsilon(1e-6));
    CHECK(clip.roles.root == 0);
    CHECK(clip.roles.left_hip == 1);
    CHECK(clip.roles.right_hip == 3);
}

TEST_CASE("ASF/AMC bad input names the file, line and what was expected") {
    const AsfSkeleton s = parse_asf("t.asf", kAsf);
    check_error([&] { parse_amc("t.amc", amc(""), s); }, 0, "no frames");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 2\n"), s); }, 6,
                "has 2 values, expected 3");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 x 3\n"), s); }, 6,
                "expected a bone value, got 'x'");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 nan 3\n"), s); }, 6, "finite");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 inf 3\n"), s); }, 6, "finite");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 1e300 3\n"), s); }, 6, "out of range");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 2 3\nrtibia 4\n"), s); }, 7,
                "unknown bone 'rtibia'");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\n2\nroot 0 0 0 0 0 0\nlfemur 0 0 0\n"), s); }, 4,
                "no line for bone 'lfemur'");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 2 3\n1\n"), s); }, 7, "does not follow");
    check_error([&] { parse_amc("t.amc", amc("1\nroot 0 0 0 0 0 0\nlfemur 1 2 3\n2\nroot 0 0 0"), s); }, 8,
                "root has 3 values");
    check_error([&] { parse_amc("t.amc", amc("lfemur 1 2 3\n"), s); }, 4, "expected a frame number");
    check_error([&] { parse_asf("x.asf", ""); }, 0, "no :root section");
    check_error([&] { parse_asf("x.asf", "garbage\x01\x02 text\n"); }, 0, "no :root section");
    std::string asf = kAsf;
    check_error([&] { parse_asf("x.asf", asf.substr(0, asf.find(":hierarchy"))); }, 0, "no :hierarchy");
    std::string duplicate = asf;
    duplicate.replace(duplicate.find("name rhipjoint"), 14, "name lhipjoint");
    check_error([&] { parse_asf("x.asf", duplicate); }, 34, "duplicate bone name 'lhipjoint'");
    std::string bad_order = asf;
    bad_order.replace(bad_order.find("0 0 90 XYZ"), 10, "0 0 90 XXZ");
    check_error([&] { parse_asf("x.asf", bad_order); }, 28, "rotation order");
    std::string orphan = asf;
    orphan.replace(orphan.find("    lhipjoint lfemur\n"), 21, "");
    check_error([&] { parse_asf("x.asf", orphan); }, 0, "'lfemur' is not connected");
    std::string unknown = asf;
    unknown.replace(unknown.find("lhipjoint lfemur"), 16, "lhipjoint lfoot");
    check_error([&] { parse_asf("x.asf", unknown); }, 44, "unknown bone 'lfoot'");
    check_error([&] { parse_asf("x.asf", asf.substr(0, asf.find("  end\n  begin\n     id 2"))); }, 16,
                "missing its 'end'");
    check_error([&] { read_clip("/nonexistent/x.amc", {}, "/nonexistent/x.asf"); }, 0, "cannot open");
    check_error([&] { read_clip("/nonexistent/x.amc"); }, 0, "needs its ASF skeleton");
}

TEST_CASE("BVH channel orders, End Sites, several roots, units and up axis") {
    // Two roots; the second chain is Z-up in its own offsets but turned by its root's channels.
    const std::string bvh =
        "HIERARCHY\n"
        "ROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
        "  JOINT Spine\n  {\n    OFFSET 0 50 0\n    CHANNELS 3 Xrotation Yrotation Zrotation\n"
        "    JOINT Head\n    {\n      OFFSET 0 60 0\n      CHANNELS 3 Zrotation Yrotation Xrotation\n"
        "      End Site\n      {\n        OFFSET 0 10 0\n      }\n    }\n  }\n"
        "  JOINT LeftUpLeg\n  {\n    OFFSET -10 0 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
        "    JOINT LeftLeg\n    {\n      OFFSET 0 -80 0\n      CHANNELS 3 Zrotation Xrotation Yrotation\n"
        "      End Site\n      {\n        OFFSET 0 -10 0\n      }\n    }\n  }\n"
        "}\n"
        "ROOT Prop\n{\n  OFFSET 100 0 0\n  CHANNELS 3 Xposition Yposition Zposition\n}\n"
        "MOTION\nFrames: 2\nFrame Time: 0.02\n"
        "0 90 0  0 0 0  0 0 0  0 0 0  90 0 0  0 0 0  1 2 3\r\n"
        "0 90 0  90 0 0  0 0 90  0 0 0  0 0 0  0 0 0  0 0 0\n";
    const Clip clip = parse_bvh("t.bvh", bvh);
    REQUIRE(clip.joint_count() == 6);
    REQUIRE(clip.frame_count() == 2);
    CHECK(clip.times[1] == doctest::Approx(0.02));
    CHECK(clip.up_axis == 1);
    CHECK(clip.parents == std::vector<int>{-1, 0, 1, 0, 3, -1});
    // Height ≈ 110 units from knee to head over the clip → centimetres.
    const float* f0 = clip.frame(0);
    CHECK(f0[1] == doctest::Approx(0.9));              // hips at 90 cm
    CHECK(f0[7] == doctest::Approx(0.9 + 0.5 + 0.6));  // head straight above
    // Left leg: Zrotation 90 on LeftUpLeg turns the shin (0, −80, 0) to (80, 0, 0).
    CHECK(f0[12] == doctest::Approx(-0.1 + 0.8));
    CHECK(f0[13] == doctest::Approx(0.9).epsilon(1e-6));
    // Prop: its own root, offset plus channels.
    CHECK(f0[15] == doctest::Approx(1.01));
    CHECK(f0[16] == doctest::Approx(0.02));
    // Frame 2: hips turned 90° about z: the spine (0, 50, 0) points to −x; the Spine's
    // Zrotation 90 turns the head offset further, to −y.
    const float* f1 = clip.frame(1);
    CHECK(f1[3] == doctest::Approx(-0.5));
    CHECK(f1[6] == doctest::Approx(-0.5).epsilon(1e-6));
    CHECK(f1[7] == doctest::Approx(0.9 - 0.6));
}

TEST_CASE("BVH bad input") {
    const std::string head = "HIERARCHY\nROOT A\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Xposition Yposition Zposition\n";
    check_error([&] { parse_bvh("t.bvh", ""); }, 0, "empty file");
    check_error([&] { parse_bvh("t.bvh", "HIERARCHY\nROOT A\n{\n  OFFSET 0 0\n"); }, 4, "file ends");
    check_error([&] { parse_bvh("t.bvh", head + "}\nMOTION\nFrames: 2\nFrame Time: 0.1\n1 2 3\n"); }, 10,
                "after 1 of 2 frames");
    check_error([&] { parse_bvh("t.bvh", head + "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n1 2\n"); }, 10,
                "has 2 values, expected 3");
    check_error([&] { parse_bvh("t.bvh", head + "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n1 2 3\n4 5 6\n"); }, 11,
                "more frame lines");
    check_error([&] { parse_bvh("t.bvh", head + "}\nMOTION\nFrames: 1\nFrame Time: 0\n1 2 3\n"); }, 9,
                "positive frame time");
    check_error([&] { parse_bvh("t.bvh", head + "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n1 nan 3\n"); }, 10, "finite");
    check_error([&] { parse_bvh("t.bvh", head + "  JOINT A\n  {\n"); }, 6, "duplicate joint name 'A'");
    check_error([&] { parse_bvh("t.bvh", "HIERARCHY\nROOT A\n{\n  OFFSET 0 0 0\n  CHANNELS 2 Xposition Wrotation\n"); },
                5, "expected a channel such as");
    check_error([&] { parse_bvh("t.bvh", "HIERARCHY\nROOT A\n{\n  OFFSET 0 0 0\n  CHANNELS 9 Xposition\n"); }, 5,
                "at most 6 channels");
    std::string deep = "HIERARCHY\nROOT J0\n{\nOFFSET 0 0 0\n";
    for (int i = 1; i < 400; ++i) deep += "JOINT J" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n";
    check_error([&] { parse_bvh("t.bvh", deep); }, 773, "nested deeper");  // JOINT J257 on line 3·257 + 2
}

TEST_CASE("MSR Action3D text: 20 joint lines per frame, lost frames kept and flagged") {
    std::string text;
    for (int f = 0; f < 3; ++f)
        for (int j = 0; j < 20; ++j) {
            const bool lost = f == 1;
            text += lost ? "0 0 0 0\n" : std::to_string(0.01 * j) + " " + std::to_string(-1.0 + 0.08 * j) + " 2.5 1\n";
        }
    const Clip clip = parse_msr_skeleton("a.txt", text);
    CHECK(clip.frame_count() == 3);
    CHECK(clip.times[2] == doctest::Approx(2.0 / 15.0));
    CHECK(clip.lost == std::vector<std::uint8_t>{0, 1, 0});
    CHECK(clip.joint_names[19] == "Head");
    CHECK(clip.roles.root == 6);
    check_error([&] { parse_msr_skeleton("a.txt", text + "1 2 3 4\n"); }, 61, "1 of 20 joint lines");
    check_error([&] { parse_msr_skeleton("a.txt", "1 2 3\n"); }, 1, "expected 4 values");
    check_error([&] { parse_msr_skeleton("a.txt", "1 2 3 4\n1 2 3e999 4\n"); }, 2, "expected a coordinate");
    check_error([&] { parse_msr_skeleton("a.txt", "\n\n"); }, 0, "empty file");
}

TEST_CASE("UTKinect text and labels") {
    std::string line = " 0.1 0.2 2.0";
    std::string values;
    for (int j = 0; j < 20; ++j) values += line;
    const std::string text = "190" + values + "\n190" + values + "\n194" + values + "\n";
    const Clip clip = parse_utkinect("j.txt", text);
    CHECK(clip.frame_count() == 3);
    CHECK(clip.times[0] == clip.times[1]);
    CHECK(clip.times[2] == doctest::Approx(194.0 / 30.0));
    check_error([&] { parse_utkinect("j.txt", text + "150" + values + "\n"); }, 4, "comes after");
    check_error([&] { parse_utkinect("j.txt", "190 1 2 3\n"); }, 1, "expected a frame id and 60 coordinates");
    check_error([&] { parse_utkinect("j.txt", "-4" + values + "\n"); }, 1, "frame id");
    const auto labels = parse_utkinect_labels("l.txt", "s01_e01\nwalk: 252 390\npush: NaN NaN\ns01_e02\nwalk: 1 2\n");
    REQUIRE(labels.size() == 2);
    CHECK(labels[0].second.size() == 2);
    CHECK(labels[0].second[0].end_frame == 390);
    CHECK_FALSE(labels[0].second[1].valid);
    check_error([&] { parse_utkinect_labels("l.txt", "walk: 1 2\n"); }, 1, "sequence name before");
    check_error([&] { parse_utkinect_labels("l.txt", "s01\nwalk: 5 2\n"); }, 2, "ends before it starts");
}

TEST_CASE("a list entry with an interval reads only the frames inside it") {
    std::string values;
    for (int j = 0; j < 20; ++j) values += " 0.1 0.2 2.0";
    const std::string path = (std::filesystem::temp_directory_path() / "actionstring_interval_test.txt").string();
    {
        std::ofstream out(path);
        out << "190" << values << "\n194" << values << "\n198" << values << "\n202" << values << "\n";
    }
    ClipListEntry entry;
    entry.path = path;
    entry.has_interval = true;
    entry.start_s = 194.0 / 30.0;
    entry.end_s = 198.0 / 30.0;
    const Clip cut = read_clip(entry);
    REQUIRE(cut.frame_count() == 2);
    CHECK(cut.times[0] == doctest::Approx(194.0 / 30.0));
    CHECK(cut.positions.size() == 2 * 20 * 3);
    CHECK(cut.lost.size() == 2);
    entry.start_s = 10.0;
    entry.end_s = 11.0;
    check_error([&] { read_clip(entry); }, 0, "no frame between");
    std::filesystem::remove(path);
}

TEST_CASE("a sensor's up direction: a list's up column or the read options turn every frame upright") {
    // An upright pose (20 joints, heights along y) as a sensor pitched 20° sees it: each point R·q,
    // so the sensor's up in the file's coordinates is R·e_y. The second frame is lost (all zeros).
    const double pitch = 20.0 * 3.14159265358979 / 180.0;
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
    std::vector<Eigen::Vector3d> upright;
    for (int j = 0; j < 20; ++j) upright.emplace_back(0.05 * (j % 5) - 0.1, 0.1 * j, 2.0 + 0.02 * (j % 3));
    std::ostringstream text;
    text.precision(9);
    for (int f = 0; f < 3; ++f) {
        text << 190 + 4 * f;
        for (const Eigen::Vector3d& q : upright) {
            const Eigen::Vector3d p = f == 1 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(tilt * q);
            text << ' ' << p.x() << ' ' << p.y() << ' ' << p.z();
        }
        text << '\n';
    }
    const std::string path = (std::filesystem::temp_directory_path() / "actionstring_up_test.txt").string();
    write_file(path, text.str());
    const Eigen::Vector3d up = tilt * Eigen::Vector3d::UnitY();
    auto check_upright = [&](const Clip& clip) {
        REQUIRE(clip.frame_count() == 3);
        for (std::size_t f : {std::size_t{0}, std::size_t{2}})
            for (std::size_t j = 0; j < 20; ++j)
                for (std::size_t a = 0; a < 3; ++a)
                    CHECK(clip.frame(f)[3 * j + a] ==
                          doctest::Approx(upright[j][static_cast<Eigen::Index>(a)]).epsilon(1e-5));
        for (std::size_t k = 0; k < 60; ++k) CHECK(clip.frame(1)[k] == 0.0f);  // still lost
        CHECK(clip.lost[1] == 1);
    };
    // Read as stored, the pose is tilted.
    const Clip stored = read_clip(path);
    CHECK(std::fabs(stored.frame(0)[3 * 19 + 2] - upright[19].z()) > 0.5);
    // The read options' up.
    ReadOptions read;
    for (int a = 0; a < 3; ++a) read.up[a] = static_cast<float>(up[a]);
    check_upright(read_clip(path, read));
    // A list's up column, which a line's own value sets (any length: a direction).
    std::ostringstream list;
    list.precision(9);
    list << "path\tlabel\tsubject\tup\n"
         << path << "\twave\ts1\t" << 3 * up.x() << ',' << 3 * up.y() << ',' << 3 * up.z() << '\n'
         << path << "\twave\ts2\t0,0,0\n";
    const std::vector<ClipListEntry> entries = parse_clip_list("l.tsv", list.str(), "/");
    REQUIRE(entries.size() == 2);
    CHECK(entries[0].up[1] == doctest::Approx(3 * up.y()));
    check_upright(read_clip(entries[0]));
    // 0,0,0 gives none: the read options' up then applies, else the file as stored.
    CHECK(read_clip(entries[1]).positions == stored.positions);
    check_upright(read_clip(entries[1], read));
    // A line's own up wins over the read options'.
    ReadOptions other;
    other.up[0] = 1.0f;
    check_upright(read_clip(entries[0], other));
    // An up along the axis turns nothing, bit for bit.
    ReadOptions along;
    along.up[1] = 2.5f;
    CHECK(read_clip(path, along).positions == stored.positions);
    // Bad values name the line (a list) or the file (turn_upright).
    const std::string header = "path\tlabel\tsubject\tup\n";
    check_error([&] { parse_clip_list("l.tsv", header + "a\tb\tc\t0,1\n", "d"); }, 2, "X,Y,Z (three numbers)");
    check_error([&] { parse_clip_list("l.tsv", header + "a\tb\tc\t0,1,x\n", "d"); }, 2, "up direction");
    check_error([&] { parse_clip_list("l.tsv", header + "a\tb\tc\t0,1e-9,0\n", "d"); }, 2, "not a direction");
    check_error([&] { parse_clip_list("l.tsv", header + "a\tb\tc\t\n", "d"); }, 2, "empty up");
    ReadOptions bad;
    bad.up[2] = std::numeric_limits<float>::infinity();
    check_error([&] { read_clip(path, bad); }, 0, "not a direction");
    std::filesystem::remove(path);

    // The one parser of X,Y,Z (lists, train/eval/annotate --up, training configs).
    float parsed[3] = {9.0f, 9.0f, 9.0f};
    parse_up_direction(" 0.1, 0.9 ,-0.2", parsed);
    CHECK(parsed[0] == 0.1f);
    CHECK(parsed[1] == 0.9f);
    CHECK(parsed[2] == -0.2f);
    parse_up_direction("0,0,0", parsed);
    CHECK((parsed[0] == 0.0f && parsed[1] == 0.0f && parsed[2] == 0.0f));
    for (const char* wrong : {"1,2", "1,2,3,4", "a,b,c", "0,nan,1", "0,inf,1", "1,,2", "", "0,1e7,0"}) {
        CAPTURE(wrong);
        CHECK_THROWS_WITH_AS(parse_up_direction(wrong, parsed), doctest::Contains("X,Y,Z (three numbers)"),
                             std::invalid_argument);
    }
    CHECK_THROWS_WITH_AS(parse_up_direction("0,1e-9,0", parsed), doctest::Contains("not a direction"),
                         std::invalid_argument);
    CHECK(parsed[1] == 0.0f);  // a refused value leaves it as it was
}

TEST_CASE("joint CSV") {
    const std::string text =
        "timestamp,SpineBase_x,SpineBase_y,SpineBase_z,HipLeft.x,HipLeft.y,HipLeft.z,HipRight X,HipRight Y,HipRight Z\n"
        "0.0, 0,1,2, -0.1,1,2, 0.1,1,2\n0.033,0,1,2,-0.1,1,2,0.1,1,2\n";
    const Clip clip = parse_joint_csv("k.csv", text);
    CHECK(clip.joint_names == std::vector<std::string>{"SpineBase", "HipLeft", "HipRight"});
    CHECK(clip.roles.complete());
    CHECK(clip.times[1] == doctest::Approx(0.033));
    check_error([&] { parse_joint_csv("k.csv", "frame,a_x,a_y,a_z\n"); }, 1, "'timestamp'");
    check_error([&] { parse_joint_csv("k.csv", "timestamp,a_x,a_y,b_z\n"); }, 1, "found none among 4 columns");
    check_error([&] { parse_joint_csv("k.csv", "timestamp,a_x,a_y,a_z,a_x,a_y,a_z\n"); }, 1,
                "both give the x of joint 'a'");
    check_error([&] { parse_joint_csv("k.csv", "timestamp,a_x,a_y,a_z\n1,2,3\n"); }, 2, "expected 4 columns");
    check_error([&] { parse_joint_csv("k.csv", "timestamp,a_x,a_y,a_z\n1,2,3,4\n0.5,2,3,4\n"); }, 3, "earlier");
    check_error([&] { parse_joint_csv("k.csv", "timestamp,a_x,a_y,a_z\n"); }, 1, "no data rows");
}

TEST_CASE("joint CSV as tools export it: spellings, separators, extra columns, time units") {
    // A Kinect recorder's export: CamelCase axes, trailing commas, an id and a label column, milliseconds from 0.
    const std::string kinect =
        "Timestamp,HipCenterX,HipCenterY,HipCenterZ,HipLeftX,HipLeftY,HipLeftZ,HipRightX,HipRightY,HipRightZ,User-ID,Action,\n"
        "0,0,1,2,-0.1,1,2,0.1,1,2,7,wave,\n33,0,1,2,-0.1,1,2,0.1,1,2,7,wave,\n67,0,1,2,-0.1,1,2,0.1,1,2,7,wave,\n";
    const Clip k = parse_joint_csv("export.csv", kinect);
    CHECK(k.joint_names == std::vector<std::string>{"HipCenter", "HipLeft", "HipRight"});
    CHECK(k.roles.complete());
    CHECK(k.times[1] == doctest::Approx(0.033));  // milliseconds, detected from the spacing
    REQUIRE(k.notes.size() == 2);
    CHECK(k.notes[0] == "2 columns ignored: 'User-ID', 'Action'");
    CHECK(k.notes[1].find("milliseconds") != std::string::npos);
    // Told the unit is seconds, the 0.03 Hz stream that makes is flagged, not taken silently.
    ReadOptions seconds;
    seconds.time_unit_s = 1.0;
    const Clip slow = parse_joint_csv("export.csv", kinect, seconds);
    CHECK(slow.times[1] == doctest::Approx(33.0));
    CHECK(slow.notes.back().find("warning: the median frame spacing gives 0.029") == 0);

    // Semicolons, case-insensitive spellings of one joint, a unit in the time column's name, Azure Kinect roles.
    const std::string azure =
        "timestamp_us;PELVIS_X;pelvis_y;Pelvis Z;HIP_LEFT_X;HIP_LEFT_Y;HIP_LEFT_Z;HIP_RIGHT.x;HIP_RIGHT.y;HIP_RIGHT.z\n"
        "1000000;0;1;2;-0.1;1;2;0.1;1;2\n1033333;0;1;2;-0.1;1;2;0.1;1;2\n";
    const Clip a = parse_joint_csv("azure.csv", azure);
    CHECK(a.joint_names == std::vector<std::string>{"PELVIS", "HIP_LEFT", "HIP_RIGHT"});
    CHECK(a.roles.root == 0);
    CHECK(a.roles.left_hip == 1);
    CHECK(a.times[1] - a.times[0] == doctest::Approx(0.033333));

    // Tabs, MediaPipe Pose names (no pelvis: the left hip is the root), seconds.
    const std::string mediapipe =
        "time\tleft_hip_x\tleft_hip_y\tleft_hip_z\tright_hip_x\tright_hip_y\tright_hip_z\tnose_x\tnose_y\tnose_z\n"
        "0.00\t-0.1\t1\t2\t0.1\t1\t2\t0\t1.6\t2\n0.04\t-0.1\t1\t2\t0.1\t1\t2\t0\t1.6\t2\n";
    const Clip m = parse_joint_csv("pose.tsv", mediapipe);
    CHECK(m.joint_count() == 3);
    CHECK(m.roles.root == 0);
    CHECK(m.roles.right_hip == 1);
    CHECK(m.notes.empty());

    // No time column: the frame rate gives the times; without one, a clear refusal.
    ReadOptions rate;
    rate.frame_rate_hz = 30.0;
    const Clip r = parse_joint_csv("rate.csv", "a_x,a_y,a_z\n1,2,3\n1,2,3\n", rate);
    CHECK(r.times[1] == doctest::Approx(1.0 / 30.0));
    check_error([&] { parse_joint_csv("k.csv", "a_x,a_y,a_z\n1,2,3\n"); }, 1, "expected a time column");
}

TEST_CASE("joint CSV rows with joints not tracked are lost frames, kept and counted") {
    // As exporters write a frame without a body: empty fields (pandas), nan (numpy), null (JavaScript);
    // one joint missing is no pose either. A malformed coordinate is still refused with its line.
    const std::string header = "time,HipCenter_x,HipCenter_y,HipCenter_z,HipLeft_x,HipLeft_y,HipLeft_z\n";
    const std::string text = header +
                             "0.000,0,1,2,-0.1,1,2\n"
                             "0.033,,,,,,\n"
                             "0.067,nan,NaN,-nan,nan,nan,nan\n"
                             "0.100,null,null,null,None,NA,n/a\n"
                             "0.133,0,1,2,,,\n"
                             "0.167,0,1,2,-0.1,1,2,\n";
    const Clip clip = parse_joint_csv("k.csv", text);
    REQUIRE(clip.frame_count() == 6);
    CHECK(clip.lost == std::vector<std::uint8_t>{0, 1, 1, 1, 1, 0});
    for (std::size_t f = 1; f <= 4; ++f)
        for (std::size_t k = 0; k < 6; ++k) CHECK(clip.frame(f)[k] == 0.0f);
    CHECK(clip.frame(5)[3] == doctest::Approx(-0.1f));
    CHECK(clip.times[4] == doctest::Approx(0.133));
    REQUIRE(clip.notes.size() == 1);
    CHECK(clip.notes[0] == "4 rows with a joint not tracked (an empty or NaN coordinate; the first at line 3) read as "
                           "lost frames");
    check_error([&] { parse_joint_csv("k.csv", header + "0,0,1,2,-0.1,1,2\n0.033,0,1,x,-0.1,1,2\n"); }, 3,
                "expected a coordinate (or an empty field or NaN for a joint not tracked), got 'x'");
    check_error([&] { parse_joint_csv("k.csv", header + "0,0,1,2,-0.1,1,2\n,0,1,2,-0.1,1,2\n"); }, 3,
                "expected a timestamp, got ''");
    check_error([&] { parse_joint_csv("k.csv", header + "0,0,1,2,-0.1,1\n"); }, 2, "expected 7 columns, got 6");
}

TEST_CASE("joint CSV length units: read off the body's height unless given") {
    // A 1.7 m body (head above hips above feet) written in metres, centimetres and millimetres.
    auto body_csv = [](double unit) {
        std::string text =
            "time,Head_x,Head_y,Head_z,HipCenter_x,HipCenter_y,HipCenter_z,FootLeft_x,FootLeft_y,FootLeft_z\n";
        for (int f = 0; f < 4; ++f) {
            const double sway = 0.01 * f;
            text += std::to_string(f / 30.0);
            for (const double y : {1.7, 0.9, 0.0})
                for (const double v : {sway, y, 2.5}) text += "," + std::to_string(v * unit);
            text += "\n";
        }
        return text;
    };
    const Clip metres = parse_joint_csv("m.csv", body_csv(1.0));
    CHECK(metres.notes.empty());
    for (const double unit : {100.0, 1000.0}) {
        const Clip clip = parse_joint_csv("u.csv", body_csv(unit));
        REQUIRE(clip.positions.size() == metres.positions.size());
        for (std::size_t k = 0; k < clip.positions.size(); ++k)
            CHECK(clip.positions[k] == doctest::Approx(metres.positions[k]).epsilon(1e-5));
        REQUIRE(clip.notes.size() == 1);
        CHECK(clip.notes[0].find(unit == 100.0 ? "lengths taken as centimetres: the body spans 170 units"
                                               : "lengths taken as millimetres: the body spans 1700 units") == 0);
    }
    // Given, the unit wins and nothing is guessed; lost frames (zeros) do not move the guess.
    ReadOptions given;
    given.length_scale = metres_per_unit("m");
    const Clip kept = parse_joint_csv("u.csv", body_csv(1000.0), given);
    CHECK(kept.frame(0)[1] == doctest::Approx(1700.0f));
    CHECK(kept.notes.empty());
    const Clip with_lost = parse_joint_csv(
        "u.csv", body_csv(1000.0) + "0.2,,,,,,,,,\n0.3,,,,,,,,,\n0.4,,,,,,,,,\n0.5,,,,,,,,,\n0.6,,,,,,,,,\n");
    CHECK(with_lost.frame(0)[1] == doctest::Approx(1.7f));
    // A skeleton of the hips alone spans nothing along the vertical: metres, as stated nowhere else.
    CHECK(parse_joint_csv("h.csv",
                          "time,HipLeft_x,HipLeft_y,HipLeft_z,HipRight_x,HipRight_y,HipRight_z\n0,-0.1,1,2,0.1,1,2\n")
              .notes.empty());
    CHECK(metres_per_unit("in") == doctest::Approx(0.0254));
    CHECK_THROWS_WITH_AS(metres_per_unit("yard"), "expected a length unit: m, dm, cm, mm or in, got 'yard'",
                         std::invalid_argument);
}

TEST_CASE("joints named after a depth-camera SDK take its bone tree") {
    // Each joint's parent by name, as the SDKs document their trees.
    auto parent_names = [](const std::vector<std::string>& names, const std::vector<int>& parents) {
        std::vector<std::string> out;
        for (const int p : parents) out.push_back(p < 0 ? "-" : names[static_cast<std::size_t>(p)]);
        return out;
    };
    const std::vector<int> v1 = sdk_parents(kinect_v1_joint_names());
    CHECK(v1 == std::vector<int>{-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18});
    const std::vector<int> v2 = sdk_parents(kinect_v2_joint_names());
    CHECK(v2[20] == 1);  // SpineShoulder ← SpineMid
    CHECK(v2[4] == 20);  // ShoulderLeft ← SpineShoulder
    CHECK(v2[21] == 7);  // HandTipLeft ← HandLeft
    const std::vector<int> azure = sdk_parents(azure_kinect_joint_names());
    REQUIRE(azure.size() == 32);
    CHECK(azure[4] == 2);    // CLAVICLE_LEFT ← SPINE_CHEST
    CHECK(azure[10] == 7);   // THUMB_LEFT ← WRIST_LEFT
    CHECK(azure[26] == 3);   // HEAD ← NECK
    CHECK(azure[31] == 26);  // EAR_RIGHT ← HEAD
    CHECK(std::count(azure.begin(), azure.end(), -1) == 1);

    // Any order and any spelling: MSR Action3D's order, then a CSV's upper-case names.
    const std::vector<std::string>& msr = msr_action3d_joint_names();
    const std::vector<std::string> by_name = parent_names(msr, sdk_parents(msr));
    for (std::size_t j = 0; j < msr.size(); ++j) {
        const auto sdk = std::find(kinect_v1_joint_names().begin(), kinect_v1_joint_names().end(), msr[j]);
        REQUIRE(sdk != kinect_v1_joint_names().end());
        const int p = v1[static_cast<std::size_t>(sdk - kinect_v1_joint_names().begin())];
        CHECK(by_name[j] == (p < 0 ? std::string("-") : kinect_v1_joint_names()[static_cast<std::size_t>(p)]));
    }
    CHECK(sdk_parents({"HAND_LEFT", "hip_center", "Shoulder-Left", "spine", "ShoulderCenter"}) ==
          std::vector<int>{2, -1, 4, 1, 3});  // the hand hangs from the shoulder: no elbow or wrist given

    // Never guessed: a joint no SDK has, one given twice, no root, MediaPipe's names.
    CHECK(sdk_parents({"HipCenter", "HipLeft", "LeftHandIndex1"}).empty());
    CHECK(sdk_parents({"HipCenter", "HipLeft", "HIP_LEFT"}).empty());
    CHECK(sdk_parents({"HipLeft", "KneeLeft", "HipRight"}).empty());
    CHECK(sdk_parents({"left_hip", "right_hip", "nose"}).empty());
    CHECK(sdk_parents({}).empty());

    // A joint CSV gets the tree by its names; the same motion as MSR text and as CSV reads the same.
    std::string msr_text, csv = "time";
    for (const std::string& name : msr) csv += "," + name + "_x," + name + "_y," + name + "_z";
    csv += "\n";
    for (int f = 0; f < 3; ++f) {
        csv += std::to_string(f / 15.0);
        for (std::size_t j = 0; j < msr.size(); ++j) {
            const std::string x = std::to_string(0.01 * static_cast<double>(j) + 0.001 * f),
                              y = std::to_string(-1.0 + 0.08 * static_cast<double>(j)), z = "2.5";
            msr_text += x + " " + y + " " + z + " 1\n";
            csv += "," + x + "," + y + "," + z;
        }
        csv += "\n";
    }
    const Clip from_text = parse_msr_skeleton("a.txt", msr_text), from_csv = parse_joint_csv("a.csv", csv);
    CHECK(from_csv.joint_names == from_text.joint_names);
    CHECK(from_csv.parents == from_text.parents);
    CHECK(from_csv.parents == sdk_parents(msr));
    CHECK(from_csv.positions == from_text.positions);
    // Names of no SDK: no tree, as before.
    CHECK(parse_joint_csv("k.csv", "timestamp,a_x,a_y,a_z\n0,1,2,3\n").parents.empty());
}

TEST_CASE("a tree given by parent names: any rig's CSV gets its bones") {
    const std::string text =
        "time,hips_x,hips_y,hips_z,spine_x,spine_y,spine_z,l_hand_x,l_hand_y,l_hand_z,R-HAND_x,R-HAND_y,R-HAND_z\n"
        "0,0,1,2,0,1.3,2,-0.5,1.3,2,0.5,1.3,2\n";
    const Clip clip = parse_joint_csv("rig.csv", text);
    REQUIRE(clip.parents.empty());  // names of no SDK
    CHECK(parents_from_names(clip, {"-", "hips", "SPINE", "spine"}) == std::vector<int>{-1, 0, 1, 1});
    CHECK(parse_parent_names(" -, hips ,spine,spine") == std::vector<std::string>{"-", "hips", "spine", "spine"});
    auto refused = [&](const std::vector<std::string>& names, const std::string& fragment) {
        try {
            parents_from_names(clip, names);
            FAIL("accepted " << names.size() << " names; expected '" << fragment << "'");
        } catch (const std::invalid_argument& error) {
            CHECK(std::string(error.what()).find(fragment) != std::string::npos);
        }
    };
    refused({"-", "hips", "spine"}, "3 names for 4 joints");
    refused({"-", "hips", "neck", "spine"}, "'neck' (the parent of l_hand) is not a joint of the file");
    refused({"-", "l_hand", "spine", "spine"}, "joint 1 is in a cycle");
    CHECK_THROWS_AS(parse_parent_names(""), std::invalid_argument);

    // Through read_clip, as every command reads files: the option wins over the file's (here none).
    const std::string path = (std::filesystem::temp_directory_path() / "actionstring_parents_test.csv").string();
    { std::ofstream(path) << text; }
    ReadOptions options;
    options.parents = {"-", "hips", "spine", "spine"};
    CHECK(read_clip(path, options).parents == std::vector<int>{-1, 0, 1, 1});
    options.parents = {"-", "hips"};
    check_error([&] { read_clip(path, options); }, 0, "2 names for 4 joints");
    std::filesystem::remove(path);
}

TEST_CASE("clip lists resolve paths against their folder") {
    const auto entries = parse_clip_list(
        "l.tsv", "path\tlabel\tsubject\tskeleton\nx/a.amc\tjump\tbd\tasf/b.asf\n/abs/c.amc\trun\tmm\ts.asf\n", "/data");
    REQUIRE(entries.size() == 2);
    CHECK(entries[0].path == "/data/x/a.amc");
    CHECK(entries[0].skeleton == "/data/asf/b.asf");
    CHECK(entries[1].path == "/abs/c.amc");
    CHECK(entries[1].line == 3);
    const auto reordered = parse_clip_list("l.tsv", "subject\tpath\tlabel\ns1\tf.txt\twave\n", "d");
    CHECK(reordered[0].path == "d/f.txt");
    CHECK(reordered[0].subject == "s1");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\n", "d"); }, 1, "path, label and subject");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\na\tb\n", "d"); }, 2,
                "expected 3 tab-separated fields");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\na\t\tc\n", "d"); }, 2, "empty label");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\n", "d"); }, 1, "names no clips");
    const auto intervals =
        parse_clip_list("l.tsv", "path\tlabel\tsubject\tstart\tend\nr.txt\twalk\ts1\t8.4\t13\n", "d");
    CHECK(intervals[0].has_interval);
    CHECK(intervals[0].start_s == 8.4);
    CHECK(intervals[0].end_s == 13.0);
    CHECK_FALSE(entries[0].has_interval);
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\tstart\na\tb\tc\t1\n", "d"); }, 1,
                "both 'start' and 'end'");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\tstart\tend\na\tb\tc\t2\t1\n", "d"); }, 2,
                "not before the start");
    check_error([&] { parse_clip_list("l.tsv", "path\tlabel\tsubject\tstart\tend\na\tb\tc\tnan\t1\n", "d"); }, 2,
                "finite");
}

TEST_CASE("joint roles can be overridden and must exist") {
    const std::string text = "timestamp,a_x,a_y,a_z,b_x,b_y,b_z,c_x,c_y,c_z\n0,0,1,0,-0.1,1,0,0.1,1,0\n";
    ReadOptions options;
    options.roles = RoleNames{"a", "b", "c"};
    const Clip clip = parse_joint_csv("k.csv", text, options);
    CHECK(clip.roles.root == 0);
    CHECK(clip.roles.right_hip == 2);
    options.roles.left_hip = "nope";
    check_error([&] { parse_joint_csv("k.csv", text, options); }, 0, "left hip joint 'nope'");
}

TEST_CASE("reliability: an ASF length unit that would make positions infinite is refused") {
    // Before: ':units length 1e-300' gave a clip of ±inf positions.
    std::string asf = kAsf;
    asf.replace(asf.find("length 0.45"), 11, "length 1e-300");
    check_error([&] { parse_asf("tiny.asf", asf); }, 6, "expected a length unit between");
    std::string huge = kAsf;
    huge.replace(huge.find("length 0.45"), 11, "length 9e+6");
    check_error([&] { parse_asf("huge.asf", huge); }, 6, "expected a length unit between");
}

TEST_CASE("reliability: no reader returns a position that is not finite") {
    Clip clip;
    clip.source = "made.csv";
    clip.joint_names = {"a", "b"};
    clip.times = {0.0, 0.1};
    clip.positions = {0, 0, 0, 1, 1, 1, 0, 0, 0, 1, std::numeric_limits<float>::infinity(), 1};
    CHECK_THROWS_WITH_AS(require_finite_positions(clip), doctest::Contains("frame 2, joint 'b'"), ReadError);
    clip.positions[10] = 2e6f;  // beyond a kilometre in every unit a body comes in
    CHECK_THROWS_AS(require_finite_positions(clip), ReadError);
    clip.positions[10] = 1.0f;
    CHECK_NOTHROW(require_finite_positions(clip));
}

TEST_CASE("reliability: files are read whole or refused with the reason") {
    const std::string dir = "reliability_files";
    std::filesystem::create_directories(dir);
    // A directory was reported as an "empty file".
    CHECK_THROWS_WITH_AS(read_file(dir), doctest::Contains("is a directory"), ReadError);
    // "cannot open the file" gave no reason.
    CHECK_THROWS_WITH_AS(read_file(dir + "/absent.csv"), doctest::Contains("No such file or directory"), ReadError);
    // Over the size limit: refused before a byte is allocated, with the sizes.
    const std::string big = dir + "/big.txt";
    write_file(big, std::string(4096, 'x'));
    CHECK(read_file(big).size() == 4096);
    CHECK_THROWS_WITH_AS(read_file(big, 1000), doctest::Contains("4096 bytes; files over 1000 bytes are refused"),
                         ReadError);
    // Through read_clip, the same reasons reach the user.
    CHECK_THROWS_WITH_AS(read_clip(dir + "/absent.bvh"), doctest::Contains("No such file or directory"), ReadError);
    std::filesystem::remove_all(dir);
}

namespace {

// An NTU RGB+D .skeleton text written from the published layout: per frame the
// body count, per body 10 values (the id first), 25, and 25 lines of 12 values.
std::string ntu_text(int frames, const std::vector<std::pair<std::string, float>>& bodies) {
    std::ostringstream out;
    out << frames << "\n";
    for (int f = 0; f < frames; ++f) {
        out << bodies.size() << "\n";
        for (const auto& [id, sway] : bodies) {
            out << id << " 0 1 1 1 1 0 0.1 0.2 2\n25\n";
            for (int j = 0; j < 25; ++j) {
                const float x = 0.05f * static_cast<float>(j % 5) + sway * static_cast<float>(f);
                const float y = 0.07f * static_cast<float>(j);
                out << x << " " << y << " 3.1 250.5 200.1 1000.2 500.3 0.9 0.1 0.2 0.3 2\n";
            }
        }
    }
    return out.str();
}

}  // namespace

TEST_CASE("joint CSV with --columns: a layout no spelling rule covers") {
    const std::string text =
        "when;a1;a2;a3;b1;b2;b3;c1;c2;c3;junk\n0;0;1;2;-0.1;1;2;0.1;1;2;x\n0.04;0;1;2;-0.1;1;2;0.1;1;2;y\n";
    ReadOptions options;
    options.columns = "time=WHEN, pelvis=a1:a2:a3, hipleft=b1:b2:b3, hipright=c1:c2:c3";
    const Clip clip = parse_joint_csv("odd.csv", text, options);
    CHECK(clip.joint_names == std::vector<std::string>{"pelvis", "hipleft", "hipright"});
    CHECK(clip.roles.complete());
    CHECK(clip.times[1] == doctest::Approx(0.04));
    CHECK(clip.frame(1)[3] == doctest::Approx(-0.1f));
    REQUIRE(clip.notes.size() == 1);
    CHECK(clip.notes[0] == "1 columns not named by --columns, ignored");
    options.columns = "time=when,pelvis=a1:a2:nope";
    check_error([&] { parse_joint_csv("odd.csv", text, options); }, 1, "no column 'nope' in the header");
    options.columns = "time=when,pelvis=a1:a2";
    check_error([&] { parse_joint_csv("odd.csv", text, options); }, 1, "expected JOINT=X:Y:Z");
    options.columns = "pelvis=a1:a2:a3";
    check_error([&] { parse_joint_csv("odd.csv", text, options); }, 1, "no time column given");
}

TEST_CASE("NTU RGB+D skeletons: the main body, or a chosen one") {
    // Body 72057594037931101 stands still, 72057594037931102 sways.
    const std::string text = ntu_text(4, {{"72057594037931101", 0.0f}, {"72057594037931102", 0.05f}});
    const Clip clip = parse_ntu_skeleton("S001C001P001R001A001.skeleton", text);
    CHECK(clip.joint_count() == 25);
    CHECK(clip.frame_count() == 4);
    CHECK(clip.joint_names[0] == "SpineBase");
    CHECK(clip.parents[3] == 2);   // Head ← Neck
    CHECK(clip.parents[2] == 20);  // Neck ← SpineShoulder
    CHECK(clip.roles.complete());
    CHECK(clip.times[1] == doctest::Approx(1.0 / 30.0));
    CHECK(clip.frame(3)[0] == doctest::Approx(0.15f));  // the swaying body: x moved 3 × 0.05
    REQUIRE(clip.notes.size() == 1);
    CHECK(clip.notes[0].find("2 bodies; read body 1 (the one that moves most)") == 0);
    ReadOptions first;
    first.body = 0;
    CHECK(parse_ntu_skeleton("a.skeleton", text, first).frame(3)[0] == doctest::Approx(0.0f));
    first.body = 2;
    check_error([&] { parse_ntu_skeleton("a.skeleton", text, first); }, 0, "body 2 asked for");
    // A body absent from a frame leaves that frame lost for it.
    const Clip one = parse_ntu_skeleton("b.skeleton", "2\n0\n" + ntu_text(1, {{"7", 0.0f}}).substr(2));
    CHECK(one.lost[0] == 1);
    CHECK(one.lost[1] == 0);
    check_error([&] { parse_ntu_skeleton("c.skeleton", "2\n1\n7 0 1 1 1 1 0 0.1 0.2 2\n25\n"); }, 4, "truncated");
    check_error([&] { parse_ntu_skeleton("c.skeleton", "1\n1\n7 0 1 1 1 1 0 0.1 0.2\n"); }, 3, "10 values");
    check_error([&] { parse_ntu_skeleton("c.skeleton", "1\n1\n7 0 1 1 1 1 0 0.1 0.2 2\n20\n"); }, 4, "25 joints");
    check_error([&] { parse_ntu_skeleton("c.skeleton", "0\n"); }, 1, "no frames");
}
