// actionstring host library — clip recognition: the model's own method on a
// list of labelled clips, scored as a confusion matrix.
#pragma once

#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
#include "eval/significance.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// One subject's clips in a list, and how many of them a method got right.
struct SubjectScore {
    std::string subject;
    std::size_t clips = 0, correct = 0;
    double accuracy = 0;  ///< correct / clips
};

/// Clip-recognition results of one method on one list.
struct ClipResults {
    std::string method;
    std::vector<std::string> labels;          ///< Row and column names of the confusion matrix.
    std::vector<std::vector<int>> confusion;  ///< [true][predicted]; the last column counts "unknown".
    std::vector<int> predictions;             ///< Per clip: index into labels, or −1 for unknown.
    double clip_accuracy = 0;
    std::size_t correct = 0;     ///< Clips predicted as their own label.
    Interval accuracy_interval;  ///< 95% Wilson interval of clip_accuracy (significance.hpp).
    double unknown_rate = 0;
    std::vector<double> precision, recall;  ///< Per label (NaN-free: 0 when undefined).
    /// Per subject, in the order of their names; empty when no clip names a
    /// subject. Cross-subject lists are few people, and one performer unlike
    /// the others can carry most of the errors: this says whether it does.
    std::vector<SubjectScore> per_subject;
    /// A baseline against the model's own method on the same clips (paired;
    /// compare_with_model()): the clips only the model gets right, those only
    /// this method gets right, and the exact McNemar p of that difference.
    bool paired = false;
    std::size_t model_only = 0, method_only = 0;
    double mcnemar_p = 1.0;
    /// The model's own method only (empty for the baselines): top_k[k − 1] is
    /// the share of clips whose true label is among the k labels its
    /// label_distances() rank first (a label tied with it ranks ahead of it;
    /// a label the model does not know, or one nothing compares with, never), for k
    /// = 1 … min(3, labels). A ranking before rejection: top-1 is above
    /// clip_accuracy when the unknown distance or the bounds turn a right label
    /// unknown, and with more than one neighbour the vote can differ from it.
    std::vector<double> top_k;
};

/// Results of `method` ready for predictions: the model's labels, then every
/// label of `clips` the model does not know (never predicted, always wrong).
ClipResults start_results(const std::string& method, const ModelView& model, const std::vector<LabelledClip>& clips);

/// Index of `label` in `labels` (labels.size() when absent).
int label_index(const std::vector<std::string>& labels, const std::string& label);

/// Fills accuracy (with its interval), unknown rate, precision, recall and
/// the per-subject scores from predictions.
void summarise(ClipResults& results, const std::vector<LabelledClip>& clips);

/// Pairs a baseline's predictions with the model's on the same clips:
/// model_only, method_only and mcnemar_p of `baseline`.
void compare_with_model(const ClipResults& model, ClipResults& baseline, const std::vector<LabelledClip>& clips);

/// The model's own method: each clip's string (runtime encoder) against the
/// representatives (runtime batch distance, kNN).
ClipResults evaluate_model(const ModelView& model, const std::vector<LabelledClip>& clips);

/// Per-frame cost of the annotator with `config` (eval's: the model's own
/// settings and the options given) over the clips' frames, joined back to
/// back as one stream, in nanoseconds (sorted).
std::vector<double> annotator_frame_times(const ModelView& model, const std::vector<LabelledClip>& clips,
                                          const AnnotatorConfig& config);

}  // namespace host
}  // namespace actionstring
