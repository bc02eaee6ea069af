// A file's skeleton against the model's: mapped by name when that is
// unambiguous, refused with a clear message otherwise, never read past.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"

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
                         "four.csv: 4 joints, the model expects 5 joints: 1 of its joints are not in the file (rhand)",
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
