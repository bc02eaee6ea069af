// Mirroring for training: left and right swapped, reflected, reversible.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "actionstring/normalize.hpp"
#include "toy/toy.hpp"
#include "train/augment.hpp"

using namespace actionstring;
using namespace actionstring::host;

TEST_CASE("joints pair with their other-side counterpart by name, midline joints with themselves") {
    CHECK(mirror_pairs({"root", "lhipjoint", "lfemur", "rhipjoint", "rfemur", "lowerback"}) ==
          std::vector<int>{0, 3, 4, 1, 2, 5});
    CHECK(mirror_pairs({"HipCenter", "HandLeft", "HandRight", "ShoulderCenter"}) == std::vector<int>{0, 2, 1, 3});
    CHECK(mirror_pairs({"CC_Base_L_Thigh", "CC_Base_Hip", "CC_Base_R_Thigh"}) == std::vector<int>{2, 1, 0});
    CHECK(mirror_pairs({"thigh_r", "pelvis", "thigh_l", "spine_01"}) == std::vector<int>{2, 1, 0, 3});  // Unreal
    CHECK(mirror_pairs({"mixamorig:LeftArm", "mixamorig:RightArm", "mixamorig:Spine"}) == std::vector<int>{1, 0, 2});
}

TEST_CASE("a mirrored clip is the other-handed performance, and mirroring twice gives it back") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    const Clip clip = toy_clips(world, 1, 4).front().clip;
    const Clip mirrored = mirror_clip(clip);
    CHECK(mirror_clip(mirrored).positions == clip.positions);
    CHECK(mirrored.joint_names == clip.joint_names);
    // Normalised, the mirrored left hand is the original right hand with its
    // lateral coordinate negated (the facing flips and is normalised again).
    std::vector<float> a(view.pose_dim()), b(view.pose_dim());
    for (std::size_t f = 0; f < clip.frame_count(); f += 5) {
        REQUIRE(normalize_pose(view, clip.frame(f), a.data()) == Status::ok);
        REQUIRE(normalize_pose(view, mirrored.frame(f), b.data()) == Status::ok);
        // Pose joints are 1..4 (lhip, rhip, lhand, rhand); the up axis is y (index 1).
        for (std::size_t pair : {0u, 2u}) {
            const std::size_t left = 3 * pair, right = 3 * (pair + 1);
            CHECK(b[left + 1] == doctest::Approx(a[right + 1]).epsilon(1e-5));  // height: unchanged
            CHECK(b[right + 1] == doctest::Approx(a[left + 1]).epsilon(1e-5));
        }
    }
}
