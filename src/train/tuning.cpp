// Training that tunes itself by cross-validation.
#include "train/tuning.hpp"

#include "common/time.hpp"
#include "train/settings.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <utility>
#include <cstdio>
#include <sstream>

namespace actionstring {
namespace host {
namespace {

std::string number(double v) { return setting_value_text(v); }

// One setting and the values tried for it.
struct Axis {
    const char* name;
    std::vector<double> values;
    std::function<void(TrainingOptions&, double)> set;
    std::function<bool(const TrainingOptions&)> applies = [](const TrainingOptions&) { return true; };
    /// A setting that only saves work: kept when its fold mean ties the best too.
    bool cheaper = false;
};

}  // namespace

TrainingOptions tuning_start() {
    TrainingOptions o;
    o.components = 0;
    o.pca_dim = 24;
    o.epsilon = 0.7;
    o.sigma = 0.75;
    o.keep_singletons = true;
    return o;
}

TuningResult tune_training(const std::vector<LabelledClip>& clips, const TrainingOptions& start,
                           const std::function<void(const TuningStep&)>& progress) {
    const auto began = std::chrono::steady_clock::now();
    TuningResult result;
    result.options = start;
    const bool has_parents = !clips.empty() && clips.front().clip.parents.size() == clips.front().clip.joint_count();
    std::vector<Axis> axes{
        {"velocity", {0.0, 0.5, 1.0, 2.0}, [](TrainingOptions& o, double v) { o.velocity_weight = v; }},
        {"velocity-span",
         {0.2, 0.4, 0.6},
         [](TrainingOptions& o, double v) { o.velocity_span_s = v; },
         [](const TrainingOptions& o) { return o.velocity_weight > 0; }},
        // After the span, which it shares: over a span of few frames (0.2 s at
        // MSR's 15 Hz) the velocity's change is mostly noise. One weight: the
        // shared lists' folds favour 0.5 where it helps at all (models/README.md,
        // "Acceleration").
        {"acceleration", {0.5}, [](TrainingOptions& o, double v) { o.acceleration_weight = v; }},
        {"mirror", {0.0, 1.0}, [](TrainingOptions& o, double v) { o.mirror = v > 0; }},
        {"string-rate", {8.0, 12.0, 15.0, 20.0}, [](TrainingOptions& o, double v) { o.string_rate_hz = v; }},
        {"epsilon", {0.5, 0.7, 1.0}, [](TrainingOptions& o, double v) { o.epsilon = v; }},
        {"sigma", {0.3, 0.75, 1.5}, [](TrainingOptions& o, double v) { o.sigma = v; }},
        {"pca", {16.0, 24.0, 32.0}, [](TrainingOptions& o, double v) { o.pca_dim = static_cast<int>(v); }},
        {"vote-weight", {0.0, 0.5, 2.0}, [](TrainingOptions& o, double v) { o.vote_weight = v; }},
        // 64 centres per label, the weight tuned (models/README.md, "Exemplars").
        {"exemplar-weight",
         {1.0, 4.0},
         [](TrainingOptions& o, double v) {
             o.exemplars = v > 0 ? 64 : 0;
             o.exemplar_weight = v;
         }},
        // Then the exemplars in half the feature's leading coordinates (a
        // multiple of four, the lanes' width): half their work per character,
        // kept when the folds do as well (models/README.md, "Exemplars of fewer
        // dimensions": MSR's folds 0.829 against 0.822, UTKinect's lost).
        {"exemplar-dims",
         {0.5},
         [](TrainingOptions& o, double v) {
             const int half = static_cast<int>(std::lround(o.pca_dim * v / 4.0)) * 4;
             o.exemplar_dims = half >= 4 && half < o.pca_dim ? half : 0;
         },
         [](const TrainingOptions& o) { return o.exemplars > 0 && o.exemplar_weight > 0 && o.pca_dim >= 8; },
         true},
        // The clip descriptor over three levels, the ridge the shared lists'
        // folds agreed on, three weights spanning where their folds peaked
        // (models/README.md, "The clip descriptor": MSR's folds 0.828 → 0.883 at
        // 24 to 32, UTKinect's 0.922 → 0.939 at 16 and 64, HDM05's at its
        // ceiling with 4 to 8). Every coordinate of the feature, which the PCA
        // dimensions tried keep within the descriptor's 64.
        {"descriptor-weight",
         {4.0, 16.0, 32.0},
         [](TrainingOptions& o, double v) {
             o.descriptor_levels = v > 0 ? 3 : 0;
             o.descriptor_ridge = 3000.0;
             o.descriptor_weight = v;
         },
         [](const TrainingOptions& o) { return o.pca_dim > 0 && o.pca_dim <= 64; }},
        // The motion directions over three levels, the ridge MSR's folds took
        // (models/README.md, "The motion directions": MSR's folds 0.883 → 0.904
        // at 8 to 12, HDM05's at its ceiling up to 2, UTKinect's unmoved).
        {"direction-weight",
         {2.0, 8.0, 16.0},
         [](TrainingOptions& o, double v) {
             o.direction_levels = v > 0 ? 3 : 0;
             o.direction_ridge = 3000.0;
             o.direction_weight = v;
         }},
    };
    auto describe = [](const Axis& axis, double v, const TrainingOptions& trial) {
        if (std::string(axis.name) == "mirror") return std::string("mirror ") + (v > 0 ? "true" : "false");
        if (std::string(axis.name) == "exemplar-weight") return "exemplars 64, exemplar-weight " + number(v);
        if (std::string(axis.name) == "exemplar-dims") return "exemplar-dims " + std::to_string(trial.exemplar_dims);
        if (std::string(axis.name) == "descriptor-weight")
            return "descriptor-levels 3, descriptor-ridge 3000, descriptor-weight " + number(v);
        if (std::string(axis.name) == "direction-weight")
            return "direction-levels 3, direction-ridge 3000, direction-weight " + number(v);
        return std::string(axis.name) + " " + number(v);
    };
    // The PCA dimension never exceeds the input's (a small skeleton, no velocity).
    const std::size_t pose_dim = clips.empty() ? 0 : 3 * (clips.front().clip.joint_count() - 1);
    auto fitted = [pose_dim](TrainingOptions o) {
        const std::size_t input_dim =
            pose_dim * (1u + (o.velocity_weight > 0 ? 1u : 0u) + (o.acceleration_weight > 0 ? 1u : 0u));
        if (static_cast<std::size_t>(o.pca_dim) > input_dim) o.pca_dim = static_cast<int>(input_dim);
        return o;
    };
    if (has_parents && result.options.scale_mode == ScaleMode::none) result.options.scale_mode = ScaleMode::torso;
    result.options = fitted(result.options);
    // A setting's score: the fold mean averaged over three seeds of the tree's
    // k-means (one seed's luck moves a fold mean by several points), and beside
    // it the mean signed margin, which decides between settings whose fold
    // means tie: at a list's ceiling (every held-out clip right) accuracy can
    // no longer tell a setting that wins by far from one that wins by a hair.
    struct Score {
        double accuracy = 0, margin = 0;
    };
    auto score = [&clips](const TrainingOptions& o, std::vector<FoldResult>& first_folds) {
        Score s;
        for (std::uint32_t k = 0; k < 3; ++k) {
            TrainingOptions seeded = o;
            seeded.seed = o.seed + k;
            std::vector<FoldResult> folds = cross_validate(clips, seeded, tuning_max_folds);
            s.accuracy += mean_accuracy(folds) / 3.0;
            s.margin += mean_margin(folds) / 3.0;
            if (k == 0) first_folds = std::move(folds);
        }
        return s;
    };
    // Fold means within this are equal (the same clips right, summed in another order).
    constexpr double tie = 1e-9;
    Score best = score(result.options, result.folds);
    TuningStep first{"(the starting settings)", best.accuracy, best.margin, true};
    result.steps.push_back(first);
    if (progress) progress(first);
    for (const Axis& axis : axes) {
        if (!axis.applies(result.options)) continue;
        TrainingOptions current = result.options;
        for (double v : axis.values) {
            TrainingOptions trial = current;
            axis.set(trial, v);
            trial = fitted(trial);
            TuningStep step{describe(axis, v, trial), 0.0, 0.0, false};
            try {
                std::vector<FoldResult> folds;
                const Score s = score(trial, folds);
                step.mean_accuracy = s.accuracy;
                step.mean_margin = s.margin;
                const bool ties = std::fabs(s.accuracy - best.accuracy) <= tie;
                if (s.accuracy > best.accuracy + tie || (ties && (axis.cheaper || s.margin > best.margin))) {
                    best = s;
                    result.options = trial;
                    result.folds = std::move(folds);
                    step.kept = true;
                }
            } catch (const std::invalid_argument&) {
                step.setting += " (cannot train)";
            }
            result.steps.push_back(step);
            if (progress) progress(step);
        }
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    return result;
}

std::string options_as_config(const TrainingOptions& o) {
    static const char* const covariance[] = {"full", "diagonal"};
    static const char* const scale[] = {"none", "hip-width", "bones", "torso"};
    static const char* const variant[] = {"paper", "whole", "subsequence"};
    static const char* const normalization[] = {"none", "path", "query"};
    std::ostringstream out;
    out << "components " << o.components << "\ncovariance " << covariance[static_cast<int>(o.covariance)] << "\npca "
        << o.pca_dim << "\nscale " << scale[static_cast<int>(o.scale_mode)] << "\nvelocity "
        << number(o.velocity_weight) << "\nvelocity-span " << number(o.velocity_span_s) << "\nacceleration "
        << number(o.acceleration_weight) << "\nepsilon " << number(o.epsilon) << "\nstring-rate "
        << number(o.string_rate_hz) << "\nvariant " << variant[static_cast<int>(o.variant)] << "\nnormalization "
        << normalization[static_cast<int>(o.normalization)] << "\nsigma " << number(o.sigma) << "\nkeep-singletons "
        << (o.keep_singletons ? "true" : "false") << "\nmirror " << (o.mirror ? "true" : "false") << "\nneighbours "
        << o.neighbours << "\nvote-weight " << number(o.vote_weight) << "\nvote-smoothing " << number(o.vote_smoothing)
        << "\nseed " << o.seed << "\nsettle " << number(us_to_seconds(o.online.settle_delay_us)) << "\nsettle-stable "
        << number(us_to_seconds(o.online.settle_stable_us)) << "\nsegment-penalty " << number(o.online.segment_penalty)
        << "\nstay-penalty " << number(o.online.stay_penalty) << "\nskip-penalty " << number(o.online.skip_penalty)
        << "\nunknown-cost " << number(o.online.unknown_cost) << "\nsegment-votes " << number(o.online.vote_weight)
        << "\nmin-action " << number(us_to_seconds(o.min_action_us)) << "\nlabel-lead "
        << number(us_to_seconds(o.label_lead_us)) << "\n";
    if (o.max_representative_chars > 0) out << "max-representative-chars " << o.max_representative_chars << "\n";
    if (o.max_representative_share > 0)
        out << "max-representative-share " << number(o.max_representative_share) << "\n";
    if (o.reject) out << "reject true\nreject-keep " << number(o.reject_keep) << "\n";
    if (o.exemplars > 0) out << "exemplars " << o.exemplars << "\nexemplar-weight " << number(o.exemplar_weight) << "\n";
    if (o.exemplars > 0 && o.exemplar_dims > 0) out << "exemplar-dims " << o.exemplar_dims << "\n";
    if (o.exemplars > 0 && !o.no_action_exemplars) out << "no-action-exemplars false\n";
    if (o.descriptor_levels > 0 && o.descriptor_weight > 0) {
        out << "descriptor-levels " << o.descriptor_levels << "\ndescriptor-weight " << number(o.descriptor_weight)
            << "\ndescriptor-ridge " << number(o.descriptor_ridge) << "\n";
        if (o.descriptor_dims > 0) out << "descriptor-dims " << o.descriptor_dims << "\n";
    }
    if (o.direction_levels > 0 && o.direction_weight > 0)
        out << "direction-levels " << o.direction_levels << "\ndirection-weight " << number(o.direction_weight)
            << "\ndirection-ridge " << number(o.direction_ridge) << "\n";
    if (o.direction_window_s > 0)
        out << "direction-window " << number(o.direction_window_s) << "\ndirection-window-ridge "
            << number(o.direction_window_ridge) << "\n";
    if (o.online.exemplar_weight > 0) out << "segment-exemplars " << number(o.online.exemplar_weight) << "\n";
    if (o.online.direction_weight > 0) out << "segment-directions " << number(o.online.direction_weight) << "\n";
    if (!o.pose_joints.empty()) {
        out << "pose-joints ";
        for (std::size_t j = 0; j < o.pose_joints.size(); ++j) out << (j ? "," : "") << o.pose_joints[j];
        out << "\n";
    }
    return out.str();
}

}  // namespace host
}  // namespace actionstring
