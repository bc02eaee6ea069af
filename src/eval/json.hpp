// actionstring host library — evaluation results as JSON (the fields
// `actionstring eval --json` writes).
#pragma once

#include <string>
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

/// One online rule's scores as a JSON object. With `labels` (the
/// evaluation's label names, ClipResults::labels: the model's in order, then
/// any the list names that the model does not know, whose rows are empty),
/// also the frames by class: frame_confusion (rows the truth, columns
/// the prediction; row and column 0 "no action", then the labels in order),
/// frame_confusion_unmodelled (the frames of labels the model does not know,
/// by prediction; only when there are any) and per_class_frames
/// (frame_class_scores(), each named).
void write_json(JsonWriter& out, const OnlineResults& results, const std::vector<std::string>* labels = nullptr);

/// One stream's settled labels scored alone (OnlineReport::per_stream) as a
/// JSON object: its name, frames, "unknown everywhere" on that stream and the
/// frame, segment and event figures.
void write_stream_json(JsonWriter& out, const std::string& name, const OnlineResults& results);

}  // namespace host
}  // namespace actionstring
