// The depth-camera SDKs' skeletons and the trees they give named joints.
#include "io/sdk_skeletons.hpp"

#include <cstddef>

#include "io/clip.hpp"

namespace actionstring {
namespace host {

const std::vector<std::string>& kinect_v1_joint_names() {
    static const std::vector<std::string> names = {
        "HipCenter", "Spine",         "ShoulderCenter", "Head",       "ShoulderLeft", "ElbowLeft", "WristLeft",
        "HandLeft",  "ShoulderRight", "ElbowRight",     "WristRight", "HandRight",    "HipLeft",   "KneeLeft",
        "AnkleLeft", "FootLeft",      "HipRight",       "KneeRight",  "AnkleRight",   "FootRight"};
    return names;
}

const std::vector<std::string>& kinect_v2_joint_names() {
    static const std::vector<std::string> names = {
        "SpineBase",   "SpineMid",      "Neck",         "Head",       "ShoulderLeft", "ElbowLeft", "WristLeft",
        "HandLeft",    "ShoulderRight", "ElbowRight",   "WristRight", "HandRight",    "HipLeft",   "KneeLeft",
        "AnkleLeft",   "FootLeft",      "HipRight",     "KneeRight",  "AnkleRight",   "FootRight", "SpineShoulder",
        "HandTipLeft", "ThumbLeft",     "HandTipRight", "ThumbRight"};
    return names;
}

const std::vector<std::string>& azure_kinect_joint_names() {
    static const std::vector<std::string> names = {
        "PELVIS",      "SPINE_NAVEL", "SPINE_CHEST",   "NECK",        "CLAVICLE_LEFT",  "SHOULDER_LEFT",  "ELBOW_LEFT",
        "WRIST_LEFT",  "HAND_LEFT",   "HANDTIP_LEFT",  "THUMB_LEFT",  "CLAVICLE_RIGHT", "SHOULDER_RIGHT", "ELBOW_RIGHT",
        "WRIST_RIGHT", "HAND_RIGHT",  "HANDTIP_RIGHT", "THUMB_RIGHT", "HIP_LEFT",       "KNEE_LEFT",      "ANKLE_LEFT",
        "FOOT_LEFT",   "HIP_RIGHT",   "KNEE_RIGHT",    "ANKLE_RIGHT", "FOOT_RIGHT",     "HEAD",           "NOSE",
        "EYE_LEFT",    "EAR_LEFT",    "EYE_RIGHT",     "EAR_RIGHT"};
    return names;
}

namespace {

struct SdkSkeleton {
    const std::vector<std::string>& (*joints)();
    std::vector<int> parents;  // in the SDK's order; −1 at the root
};

// The SDKs' documented trees, tried in this order.
const std::vector<SdkSkeleton>& sdk_skeletons() {
    static const std::vector<SdkSkeleton> skeletons = {
        {kinect_v1_joint_names, {-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18}},
        {kinect_v2_joint_names,
         {-1, 0, 20, 2, 20, 4, 5, 6, 20, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18, 1, 7, 7, 11, 11}},
        {azure_kinect_joint_names, {-1, 0,  1, 2,  2,  4,  5, 6,  7,  8,  7, 2,  11, 12, 13, 14,
                                    15, 14, 0, 18, 19, 20, 0, 22, 23, 24, 3, 26, 26, 26, 26, 26}},
    };
    return skeletons;
}

}  // namespace

std::vector<int> sdk_parents(const std::vector<std::string>& names) {
    for (const SdkSkeleton& sdk : sdk_skeletons()) {
        const std::vector<std::string>& joints = sdk.joints();
        // where each SDK joint is among `names` (−1: absent)
        std::vector<int> present(joints.size(), -1);
        bool all_known = true;
        for (std::size_t n = 0; n < names.size() && all_known; ++n) {
            const std::string key = joint_spelling_key(names[n]);
            std::size_t s = 0;
            while (s < joints.size() && joint_spelling_key(joints[s]) != key) ++s;
            all_known = s < joints.size() && present[s] < 0;  // unknown here, or given twice
            if (all_known) present[s] = static_cast<int>(n);
        }
        if (!all_known || names.empty() || present[0] < 0) continue;
        std::vector<int> parents(names.size(), -1);
        for (std::size_t s = 1; s < joints.size(); ++s) {
            if (present[s] < 0) continue;
            int up = sdk.parents[s];
            while (present[static_cast<std::size_t>(up)] < 0) up = sdk.parents[static_cast<std::size_t>(up)];
            parents[static_cast<std::size_t>(present[s])] = present[static_cast<std::size_t>(up)];
        }
        return parents;
    }
    return {};
}

}  // namespace host
}  // namespace actionstring
