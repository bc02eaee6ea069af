// Clip recognition with the model's own method, and its summary.
#include "eval/clip_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "actionstring/annotator.hpp"
#include "common/time.hpp"
#include "model/model_data.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "run/stream_labels.hpp"
#include "run/state.hpp"

namespace actionstring {
namespace host {

ClipResults start_results(const std::string& method, const ModelView& model, const std::vector<LabelledClip>& clips) {
    ClipResults r;
    r.method = method;
    r.labels = name_strings(model.label_names, model.label_count);
    for (const LabelledClip& c : clips)
        if (std::find(r.labels.begin(), r.labels.end(), c.label) == r.labels.end()) r.labels.push_back(c.label);
    return r;
}

int label_index(const std::vector<std::string>& labels, const std::string& label) {
    return static_cast<int>(std::find(labels.begin(), labels.end(), label) - labels.begin());
}

void summarise(ClipResults& r, const std::vector<LabelledClip>& clips) {
    const std::size_t L = r.labels.size();
    r.confusion.assign(L, std::vector<int>(L + 1, 0));
    int right = 0, unknown = 0;
    for (std::size_t c = 0; c < clips.size(); ++c) {
        const int truth = label_index(r.labels, clips[c].label);
        const int predicted = r.predictions[c];
        ++r.confusion[static_cast<std::size_t>(truth)][predicted < 0 ? L : static_cast<std::size_t>(predicted)];
        right += predicted == truth;
        unknown += predicted < 0;
    }
    const double n = clips.empty() ? 1.0 : static_cast<double>(clips.size());
    r.clip_accuracy = right / n;
    r.correct = static_cast<std::size_t>(right);
    r.accuracy_interval = wilson_interval(r.correct, clips.size());
    r.unknown_rate = unknown / n;
    r.precision.assign(L, 0.0);
    r.recall.assign(L, 0.0);
    for (std::size_t l = 0; l < L; ++l) {
        int predicted_as = 0, support = 0;
        for (std::size_t t = 0; t < L; ++t) predicted_as += r.confusion[t][l];
        for (std::size_t p = 0; p <= L; ++p) support += r.confusion[l][p];
        if (predicted_as > 0) r.precision[l] = static_cast<double>(r.confusion[l][l]) / predicted_as;
        if (support > 0) r.recall[l] = static_cast<double>(r.confusion[l][l]) / support;
    }
    r.per_subject.clear();
    std::map<std::string, SubjectScore> subjects;
    bool named = false;
    for (std::size_t c = 0; c < clips.size(); ++c) {
        named = named || !clips[c].subject.empty();
        SubjectScore& score = subjects[clips[c].subject];
        score.subject = clips[c].subject;
        ++score.clips;
        score.correct += r.predictions[c] == label_index(r.labels, clips[c].label);
    }
    if (!named) return;
    for (auto& [name, score] : subjects) {
        score.accuracy = static_cast<double>(score.correct) / static_cast<double>(score.clips);
        r.per_subject.push_back(score);
    }
}

void compare_with_model(const ClipResults& model, ClipResults& baseline, const std::vector<LabelledClip>& clips) {
    baseline.model_only = baseline.method_only = 0;
    for (std::size_t c = 0; c < clips.size() && c < model.predictions.size() && c < baseline.predictions.size(); ++c) {
        const bool model_right = model.predictions[c] == label_index(model.labels, clips[c].label);
        const bool baseline_right = baseline.predictions[c] == label_index(baseline.labels, clips[c].label);
        baseline.model_only += model_right && !baseline_right;
        baseline.method_only += baseline_right && !model_right;
    }
    baseline.mcnemar_p = mcnemar_exact_p(baseline.model_only, baseline.method_only);
    baseline.paired = true;
}

ClipResults evaluate_model(const ModelView& model, const std::vector<LabelledClip>& clips) {
    ClipResults r = start_results("action strings (representatives, kNN)", model, clips);
    const std::size_t K = std::min<std::size_t>(3, model.label_count);
    std::vector<std::size_t> within(K, 0);
    for (const LabelledClip& c : clips) {
        const ScoredClip scored = score_clip(model, c.clip);
        r.predictions.push_back(frame_label(scored.classification.label));
        // The true label's rank among the labels' scores: how many other labels
        // score as near or nearer (a tie is not won by the true label).
        const int truth = label_index(r.labels, c.label);
        if (truth < 0 || static_cast<std::size_t>(truth) >= model.label_count) continue;
        const std::vector<float>& scores = scored.label_distances;
        const float own = scores[static_cast<std::size_t>(truth)];
        if (!std::isfinite(own)) continue;
        std::size_t rank = 0;
        for (std::size_t l = 0; l < scores.size(); ++l)
            rank += l != static_cast<std::size_t>(truth) && scores[l] <= own;
        for (std::size_t j = rank; j < K; ++j) ++within[j];
    }
    summarise(r, clips);
    for (const std::size_t n : within)
        r.top_k.push_back(clips.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(clips.size()));
    return r;
}

std::vector<double> annotator_frame_times(const ModelView& model, const std::vector<LabelledClip>& clips,
                                          const AnnotatorConfig& config) {
    for (const LabelledClip& c : clips) require_joint_count(model, c.clip.joint_count(), c.clip.source);
    // As a device runs it, with the settings the online figures used.
    Stateful<Annotator> annotator;
    std::vector<double> times;
    if (annotator.init(model, config) != Status::ok) return times;
    // Clips back to back on one clock: each starts 1 µs after the previous
    // ends, whatever its own time axis (an interval of a recording starts late).
    std::int64_t offset = 0;
    for (const LabelledClip& c : clips) {
        if (c.clip.frame_count() == 0) continue;
        const double first = c.clip.times.front();
        for (std::size_t f = 0; f < c.clip.frame_count(); ++f) {
            const std::int64_t t = offset + seconds_to_us(c.clip.times[f] - first);
            const auto begin = std::chrono::steady_clock::now();
            annotator->push_frame(t, c.clip.frame(f));
            times.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - begin).count());
        }
        offset += seconds_to_us(c.clip.duration()) + 1;
    }
    std::sort(times.begin(), times.end());
    return times;
}

}  // namespace host
}  // namespace actionstring
