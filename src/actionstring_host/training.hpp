// actionstring host library — training: PCA, GMM by EM, the ε cluster tree,
// training strings and representative strings (DESIGN §1).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "actionstring/classify.hpp"
#include "actionstring/model.hpp"
#include "actionstring_host/clip.hpp"
#include "actionstring_host/model_data.hpp"

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
    int components = 20;                        ///< J.
    Covariance covariance = Covariance::full;
    double covariance_floor = 1e-4;             ///< λ/N̄ of the MAP prior: variance added to an average component (units²).
    int pca_dim = 24;                           ///< d; 0 = no projection.
    double feature_rate_hz = 30.0;              ///< Frames per second used to fit the GMM and the tree.
    int em_max_iterations = 100;
    /// EM runs from seeds seed, seed+1, …; the fit with the highest final
    /// objective (training data only) is kept. Default 1: on hdm05 the
    /// training likelihood did not reliably pick the seeds that generalise
    /// (8 restarts from three base seeds gave 0.955, 0.795, 0.909 on val).
    int em_restarts = 1;
    double em_tolerance = 1e-6;                 ///< Stop when the objective's relative change is below this.
    ScaleMode scale_mode = ScaleMode::none;
    // Characters.
    double epsilon = 1.0;                       ///< Split a cluster whose L1 diameter is ≥ ε.
    int max_characters = 4096;
    // Strings and representatives.
    double string_rate_hz = 12.0;
    MatchVariant variant = MatchVariant::whole;
    LengthNormalization normalization = LengthNormalization::none;
    double sigma = 6.0;                         ///< Merge clusters while their centroid distance ≤ σ.
    bool keep_singletons = false;               ///< Paper: clusters of one string are noise.
    // Labelling.
    int neighbours = 1;
    double window_seconds = 2.0;
    double step_seconds = 0.5;
    double unknown_distance = -1.0;             ///< < 0: never unknown.
    std::uint32_t seed = 1;
    /// Called with the name of each stage as it starts (progress reports); may be empty.
    std::function<void(const char*)> progress;
};

/// One training or evaluation clip with its label.
struct LabelledClip {
    Clip clip;
    std::string label;
    std::string subject;
};

/// What fitting the GMM did, for reports and tests.
struct EmReport {
    std::vector<double> objective;       ///< Penalised log-likelihood after each iteration.
    std::vector<double> log_likelihood;  ///< Plain log-likelihood after each iteration.
    std::vector<int> reseeded;           ///< Iterations at which an emptied component was re-seeded.
    int dropped = 0;                     ///< Components dropped after collapsing a third time.
    bool converged = false;
};

/// A GMM fitted in double precision.
struct GmmFit {
    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covariances;
    std::vector<double> weights;
    EmReport report;
};

/// Fits a J-component GMM to the columns of `samples` (d × N) by EM from a
/// k-means++ start (seeded). The covariance update is the MAP estimate
/// Σ_j = (S_j + λ I) / N_j with λ = covariance_floor · N / J, so the objective
/// log-likelihood − ½ λ Σ_j tr(Σ_j⁻¹) never decreases. A component left with
/// (almost) no responsibility is re-seeded at the worst-explained sample with
/// the other components' mean covariance and weight 1/J; one that collapses a
/// third time is dropped, so the fit may return fewer than J components.
/// Both are recorded in the report (the objective may drop at those iterations). Throws std::invalid_argument for fewer samples
/// than components or non-finite samples.
GmmFit fit_gmm(const Eigen::MatrixXd& samples, int components, Covariance covariance, double covariance_floor,
               int max_iterations, double tolerance, std::uint32_t seed);

/// Principal axes of the columns of `samples`: mean and the top `dim` axes as
/// rows of a dim × D matrix, largest variance first, each with its sign fixed
/// (largest |component| positive) so results do not depend on the solver.
void fit_pca(const Eigen::MatrixXd& samples, int dim, Eigen::VectorXd& mean, Eigen::MatrixXd& axes);

/// Timings and sizes of one training run.
struct TrainingReport {
    std::size_t frames_read = 0, frames_used = 0, frames_rejected = 0, feature_samples = 0;
    EmReport em;
    int em_restart_chosen = 0;                ///< Index of the kept restart.
    std::vector<double> em_restart_objectives; ///< Final objective of each restart.
    int characters = 0;
    int strings = 0, representatives = 0;
    std::vector<int> representatives_per_label;
    std::vector<std::pair<std::string, double>> stage_seconds;
};

/// Trains every table of a model from labelled clips (all on one skeleton).
/// The runtime's own code normalises, projects, computes posteriors,
/// descends the tree, samples strings and measures string distances.
/// Throws std::invalid_argument with a clear message on unusable input.
ModelData train_model(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                      TrainingReport* report = nullptr);

/// The action string of a clip under a trained model (the runtime's encoder).
std::vector<Character> clip_string(const ModelView& model, const Clip& clip);

}  // namespace host
}  // namespace actionstring

namespace actionstring {
namespace host {

/// Label of a whole clip's string: the runtime's batch distance to every
/// representative (the string is the query), then the runtime's kNN.
Classification classify_string(const ModelView& model, const std::vector<Character>& string);

/// Fraction of clips whose predicted label name equals their label.
double clip_accuracy(const ModelView& model, const std::vector<LabelledClip>& clips);

}  // namespace host
}  // namespace actionstring
