// One evaluation run, as `actionstring eval` and the Python package report it.
#include "eval/evaluation.hpp"

#include <algorithm>

#include "common/json.hpp"
#include "common/stats.hpp"
#include "common/time.hpp"
#include "eval/baselines.hpp"
#include "eval/json.hpp"
#include "model/model_data.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "train/rejection.hpp"

namespace actionstring {
namespace host {

Evaluation evaluate(const ModelView& view, std::vector<LabelledClip> clips, std::vector<LabelledClip> train,
                    std::vector<LabelledRecording> recordings, bool online, std::uint32_t seed,
                    const AnnotatorConfig& config, const Perturbation& perturbation) {
    Evaluation e;
    e.recordings = !recordings.empty();
    e.clips = std::move(clips);
    e.perturbation = perturbation.describe();
    for (std::size_t i = 0; i < e.clips.size(); ++i) perturb_clip(e.clips[i].clip, perturbation, i);
    for (std::size_t r = 0; r < recordings.size(); ++r)
        perturb_clip(recordings[r].clip, perturbation, (std::uint64_t{1} << 32) + r);
    conform_to_model(view, e.clips);
    e.results.push_back(evaluate_model(view, e.clips));
    {  // The classifier's rejection of synthetic non-actions made from these clips
        // (with exemplars, each character's exemplar distances spliced and warped
        // with it, and summed as classify_clip() sums a clip's).
        // With a clip descriptor, the negatives' features (and records), cut with them, give their
        // descriptor's penalties, as classify_clip() adds them.
        const std::size_t L = view.label_count;
        const bool exemplars = view.has_exemplars(), described = view.has_descriptor() || view.has_directions();
        std::vector<std::vector<Character>> strings;
        std::vector<std::vector<float>> rows, features;
        std::vector<LabelId> labels;
        const std::vector<std::string> names = name_strings(view.label_names, view.label_count);
        for (const LabelledClip& c : e.clips) {
            const auto at = std::find(names.begin(), names.end(), c.label);
            if (at == names.end()) continue;
            EncodedClip encoded = encode_clip(view, c.clip, exemplars || described, view.has_directions());
            strings.push_back(std::move(encoded.string));
            rows.push_back(exemplar_rows(view, encoded.features));
            features.push_back(described ? descriptor_rows(view, encoded.features, encoded.records)
                                         : std::vector<float>{});
            labels.push_back(static_cast<LabelId>(at - names.begin()));
        }
        std::vector<PerCharacterRows> per_character;
        if (exemplars) per_character.push_back({&rows, L});
        if (described) per_character.push_back({&features, descriptor_row_width(view)});
        for (const SyntheticNegative& n : synthetic_negatives(strings, labels, seed, per_character)) {
            const std::vector<float> sums = exemplars ? sum_exemplar_rows(n.rows.front(), L) : std::vector<float>{};
            const std::vector<float> penalties =
                described ? descriptor_row_penalties(view, n.rows.back()) : std::vector<float>{};
            const Classification c = classify_string(view, n.string, {}, exemplars ? sums.data() : nullptr,
                                                     described ? penalties.data() : nullptr);
            if (n.own != unknown_label && c.nearest_label == n.own) continue;  // still its own action
            ++e.synthetic_negatives;
            e.synthetic_unknown += c.label == unknown_label;
        }
    }
    if (!train.empty()) {
        conform_to_model(view, train);
        e.results.push_back(evaluate_all_strings(view, train, e.clips));
        e.results.push_back(evaluate_pca_characters(view, train, e.clips));
        e.results.push_back(evaluate_pose_dtw(view, train, e.clips));
        for (std::size_t i = 1; i < e.results.size(); ++i) compare_with_model(e.results.front(), e.results[i], e.clips);
    }
    e.frame_ns = annotator_frame_times(view, e.clips, config);
    e.frame_spread = config.spread_work;
    e.online = online;
    if (online && e.recordings) {
        for (LabelledRecording& recording : recordings) conform_to_model(view, recording.clip);
        for (const LabelledClip& stretch : unlabelled_stretches(recordings, 1.0)) {
            ++e.no_action_stretches;
            e.no_action_unknown += classify_clip(view, stretch.clip).label == unknown_label;
        }
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
    out.field("perturbation", e.perturbation);
    out.key("frame_time_ns")
        .begin_object()
        .field("median", sorted_quantile(e.frame_ns, 0.5))
        .field("p99", sorted_quantile(e.frame_ns, 0.99))
        .field("max", sorted_quantile(e.frame_ns, 1.0))
        .field("spread_work", e.frame_spread)
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
        write_json(out, e.online_report.settled, &e.results.front().labels);
        out.key("live");
        write_json(out, e.online_report.live);
        out.key("latest_window");
        write_json(out, e.online_report.window);
        // The settled labels on each stream alone (a subject's clips joined, or one recording).
        out.key("per_stream").begin_array();
        for (std::size_t s = 0; s < e.online_report.per_stream.size() && s < e.online_report.streams.size(); ++s)
            write_stream_json(out, e.online_report.streams[s].name, e.online_report.per_stream[s]);
        out.end_array();
        out.end_object();
    }
    out.key("synthetic_negatives")
        .begin_object()
        .field("count", static_cast<long long>(e.synthetic_negatives))
        .field("unknown", static_cast<long long>(e.synthetic_unknown))
        .end_object();
    if (e.no_action_stretches > 0)
        out.key("no_action_stretches")
            .begin_object()
            .field("count", static_cast<long long>(e.no_action_stretches))
            .field("unknown", static_cast<long long>(e.no_action_unknown))
            .end_object();
    return out.end_object().str();
}

}  // namespace host
}  // namespace actionstring
