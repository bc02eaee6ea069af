// Leave-one-subject-out cross-validation.
#include "train/cross_validation.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "common/parallel.hpp"
#include "run/classify.hpp"
#include "train/pipeline.hpp"

namespace actionstring {
namespace host {

std::vector<FoldResult> cross_validate(const std::vector<LabelledClip>& clips, const TrainingOptions& options) {
    std::set<std::string> subject_set;
    for (const LabelledClip& c : clips) subject_set.insert(c.subject);
    if (subject_set.size() < 2)
        throw std::invalid_argument("cross-validation needs at least two subjects in the list's subject column");
    const std::vector<std::string> subjects(subject_set.begin(), subject_set.end());
    std::vector<FoldResult> folds(subjects.size());
    TrainingOptions quiet = options;
    quiet.progress = nullptr;
    parallel_for(subjects.size(), std::min<std::size_t>(2, hardware_workers()), [&](std::size_t k) {
        std::vector<LabelledClip> train, held_out;
        for (const LabelledClip& c : clips) (c.subject == subjects[k] ? held_out : train).push_back(c);
        TrainingReport report;
        const ModelData model = train_model(train, quiet, &report);
        folds[k] = {subjects[k], held_out.size(), clip_accuracy(model.view(), held_out), report.representatives};
    });
    return folds;
}

double mean_accuracy(const std::vector<FoldResult>& folds) {
    double sum = 0;
    for (const FoldResult& f : folds) sum += f.clip_accuracy;
    return folds.empty() ? 0.0 : sum / static_cast<double>(folds.size());
}

}  // namespace host
}  // namespace actionstring
