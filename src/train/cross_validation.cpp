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

std::vector<std::vector<std::string>> subject_folds(const std::vector<LabelledClip>& clips, std::size_t max_folds) {
    std::set<std::string> subject_set;
    for (const LabelledClip& c : clips) subject_set.insert(c.subject);
    const std::vector<std::string> subjects(subject_set.begin(), subject_set.end());
    const std::size_t count = max_folds > 0 ? std::min(max_folds, subjects.size()) : subjects.size();
    std::vector<std::vector<std::string>> folds(count);
    for (std::size_t s = 0; s < subjects.size(); ++s) folds[s % count].push_back(subjects[s]);
    return folds;
}

std::vector<FoldResult> cross_validate(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                                       std::size_t max_folds) {
    const std::vector<std::vector<std::string>> groups = subject_folds(clips, max_folds);
    if (groups.size() < 2)
        throw std::invalid_argument("cross-validation needs at least two subjects in the list's subject column");
    std::vector<FoldResult> folds(groups.size());
    TrainingOptions quiet = options;
    quiet.progress = nullptr;
    parallel_for(groups.size(), std::min<std::size_t>(2, hardware_workers()), [&](std::size_t k) {
        const std::vector<std::string>& held = groups[k];
        std::vector<LabelledClip> train, held_out;
        for (const LabelledClip& c : clips)
            (std::find(held.begin(), held.end(), c.subject) != held.end() ? held_out : train).push_back(c);
        TrainingReport report;
        const ModelData model = train_model(train, quiet, &report);
        std::string name;
        for (const std::string& s : held) name += (name.empty() ? "" : "+") + s;
        const ClipScore score = clip_score(model.view(), held_out);
        folds[k] = {name, held_out.size(), score.accuracy, report.representatives, score.margin};
    });
    return folds;
}

double mean_accuracy(const std::vector<FoldResult>& folds) {
    double sum = 0;
    for (const FoldResult& f : folds) sum += f.clip_accuracy;
    return folds.empty() ? 0.0 : sum / static_cast<double>(folds.size());
}

double mean_margin(const std::vector<FoldResult>& folds) {
    double sum = 0;
    for (const FoldResult& f : folds) sum += f.margin;
    return folds.empty() ? 0.0 : sum / static_cast<double>(folds.size());
}

}  // namespace host
}  // namespace actionstring
