// actionstring host library — the settings of a training run and what it reports.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "actionstring/model.hpp"
#include "actionstring/segmenter.hpp"
#include "train/gmm_em.hpp"
#include "train/rejection.hpp"

namespace actionstring {
namespace host {

/// Every training parameter, with the defaults the CLI documents. The
/// defaults were chosen on hdm05/val.tsv (cross-subject), never on a test
/// list: J = 20 and PCA to 24 dimensions generalised to the held-out actor
/// better than the paper's J = 40 (0.82–0.96 clip accuracy over EM seeds,
/// against 0.68–0.80), whole-DTW matching far better than the paper's
/// boundaries (see models/README.md for the measurements).
struct TrainingOptions {
    // Features.
    int components = 20;  ///< J.
    Covariance covariance = Covariance::full;
    double covariance_floor = 1e-4;  ///< λ/N̄ of the MAP prior: variance added to an average component (units²).
    int pca_dim = 24;                ///< d; 0 = no projection.
    double feature_rate_hz = 30.0;   ///< Frames per second used to fit the GMM and the tree.
    int em_max_iterations = 100;
    /// EM runs from seeds seed, seed+1, …; the fit with the highest final
    /// objective (training data only) is kept. Default 1: on hdm05 the
    /// training likelihood did not reliably pick the seeds that generalise
    /// (8 restarts from three base seeds gave 0.955, 0.795, 0.909 on val).
    int em_restarts = 1;
    double em_tolerance = 1e-6;  ///< Stop when the objective's relative change is below this.
    ScaleMode scale_mode = ScaleMode::none;
    /// Weight of the pose's velocity beside the pose (motion.hpp); 0 = none.
    double velocity_weight = 0.0;
    /// Also train on every clip mirrored (left and right swapped): for data
    /// whose classes are not lateral, so left- and right-handed people match.
    bool mirror = false;
    /// Time the velocity is taken over, in seconds (10 ms to 2 s); the
    /// acceleration too.
    double velocity_span_s = 0.2;
    /// Weight of the change of that velocity across the span (motion.hpp),
    /// after the velocity; 0 = none.
    double acceleration_weight = 0.0;
    /// The joints the model reads (names; the root and hips are added). Empty:
    /// an engine rig's built-in body joints, or every joint of other skeletons
    /// (select_pose_joints() in run/skeleton.hpp).
    std::vector<std::string> pose_joints;
    // Characters.
    double epsilon = 1.0;  ///< Split a cluster whose L1 diameter is ≥ ε.
    int max_characters = 4096;
    // Strings and representatives.
    double string_rate_hz = 12.0;
    MatchVariant variant = MatchVariant::whole;
    LengthNormalization normalization = LengthNormalization::none;
    double sigma = 6.0;            ///< Merge clusters while their centroid distance ≤ σ.
    bool keep_singletons = false;  ///< Paper: clusters of one string are noise.
    /// Bound on the representatives' characters in all (0: none). The
    /// segmenter and the window rule pass over every representative character
    /// once per character, so this bounds their per-frame cost (README,
    /// "Benchmarks"): clusters keep merging past σ, nearest first, until the
    /// medoids kept fit.
    int max_representative_chars = 0;
    /// The same bound as a share of the characters σ's clusters leave (0 < F <
    /// 1; 0: none): merging goes on past σ until the medoids fit in F times
    /// those. Unlike a count, a share means the same on a list of any size, so
    /// a config can carry it to other data (and a fold trains as the full list).
    /// With both, the tighter one binds.
    double max_representative_share = 0.0;
    // Labelling.
    /// λ: weight of the characters' label votes beside DTW in clip
    /// classification (vote_penalties() in classify.hpp); 0 = DTW alone. 1 was
    /// chosen on the training subjects' folds of HDM05, MSR Action3D and
    /// UTKinect (models/README.md).
    double vote_weight = 1.0;
    /// α: added to every character's count when estimating P(c | label), so an
    /// unseen key-pose costs a finite amount.
    double vote_smoothing = 0.01;
    /// Exemplars per label (exemplars.hpp): k-means centres of each label's
    /// training features, whose mean nearest distance over a clip's characters
    /// joins the votes in clip classification with weight `exemplar_weight`
    /// (relative to the training features' own mean distance). 0: none.
    int exemplars = 0;
    double exemplar_weight = 0.0;
    /// The features' leading coordinates the exemplars keep, 0 = all (at most
    /// the feature's d): each centre costs this many multiply-adds per
    /// character, and a PCA feature's first coordinates hold most of its variance.
    int exemplar_dims = 0;
    /// With exemplars and a list of recordings: centres of "no action" too,
    /// from the unlabelled stretches (at most `exemplars` of them), which the
    /// segmenter weighs against the labels' (segment-exemplars).
    bool no_action_exemplars = true;
    /// The clip descriptor (descriptor.hpp): a temporal pyramid of
    /// `descriptor_levels` levels over the features' first `descriptor_dims`
    /// coordinates (0 = all, at most 64), scored by ridge regression with
    /// penalty `descriptor_ridge`; its penalties join the votes in clip
    /// classification with weight `descriptor_weight`. Levels 0: none.
    int descriptor_levels = 0;
    int descriptor_dims = 0;
    double descriptor_ridge = 1000.0;
    double descriptor_weight = 0.0;
    /// The motion directions (descriptor.hpp): each pose joint's histograms
    /// of step directions over a pyramid of `direction_levels` levels, scored
    /// per label by ridge regression with penalty `direction_ridge`; their
    /// penalties join the descriptor's with weight `direction_weight`. Levels 0: none.
    int direction_levels = 0;
    double direction_ridge = 1000.0;
    double direction_weight = 0.0;
    /// The window's directions (descriptor.hpp, window_direction_penalties()):
    /// the same histograms over a stream's last `direction_window_s` seconds
    /// of characters, scored per label by a ridge regression (penalty
    /// `direction_window_ridge`) fitted on every training clip's windows; the
    /// segmenter weighs them by online.direction_weight (segment-directions).
    /// 0 s: none.
    double direction_window_s = 0.0;
    double direction_window_ridge = 1000.0;
    int neighbours = 1;
    double window_seconds = 2.0;
    double step_seconds = 0.5;
    double unknown_distance = -1.0;  ///< < 0: never unknown.
    /// Learn each label's rejection bound (train/rejection.hpp), so what is
    /// unlike every label's training clips is unknown.
    bool reject = false;
    /// Fraction of a label's held-out training clips its bound must keep.
    double reject_keep = 0.95;
    /// The segmenter's settings, stored in the model: a device uses them unless told otherwise.
    SegmenterConfig online;
    /// The events' shortest action, stored in the model (AnnotatorConfig::min_action_us).
    std::int64_t min_action_us = 250000;
    /// How much earlier than its tick a character's label applies, stored in
    /// the model (AnnotatorConfig::label_lead_us).
    std::int64_t label_lead_us = 0;
    /// Self-tuning's online search keeps only settings whose mean detection
    /// latency on the folds (true start → `started` report) is at most this
    /// many seconds, and then also tries shorter settle delays (1 and 1.5 s);
    /// 0 = no budget. A tuning directive: the model stores what it chose.
    double latency_budget_s = 0.0;
    std::uint32_t seed = 1;
    /// Called with the name of each stage as it starts (progress reports); may be empty.
    std::function<void(const char*)> progress;
    /// Called after every EM iteration with the restart's index (restarts run
    /// on two threads at once: the callee must be thread-safe); may be empty.
    std::function<void(int restart, const EmProgress&)> em_progress;
};

/// Timings and sizes of one training run.
struct TrainingReport {
    std::size_t frames_read = 0, frames_used = 0, frames_rejected = 0, feature_samples = 0;
    EmReport em;
    int em_restart_chosen = 0;                  ///< Index of the kept restart.
    std::vector<double> em_restart_objectives;  ///< Final objective of each restart.
    int characters = 0;
    int strings = 0, representatives = 0;
    std::size_t representative_chars = 0;  ///< Characters of all representatives (the segmenter's cells).
    /// The characters max_representative_share allowed (0 without one).
    std::size_t representative_budget = 0;
    /// Distance of the last merge past σ that max_representative_chars asked
    /// for (0: the bound, if any, needed none).
    double budget_merge_distance = 0;
    std::vector<int> representatives_per_label;
    std::vector<std::pair<std::string, double>> stage_seconds;
    std::vector<LabelBoundReport> label_bounds;  ///< Per label, when reject is on.
    int no_action_stretches = 0;  ///< Stretches of no action the model learned its "no action" votes from.
    std::string skeleton;  ///< Which joints were kept, e.g. "CC_Base rig: 23 of 100 joints" ("" all of them).
};

}  // namespace host
}  // namespace actionstring
