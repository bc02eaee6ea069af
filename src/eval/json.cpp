// Evaluation results as JSON.
#include "eval/json.hpp"

namespace actionstring {
namespace host {

void write_fields(JsonWriter& out, const ClipResults& r, const std::vector<LabelledClip>& clips) {
    out.field("method", r.method)
        .field("clips", clips.size())
        .field("clip_accuracy", r.clip_accuracy)
        .field("correct", r.correct)
        .field("unknown_rate", r.unknown_rate);
    out.key("clip_accuracy_ci95").array(std::vector<double>{r.accuracy_interval.low, r.accuracy_interval.high});
    if (!r.top_k.empty()) out.key("top_k").array(r.top_k);
    if (r.paired)
        out.key("paired_with_model")
            .begin_object()
            .field("model_only", r.model_only)
            .field("baseline_only", r.method_only)
            .field("mcnemar_p", r.mcnemar_p)
            .end_object();
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
    out.key("per_subject").begin_array();
    for (const SubjectScore& s : r.per_subject)
        out.begin_object()
            .field("subject", s.subject)
            .field("clips", s.clips)
            .field("correct", s.correct)
            .field("clip_accuracy", s.accuracy)
            .end_object();
    out.end_array();
}

void write_json(JsonWriter& out, const ClipResults& r, const std::vector<LabelledClip>& clips) {
    out.begin_object();
    write_fields(out, r, clips);
    out.end_object();
}

void write_json(JsonWriter& out, const OnlineResults& r, const std::vector<std::string>* labels) {
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
        .field("final_after_median_s", r.final_after_median_s)
        .field("final_after_p95_s", r.final_after_p95_s)
        .field("missed_segments", r.missed_segments)
        .field("flicker_per_min", r.flicker_per_min)
        .field("label_changes_per_min", r.label_changes_per_min)
        .field("true_changes_per_min", r.true_changes_per_min)
        .field("frame_f1", r.frame_f1)
        .field("unknown_everywhere_accuracy", r.unknown_everywhere_accuracy);
    // 95% intervals resampling the true runs (OnlineResults::units).
    out.key("frame_accuracy_ci95")
        .array(std::vector<double>{r.frame_accuracy_interval.low, r.frame_accuracy_interval.high})
        .key("segment_f1_ci95")
        .array(std::vector<double>{r.segment_f1_interval.low, r.segment_f1_interval.high})
        .key("gain_over_unknown_everywhere_ci95")
        .array(std::vector<double>{r.gain_over_unknown_interval.low, r.gain_over_unknown_interval.high});
    if (r.has_events) {
        out.key("events")
            .begin_object()
            .field("reported", r.events)
            .field("matched", r.matched_events)
            .field("precision", r.event_precision)
            .field("recall", r.event_recall)
            .field("f1", r.event_f1)
            .field("iou_matched", r.iou_matched_events)
            .field("segment_f1", r.event_segment_f1)
            .key("segment_f1_ci95")
            .array(std::vector<double>{r.event_segment_f1_interval.low, r.event_segment_f1_interval.high})
            .field("detection_latency_s", r.detection_latency_s)
            .field("start_error_s", r.start_error_s)
            .field("end_error_s", r.end_error_s)
            .field("start_bias_s", r.start_bias_s)
            .field("end_bias_s", r.end_bias_s)
            .field("false_events_per_min", r.false_events_per_min)
            .field("false_events_per", r.false_events_per_stream_min ? "minute of stream" : "minute of no action")
            .end_object();
    }
    if (labels != nullptr) {
        // Every label of the model, whether or not the streams hold it, so the table's shape is the model's.
        const int count = static_cast<int>(labels->size());
        auto name = [labels](int label) { return frame_class_name(label, *labels); };
        out.key("frame_confusion").begin_array();
        for (int row = -1; row < count; ++row) {
            std::vector<unsigned long> counts;
            for (int column = -1; column < count; ++column) counts.push_back(r.confused(row, column));
            out.array(counts);
        }
        out.end_array();
        // The frames of labels the model does not know (always wrong), by what they were labelled.
        std::vector<unsigned long> unmodelled;
        std::size_t any = 0;
        for (int column = -1; column < count; ++column) {
            unmodelled.push_back(r.confused(-2, column));
            any += unmodelled.back();
        }
        if (any > 0) out.key("frame_confusion_unmodelled").array(unmodelled);
        out.key("per_class_frames").begin_array();
        for (const FrameClassScore& c : frame_class_scores(r)) {
            if (c.label >= count) continue;
            out.begin_object()
                .field("label", name(c.label))
                .field("frames", c.frames)
                .field("right", c.right)
                .field("labelled", c.labelled)
                .field("recall", c.recall)
                .field("precision", c.precision)
                .field("f1", c.f1);
            if (c.most_taken_for_frames > 0 && c.most_taken_for < count)
                out.field("most_taken_for", name(c.most_taken_for))
                    .field("most_taken_for_frames", c.most_taken_for_frames);
            out.end_object();
        }
        out.end_array();
    }
    out.end_object();
}

void write_stream_json(JsonWriter& out, const std::string& name, const OnlineResults& r) {
    out.begin_object()
        .field("name", name)
        .field("frames", r.frames)
        .field("frame_accuracy", r.frame_accuracy)
        .field("no_action_frames", r.no_action_frames)
        .field("action_frame_accuracy", r.action_frame_accuracy)
        .field("no_action_accuracy", r.no_action_accuracy)
        .field("unknown_everywhere_accuracy", r.unknown_everywhere_accuracy)
        .field("frame_f1", r.frame_f1)
        .field("segment_f1", r.segment_f1)
        .field("event_f1", r.event_f1)
        .field("event_segment_f1", r.event_segment_f1)
        .field("false_events_per_min", r.false_events_per_min)
        .end_object();
}

}  // namespace host
}  // namespace actionstring
