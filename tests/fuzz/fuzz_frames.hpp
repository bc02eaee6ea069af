// A frame the fuzz targets stream through a model the fuzzer made: a standing
// body of the model's joints whose hips (the model's roles) are apart.
#pragma once

#include <cstddef>
#include <vector>

#include "actionstring/model.hpp"

namespace actionstring {
namespace fuzz {

inline std::vector<float> frame_for(const ModelView& model, int step) {
    std::vector<float> frame(3u * model.joint_count);
    for (std::size_t j = 0; j < model.joint_count; ++j) {
        frame[3 * j + 0] = 0.05f * static_cast<float>(j % 7) + 0.01f * static_cast<float>(step % 13);
        frame[3 * j + 1] = 0.8f + 0.03f * static_cast<float>(j % 11);
        frame[3 * j + 2] = 0.02f * static_cast<float>(j % 5);
    }
    frame[3u * model.left_hip_joint] = 0.15f;
    frame[3u * model.right_hip_joint] = -0.15f;
    return frame;
}

}  // namespace fuzz
}  // namespace actionstring
