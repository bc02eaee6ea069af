// One evaluation run, as `actionstring eval` and the Python package report it.
#include "eval/evaluation.hpp"

#include "common/json.hpp"
#include "common/stats.hpp"
#include "common/time.hpp"
#include "eval/baselines.hpp"
#include "eval/json.hpp"
#include "run/skeleton.hpp"

namespace actionstring {
namespace host {

Evaluation evaluate(const ModelView& view, std::vector<LabelledClip> clips, std::vector<LabelledClip> train,
                    std::vector<LabelledRecording> recordings, bool online, std::uint32_t seed,
                    const AnnotatorConfig& config) {
    Evaluation e;
    e.recordings = !recordings.empty();
    e.clips = std::move(clips);
    conform_to_model(view, e.clips);
    e.results.push_back(evaluate_model(view, e.clips));
    if (!train.empty()) {
        conform_to_model(view, train);
        e.results.push_back(evaluate_all_strings(view, train, e.clips));
        e.results.push_back(evaluate_pca_characters(view, train, e.clips));
        e.results.push_back(evaluate_pose_dtw(view, train, e.clips));
    }
    e.frame_ns = annotator_frame_times(view, e.clips);
    e.online = online;
    if (online && e.recordings) {
        for (LabelledRecording& recording : recordings) conform_to_model(view, recording.clip);
        e.online_report = evaluate_recordings(view, recordings, config);
    } else if (online) {
        e.online_report = evaluate_online(view, e.clips, seed, config);
    }
    return e;
}

std::string evaluation_json(const Evaluation& e, const std::string& model_name, std::uint32_t seed,
                            const AnnotatorConfig& config) {
    JsonWriter out;
    out.begin_object();
    write_fields(out, e.results.front(), e.clips);
    out.field("model", model_name);
    out.key("frame_time_ns")
        .begin_object()
        .field("median", sorted_quantile(e.frame_ns, 0.5))
        .field("p99", sorted_quantile(e.frame_ns, 0.99))
        .field("max", sorted_quantile(e.frame_ns, 1.0))
        .end_object();
    out.key("baselines").begin_array();
    for (std::size_t i = 1; i < e.results.size(); ++i) write_json(out, e.results[i], e.clips);
    out.end_array();
    if (e.online) {
        out.field("frame_accuracy", e.online_report.settled.frame_accuracy);
        out.key("online").begin_object();
        out.field("streams", e.recordings ? "recordings" : "concatenated clips")
            .field("seed", static_cast<long long>(seed))
            .field("settle_delay_s", us_to_seconds(config.segmenter.settle_delay_us));
        out.key("settled");
        write_json(out, e.online_report.settled);
        out.key("live");
        write_json(out, e.online_report.live);
        out.key("latest_window");
        write_json(out, e.online_report.window);
        out.end_object();
    }
    return out.end_object().str();
}

}  // namespace host
}  // namespace actionstring
