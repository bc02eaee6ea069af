// Evaluation results as JSON.
#include "eval/json.hpp"

namespace actionstring {
namespace host {

void write_fields(JsonWriter& out, const ClipResults& r, const std::vector<LabelledClip>& clips) {
    out.field("method", r.method)
        .field("clips", clips.size())
        .field("clip_accuracy", r.clip_accuracy)
        .field("unknown_rate", r.unknown_rate);
    out.key("labels").array(r.labels);
    out.key("confusion").begin_array();
    for (const std::vector<int>& row : r.confusion) out.array(row);
    out.end_array();
    out.key("per_class").begin_object();
    for (std::size_t l = 0; l < r.labels.size(); ++l) {
        int support = 0;
        for (int v : r.confusion[l]) support += v;
        out.key(r.labels[l]).begin_object();
        out.field("precision", r.precision[l]).field("recall", r.recall[l]).field("support", support);
        out.end_object();
    }
    out.end_object();
}

void write_json(JsonWriter& out, const ClipResults& r, const std::vector<LabelledClip>& clips) {
    out.begin_object();
    write_fields(out, r, clips);
    out.end_object();
}

void write_json(JsonWriter& out, const OnlineResults& r) {
    out.begin_object()
        .field("frames", r.frames)
        .field("frame_accuracy", r.frame_accuracy)
        .field("no_action_frames", r.no_action_frames)
        .field("action_frame_accuracy", r.action_frame_accuracy)
        .field("no_action_accuracy", r.no_action_accuracy)
        .field("segment_f1", r.segment_f1)
        .field("segment_precision", r.segment_precision)
        .field("segment_recall", r.segment_recall)
        .field("mean_delay_s", r.mean_delay_s)
        .field("missed_segments", r.missed_segments)
        .field("flicker_per_min", r.flicker_per_min)
        .field("label_changes_per_min", r.label_changes_per_min)
        .field("true_changes_per_min", r.true_changes_per_min)
        .end_object();
}

}  // namespace host
}  // namespace actionstring
