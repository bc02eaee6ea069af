// actionstring host library — evaluation results as JSON (the fields
// `actionstring eval --json` writes).
#pragma once

#include <vector>

#include "common/json.hpp"
#include "eval/clip_eval.hpp"
#include "eval/online.hpp"

namespace actionstring {
namespace host {

/// Writes the results' fields into the object `out` has open: method, clips,
/// clip_accuracy, unknown_rate, labels, confusion, per_class (precision,
/// recall, support).
void write_fields(JsonWriter& out, const ClipResults& results, const std::vector<LabelledClip>& clips);

/// The results as one JSON object.
void write_json(JsonWriter& out, const ClipResults& results, const std::vector<LabelledClip>& clips);

/// One online rule's scores as a JSON object.
void write_json(JsonWriter& out, const OnlineResults& results);

}  // namespace host
}  // namespace actionstring
