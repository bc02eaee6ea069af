// A file's skeleton against the model's: mapped by name when that is
// unambiguous, refused with a clear message otherwise, never read past.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// The clip with its joints in `order` (indices into the toy skeleton), and
// optionally an extra joint `extra` copied from joint 0 at the front.
Clip rearranged(const Clip& clip, const std::vector<std::size_t>& order, const std::string& extra = {}) {
    Clip out = clip;
    out.joint_names.clear();
    out.positions.clear();
    out.parents.clear();
    if (!extra.empty()) out.joint_names.push_back(extra);
    for (std::size_t j : order) out.joint_names.push_back(clip.joint_names[j]);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (!extra.empty()) out.positions.insert(out.positions.end(), clip.frame(f), clip.frame(f) + 3);
        for (std::size_t j : order) out.positions.insert(out.positions.end(), clip.frame(f) + 3 * j, clip.frame(f) + 3 * j + 3);
    }
    return out;
}

}  // namespace

TEST_CASE("the model records its input skeleton, and a file in another joint order is mapped by name") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    REQUIRE(view.joint_names.present());
    CHECK(std::string(view.joint_names[3]) == "lhand");
    const std::vector<LabelledClip> clips = toy_clips(world, 1, 3);
    const Clip& original = clips.front().clip;
    const std::vector<Character> expected = clip_string(view, original);

    Clip reversed = rearranged(original, {4, 3, 2, 1, 0});
    conform_to_model(view, reversed);
    CHECK(reversed.joint_names == original.joint_names);
    CHECK(reversed.positions == original.positions);
    CHECK(clip_string(view, reversed) == expected);

    Clip extra = rearranged(original, {2, 0, 1, 3, 4}, "lfoot");  // an extra joint, and another order
    conform_to_model(view, extra);
    CHECK(extra.positions == original.positions);

    Clip shouting = original;  // names that differ only in case still match
    for (std::string& name : shouting.joint_names) std::transform(name.begin(), name.end(), name.begin(), ::toupper);
    conform_to_model(view, shouting);
    CHECK(shouting.positions == original.positions);
}

TEST_CASE("a file without the model's joints is refused with the counts and the joints it lacks") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    Clip missing = rearranged(toy_clips(world, 1, 3).front().clip, {0, 1, 2, 3});
    missing.source = "four.csv";
    CHECK_THROWS_WITH_AS(conform_to_model(view, missing),
                         "four.csv: 4 joints, the model expects 5 joints: 1 of them are not in the file (rhand)",
                         ReadError);
}

TEST_CASE("a stream of the wrong joint count is refused before any frame is read") {
    // Before: label_stream read 31 joints' worth from each 20-joint frame.
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    const std::vector<float> frames(4 * 3 * 10, 0.5f);  // ten frames of four joints
    const std::vector<double> times{0, .1, .2, .3, .4, .5, .6, .7, .8, .9};
    CHECK_THROWS_WITH_AS(label_stream(view, {}, times, frames.data(), 4),
                         doctest::Contains("4 joints, the model expects 5 joints"), std::invalid_argument);
    Clip short_clip = rearranged(toy_clips(world, 1, 3).front().clip, {0, 1, 2, 3});
    CHECK_THROWS_AS(clip_string(view, short_clip), std::invalid_argument);
}

namespace {

// A Mixamo-style rig of 100 joints ("mixamorig:" names): 22 body joints, then
// fingers, twist bones, toe ends and face bones, as engine rigs carry them.
struct Rig {
    std::vector<std::string> names;
    std::vector<int> parents;
    std::vector<Eigen::Vector3f> offsets;  // rest offset from the parent, metres, y up
    int add(const std::string& name, int parent, float x, float y, float z) {
        names.push_back("mixamorig:" + name);
        parents.push_back(parent);
        offsets.emplace_back(x, y, z);
        return static_cast<int>(names.size()) - 1;
    }
    int index(const std::string& name) const {
        return static_cast<int>(std::find(names.begin(), names.end(), "mixamorig:" + name) - names.begin());
    }
};

Rig hundred_joint_rig(bool extra_root, bool face) {
    Rig r;
    const int root = extra_root ? r.add("Armature", -1, 0, 0, 0) : -1;
    const int hips = r.add("Hips", root, 0, 1.0f, 0);
    for (const float side : {1.0f, -1.0f}) {
        const std::string s = side > 0 ? "Left" : "Right";
        const int up = r.add(s + "UpLeg", hips, 0.1f * side, -0.05f, 0);
        const int leg = r.add(s + "Leg", up, 0, -0.45f, 0);
        const int foot = r.add(s + "Foot", leg, 0, -0.42f, 0);
        const int toe = r.add(s + "ToeBase", foot, 0, -0.05f, 0.12f);
        r.add(s + "Toe_End", toe, 0, 0, 0.05f);
        r.add(s + "UpLegTwist", up, 0, -0.2f, 0);
        r.add(s + "LegTwist", leg, 0, -0.2f, 0);
    }
    const int spine = r.add("Spine", hips, 0, 0.1f, 0);
    const int spine1 = r.add("Spine1", spine, 0, 0.12f, 0);
    const int spine2 = r.add("Spine2", spine1, 0, 0.12f, 0);
    const int neck = r.add("Neck", spine2, 0, 0.12f, 0);
    const int head = r.add("Head", neck, 0, 0.1f, 0);
    for (const float side : {1.0f, -1.0f}) {
        const std::string s = side > 0 ? "Left" : "Right";
        const int shoulder = r.add(s + "Shoulder", spine2, 0.05f * side, 0.1f, 0);
        const int arm = r.add(s + "Arm", shoulder, 0.12f * side, 0, 0);
        const int fore = r.add(s + "ForeArm", arm, 0.28f * side, 0, 0);
        const int hand = r.add(s + "Hand", fore, 0.25f * side, 0, 0);
        r.add(s + "ArmTwist", arm, 0.14f * side, 0, 0);
        r.add(s + "ForeArmTwist", fore, 0.12f * side, 0, 0);
        const char* fingers[] = {"Thumb", "Index", "Middle", "Ring", "Pinky"};
        for (int f = 0; f < 5; ++f) {
            int parent = hand;
            for (int k = 1; k <= 4; ++k)
                parent = r.add(s + "Hand" + fingers[f] + std::to_string(k), parent, 0.03f * side, 0, 0.02f * static_cast<float>(f - 2));
        }
    }
    if (face)
        for (int k = 1; k <= 28; ++k) r.add("Face" + std::to_string(k), head, 0.01f * static_cast<float>(k % 5), 0.01f * static_cast<float>(k % 7),
                  0.08f);
    return r;
}

// One performance: "raise" lifts the left arm sideways and back, "kick" swings
// the right leg forward; speed and amplitude vary with the seed.
Clip perform(const Rig& rig, const std::string& action, std::uint32_t seed, const std::string& source) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> vary(0.8f, 1.2f);
    const float amplitude = vary(rng), seconds = 2.0f * vary(rng), size = vary(rng);
    const std::size_t J = rig.names.size();
    Clip clip;
    clip.source = source;
    clip.joint_names = rig.names;
    clip.parents = rig.parents;
    clip.up_axis = 1;
    const bool raise = action == "raise";
    const int pivot = raise ? rig.index("LeftArm") : rig.index("RightUpLeg");
    std::vector<bool> moves(J, false);  // the pivot and everything below it
    for (std::size_t j = 0; j < J; ++j)
        for (int a = static_cast<int>(j); a >= 0; a = rig.parents[static_cast<std::size_t>(a)])
            if (a == pivot) moves[j] = true;
    for (int f = 0; static_cast<float>(f) / 60.0f < seconds; ++f) {
        const float t = static_cast<float>(f) / 60.0f;
        clip.times.push_back(t);
        const float angle = amplitude * 1.3f * std::sin(3.14159265f * t / seconds);
        const Eigen::Matrix3f turn =
            Eigen::AngleAxisf(raise ? angle : -angle, raise ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX())
                .toRotationMatrix();
        std::vector<Eigen::Vector3f> world(J);
        for (std::size_t j = 0; j < J; ++j) {
            const int p = rig.parents[j];
            world[j] = (p < 0 ? Eigen::Vector3f::Zero() : world[static_cast<std::size_t>(p)]) + rig.offsets[j] * size;
        }
        const Eigen::Vector3f centre = world[static_cast<std::size_t>(pivot)];
        for (std::size_t j = 0; j < J; ++j) {
            if (moves[j]) world[j] = centre + turn * (world[j] - centre);
            clip.positions.insert(clip.positions.end(), {world[j].x(), world[j].y(), world[j].z()});
        }
    }
    assign_roles(clip, {});
    flag_lost_frames(clip);
    return clip;
}

}  // namespace

TEST_CASE("a 100-joint engine rig trains end to end on its body joints, files of other joint counts together") {
    const Rig full = hundred_joint_rig(false, true);
    REQUIRE(full.names.size() == 100);
    const Rig with_root = hundred_joint_rig(true, true);    // 101 joints: an extra root
    const Rig without_face = hundred_joint_rig(false, false);  // 72 joints
    std::vector<LabelledClip> clips;
    std::uint32_t seed = 1;
    for (const std::string subject : {"a", "b"})
        for (const std::string action : {"raise", "kick"})
            for (const Rig* rig : {&full, &with_root, &without_face}) {
                const std::string name = subject + action + std::to_string(seed) + ".bvh";
                clips.push_back({perform(*rig, action, seed++, name), action, subject});
            }
    std::string rig_found;
    CHECK(body_joints(clips.front().clip, &rig_found).size() == 22);
    CHECK(rig_found == "Mixamo rig");

    TrainingOptions options;
    options.components = 0;
    options.pca_dim = 12;
    options.scale_mode = ScaleMode::bone_lengths;
    options.velocity_weight = 1.0;
    options.velocity_span_s = 0.2;
    options.keep_singletons = true;
    options.epsilon = 0.5;
    options.sigma = 0.5;
    TrainingReport report;
    const ModelData model = train_model(clips, options, &report);
    const ModelView view = model.view();
    CHECK(validate_model(view) == Status::ok);
    CHECK(report.skeleton == "Mixamo rig: 22 of 100 joints");
    CHECK(view.joint_count == 22);
    CHECK(rig_name(view) == "Mixamo rig");
    CHECK(std::string(view.joint_names[view.root_joint]) == "mixamorig:Hips");
    // Bones: each kept joint's parent is its nearest kept ancestor (the shoulder's is Spine2, not a finger).
    const auto named = [&](const std::string& n) {
        for (std::size_t j = 0; j < view.joint_count; ++j)
            if (std::string(view.joint_names[j]) == "mixamorig:" + n) return static_cast<int>(j);
        return -1;
    };
    CHECK(view.joint_parents[named("LeftShoulder")] == named("Spine2"));
    CHECK(view.joint_parents[named("Hips")] == -1);

    // Files of any of the three joint counts are read onto the model's joints and recognised.
    std::vector<LabelledClip> held_out;
    for (const Rig* rig : {&with_root, &without_face, &full})
        for (const std::string action : {"raise", "kick"})
            held_out.push_back({perform(*rig, action, 1000 + seed++, "held_out.bvh"), action, "c"});
    conform_to_model(view, held_out);
    for (const LabelledClip& c : held_out) CHECK(c.clip.joint_count() == 22);
    CHECK(clip_accuracy(view, held_out) == 1.0);

    // A subset named by hand: the root and hips are added, a missing joint is refused naming the file.
    options.pose_joints = {"mixamorig:LeftHand", "mixamorig:RightHand", "mixamorig:Head", "mixamorig:RightFoot"};
    const ModelData hands = train_model(clips, options, &report);
    CHECK(hands.view().joint_count == 7);
    CHECK(report.skeleton == "pose joints: 7 of 100 joints");
    options.pose_joints = {"mixamorig:Face3"};
    CHECK_THROWS_WITH_AS(train_model(clips, options), doctest::Contains("of them are not in the file (mixamorig:Face3)"),
                         ReadError);
}

TEST_CASE("the torso's bones: hips, the spine up to the chest, and the chest's children") {
    auto joints = [](const std::vector<bool>& torso) {
        std::vector<int> out;
        for (std::size_t j = 0; j < torso.size(); ++j)
            if (torso[j]) out.push_back(static_cast<int>(j));
        return out;
    };
    // Kinect v1 (SDK order): HipCenter 0, Spine 1, ShoulderCenter 2, Head 3, ShoulderLeft 4 … HandLeft 7,
    // ShoulderRight 8 … HandRight 11, HipLeft 12 … FootLeft 15, HipRight 16 … FootRight 19.
    const std::vector<int> v1 = {-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18};
    CHECK(joints(host::torso_bones(v1, {0, 12, 16})) == std::vector<int>{1, 2, 3, 4, 8, 12, 16});
    // Kinect v2: SpineBase 0, SpineMid 1, Neck 2, Head 3, shoulders 4 and 8, hips 12 and 16,
    // SpineShoulder 20 (the chest), hand tips and thumbs 21–24 (not torso: the wrists branch, not the chest).
    const std::vector<int> v2 = {-1, 0,  20, 2, 20, 4,  5,  6, 20, 8, 9,  10, 0,
                                 12, 13, 14, 0, 16, 17, 18, 1, 7,  7, 11, 11};
    CHECK(joints(host::torso_bones(v2, {0, 12, 16})) == std::vector<int>{1, 2, 4, 8, 12, 16, 20});
    // An ASF-like tree whose hip roles sit two bones below the root: root 0, lhipjoint 1, lfemur 2,
    // rhipjoint 3, rfemur 4, lowerback 5, upperback 6, thorax 7, lowerneck 8, lclavicle 9, rclavicle 10,
    // lhumerus 11, rhumerus 12.
    const std::vector<int> asf = {-1, 0, 1, 0, 3, 0, 5, 6, 7, 7, 7, 9, 10};
    CHECK(joints(host::torso_bones(asf, {0, 2, 4})) == std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
    // Incomplete roles, or roles outside the skeleton: nothing to measure.
    CHECK(host::torso_bones(v1, {0, -1, 16}).empty());
    CHECK(host::torso_bones(v1, {0, 12, 40}).empty());
    // A cycle in the parents cannot hang the walk.
    CHECK_NOTHROW(host::torso_bones({1, 2, 0, 0}, {0, 1, 2}));
}
