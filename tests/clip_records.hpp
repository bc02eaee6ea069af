// Clips' direction records and labels as a model encodes them, for the tests
// that fit the motion directions by hand (test_directions.cpp,
// test_window_directions.cpp).
#pragma once

#include <algorithm>
#include <vector>

#include "io/clip_list.hpp"
#include "model/model_data.hpp"
#include "run/encode.hpp"

namespace test {

struct ClipRecords {
    std::vector<std::vector<float>> records;    ///< each clip's, direction_record_floats() per character
    std::vector<actionstring::LabelId> labels;  ///< each clip's label among the model's
};

inline ClipRecords clip_records(const actionstring::host::ModelData& model,
                                const std::vector<actionstring::host::LabelledClip>& clips) {
    ClipRecords out;
    const actionstring::ModelView view = model.view();
    for (const actionstring::host::LabelledClip& c : clips) {
        out.records.push_back(actionstring::host::encode_clip(view, c.clip, false, true).records);
        out.labels.push_back(static_cast<actionstring::LabelId>(
            std::find(model.label_names.begin(), model.label_names.end(), c.label) - model.label_names.begin()));
    }
    return out;
}

}  // namespace test
