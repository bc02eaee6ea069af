// The training pipeline (design §1), one function per stage: every per-frame
// computation goes through the runtime's own code on the float tables, so the
// strings and representatives are what the device will see.
#include "train/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "actionstring/storage.hpp"
#include "actionstring/gmm.hpp"
#include "actionstring/projection.hpp"
#include "actionstring/string_distance.hpp"
#include "common/parallel.hpp"
#include "common/stats.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "train/augment.hpp"
#include "train/clustering.hpp"
#include "train/gmm_order.hpp"
#include "train/pca.hpp"
#include "train/descriptor.hpp"
#include "train/exemplars.hpp"
#include "train/rejection.hpp"
#include "train/settings.hpp"

namespace actionstring {
namespace host {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Times one stage and tells the caller's progress hook when it starts.
class StageTimer {
public:
    StageTimer(const TrainingOptions& options, TrainingReport& report) : options_(options), report_(report) {}
    void start(const char* progress) {
        if (options_.progress) options_.progress(progress);
        start_ = Clock::now();
    }
    void finish(const char* stage) { report_.stage_seconds.emplace_back(stage, seconds_since(start_)); }

private:
    const TrainingOptions& options_;
    TrainingReport& report_;
    Clock::time_point start_ = Clock::now();
};

void check_options(const TrainingOptions& o) {
    auto require = [](bool ok, const char* what) {
        if (!ok) throw std::invalid_argument(what);
    };
    require(o.components >= 0 && o.components <= 256, "components (J) must be between 0 (no GMM) and 256");
    require(o.neighbours >= 1 && o.neighbours <= static_cast<int>(max_neighbours), "k must be between 1 and 64");
    require(o.covariance_floor > 0, "the covariance floor must be positive");
    require(o.pca_dim >= 0, "the PCA dimension must be ≥ 0");
    require(o.feature_rate_hz > 0 && o.string_rate_hz > 0, "rates must be positive");
    require(o.string_rate_hz >= 1.0 && o.string_rate_hz <= 1000.0, "the string rate must be between 1 and 1000 Hz");
    require(o.epsilon > 0, "ε must be positive");
    require(o.sigma >= 0, "σ must be ≥ 0");
    require(o.neighbours >= 1, "k must be ≥ 1");
    require(o.window_seconds > 0 && o.step_seconds > 0, "window and step must be positive");
    require(o.em_max_iterations >= 1, "EM needs at least one iteration");
    require(o.em_restarts >= 1 && o.em_restarts <= 64, "EM restarts must be between 1 and 64");
    require(o.max_characters >= 1 && o.max_characters <= 4096, "the character limit must be between 1 and 4096");
    require(o.velocity_weight >= 0 && o.velocity_weight <= 1000, "the velocity weight must be between 0 and 1000");
    require(o.velocity_span_s >= 0.01 && o.velocity_span_s <= 2, "the velocity span must be between 0.01 and 2 s");
    require(o.acceleration_weight >= 0 && o.acceleration_weight <= 1000,
            "the acceleration weight must be between 0 and 1000");
    require(o.vote_weight >= 0 && o.vote_weight <= 1000, "the vote weight must be between 0 and 1000");
    require(o.vote_smoothing >= 1e-6 && o.vote_smoothing <= 1e3, "the vote smoothing must be between 1e-6 and 1000");
    require(o.exemplars >= 0 && o.exemplars <= 4096, "exemplars per label must be between 0 and 4096");
    require(o.exemplar_weight >= 0 && o.exemplar_weight <= 1000, "the exemplar weight must be between 0 and 1000");
    require(o.exemplar_dims >= 0 && o.exemplar_dims <= 65535, "the exemplars' dimensions must be between 0 and 65535");
    require(o.descriptor_levels >= 0 && o.descriptor_levels <= 8, "the descriptor's levels must be between 0 and 8");
    require(o.descriptor_dims >= 0 && o.descriptor_dims <= 64, "the descriptor's dimensions must be between 0 and 64");
    require(o.descriptor_ridge > 0 && o.descriptor_ridge <= 1e9, "the descriptor's ridge must be above 0, at most 1e9");
    require(o.descriptor_weight >= 0 && o.descriptor_weight <= 1000,
            "the descriptor weight must be between 0 and 1000");
    require(o.direction_levels >= 0 && o.direction_levels <= 8, "the directions' levels must be between 0 and 8");
    require(o.direction_ridge > 0 && o.direction_ridge <= 1e9, "the directions' ridge must be above 0, at most 1e9");
    require(o.direction_weight >= 0 && o.direction_weight <= 1000, "the direction weight must be between 0 and 1000");
    require(o.direction_window_s >= 0 && o.direction_window_s <= 60,
            "the directions' window must be between 0 and 60 seconds");
    require(o.direction_window_ridge > 0 && o.direction_window_ridge <= 1e9,
            "the window directions' ridge must be above 0, at most 1e9");
    require(o.max_representative_share >= 0 && o.max_representative_share < 1,
            "the representatives' share must be at least 0 and below 1");
    require(o.online.settle_delay_us >= 0 && o.online.settle_delay_us <= 60000000,
            "the settle delay must be 0 to 60 s");
    require(o.online.settle_stable_us >= 0 && o.online.settle_stable_us <= 60000000,
            "the early settling's agreement must be 0 to 60 s");
    require(o.min_action_us >= 0 && o.min_action_us <= 60000000, "the shortest action must be 0 to 60 s");
    require(o.label_lead_us >= 0 && o.label_lead_us <= 60000000, "the label lead must be 0 to 60 s");
}

// Distance between joints a and b of one frame, in double.
double joint_distance(const float* frame, std::size_t a, std::size_t b) {
    double sum = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
        const double d = static_cast<double>(frame[3 * a + k]) - static_cast<double>(frame[3 * b + k]);
        sum += d * d;
    }
    return std::sqrt(sum);
}

// Median 3-D hip width over a clip's frames.
double median_hip_width(const Clip& clip) {
    std::vector<double> widths;
    const auto l = static_cast<std::size_t>(clip.roles.left_hip), r = static_cast<std::size_t>(clip.roles.right_hip);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) widths.push_back(joint_distance(clip.frame(f), l, r));
    return median(widths);
}

// The kinematic tree of the clips' skeleton, joints ordered parents first,
// and each bone's reference length: its mean over every training frame.
void set_bones(ModelData& m, const std::vector<LabelledClip>& clips) {
    const Clip& first = clips.front().clip;
    const std::size_t J = first.joint_count();
    if (first.parents.size() != J)
        throw std::invalid_argument(first.source +
                                    ": bone and torso scaling need the skeleton's tree (each joint's parent), "
                                    "which the file does not give and its joint names do not name all of one "
                                    "SDK's (Kinect v1, Kinect v2, Azure Kinect); give one with --parents P,P,... "
                                    "(Python: Clip(..., parents=[...])), or use --scale none");
    if (J > max_bone_joints)
        throw std::invalid_argument(first.source + ": " + std::to_string(J) +
                                    " joints; bone-length scaling takes at most " + std::to_string(max_bone_joints));
    m.joint_parents.clear();
    for (int parent : first.parents) m.joint_parents.push_back(static_cast<std::int16_t>(parent));
    // Parents first: roots, then each joint whose parent is placed, in index order.
    std::vector<bool> placed(J, false);
    m.bone_order.clear();
    while (m.bone_order.size() < J) {
        const std::size_t before = m.bone_order.size();
        for (std::size_t j = 0; j < J; ++j) {
            const int parent = first.parents[j];
            if (!placed[j] && (parent < 0 || placed[static_cast<std::size_t>(parent)])) {
                placed[j] = true;
                m.bone_order.push_back(static_cast<std::uint16_t>(j));
            }
        }
        if (m.bone_order.size() == before)
            throw std::invalid_argument(first.source + ": the joints' parents form a cycle");
    }
    std::vector<double> sum(J, 0.0);
    std::size_t frames = 0;
    for (const LabelledClip& c : clips)
        for (std::size_t f = 0; f < c.clip.frame_count(); ++f) {
            if (!c.clip.lost.empty() && c.clip.lost[f]) continue;
            const float* p = c.clip.frame(f);
            for (std::size_t j = 0; j < J; ++j)
                if (first.parents[j] >= 0) sum[j] += joint_distance(p, j, static_cast<std::size_t>(first.parents[j]));
            ++frames;
        }
    if (frames == 0) throw std::invalid_argument("no tracked frame to measure bone lengths on");
    m.bone_lengths.clear();
    for (std::size_t j = 0; j < J; ++j)
        m.bone_lengths.push_back(static_cast<float>(sum[j] / static_cast<double>(frames)));
    if (m.scale_mode == ScaleMode::torso) {
        // Only the torso's bones measure a frame's size; the others keep length 0.
        const std::vector<bool> torso = torso_bones(first.parents, first.roles);
        float total = 0.0f;
        for (std::size_t j = 0; j < J; ++j) {
            if (j >= torso.size() || !torso[j]) m.bone_lengths[j] = 0.0f;
            total += m.bone_lengths[j];
        }
        if (!(total > 1.0e-3f))
            throw std::invalid_argument(first.source +
                                        ": no torso bone (hips, spine, neck, shoulders) of any length to scale "
                                        "by; use --scale bones or none");
    }
}

// Stage 0: the skeleton tables, from the first clip (all clips share its joints).
ModelData start_model(const std::vector<LabelledClip>& clips, const TrainingOptions& options, TrainingReport& r) {
    if (clips.empty()) throw std::invalid_argument("no training clips");
    const Clip& first = clips.front().clip;
    for (const LabelledClip& c : clips) {
        if (c.clip.joint_names != first.joint_names)
            throw std::invalid_argument(c.clip.source + ": its joints (" + std::to_string(c.clip.joint_count()) +
                                        ") differ from " + first.source + "'s (" + std::to_string(first.joint_count()) +
                                        "); name the joints to train on, present in every file: --pose-joints "
                                        "NAME,NAME,...");
        r.frames_read += c.clip.frame_count();
    }
    if (!first.roles.complete())
        throw std::invalid_argument(first.source +
                                    ": root and hip joints unknown; name them (--roles ROOT,LEFT_HIP,RIGHT_HIP)");
    if (first.roles.left_hip == first.roles.right_hip)
        throw std::invalid_argument(first.source + ": the left and right hip are the same joint (" +
                                    first.joint_names[static_cast<std::size_t>(first.roles.left_hip)] +
                                    "), so no frame has a facing direction; name two hips with --roles");
    ModelData m;
    m.joint_count = static_cast<std::uint16_t>(first.joint_count());
    m.joint_names.assign(first.joint_names.begin(), first.joint_names.end());
    m.root_joint = static_cast<std::uint16_t>(first.roles.root);
    m.left_hip_joint = static_cast<std::uint16_t>(first.roles.left_hip);
    m.right_hip_joint = static_cast<std::uint16_t>(first.roles.right_hip);
    m.up_axis = static_cast<std::uint8_t>(first.up_axis);
    for (std::size_t j = 0; j < first.joint_count(); ++j)
        if (static_cast<int>(j) != first.roles.root) m.pose_joints.push_back(static_cast<std::uint16_t>(j));
    // The model stores dimensions in 16 bits: the input (pose, velocity and
    // acceleration, 9 per joint) must fit.
    constexpr std::size_t most_pose_joints = 65535 / 9;
    if (m.pose_joints.size() > most_pose_joints)
        throw std::invalid_argument("the skeleton has " + std::to_string(m.pose_joints.size()) +
                                    " joints besides the root; at most " + std::to_string(most_pose_joints) +
                                    " are supported");
    m.scale_mode = options.scale_mode;
    if (uses_kinematic_tree(options.scale_mode)) set_bones(m, clips);
    m.velocity_weight = static_cast<float>(options.velocity_weight);
    m.acceleration_weight = static_cast<float>(options.acceleration_weight);
    m.velocity_span_us = options.velocity_weight > 0 || options.acceleration_weight > 0
                             ? static_cast<std::uint32_t>(std::lround(options.velocity_span_s * 1e6))
                             : 0u;
    if (options.scale_mode == ScaleMode::hip_width) {
        m.reference_scale = static_cast<float>(median_hip_width(first));
        if (!(m.reference_scale > 0)) throw std::invalid_argument("hip width is zero: cannot scale by it");
    }
    return m;
}

// Stage 1: normalised poses of every clip at the feature rate.
std::vector<float> sample_training_poses(const ModelData& m, const std::vector<LabelledClip>& clips,
                                         const TrainingOptions& options, TrainingReport& r) {
    const ModelView view = m.view();
    std::vector<float> poses;
    for (const LabelledClip& c : clips) r.frames_rejected += sample_poses(view, c.clip, options.feature_rate_hz, poses);
    r.feature_samples = poses.size() / view.input_dim();
    r.frames_used = r.frames_read - r.frames_rejected;
    if (r.feature_samples == 0)
        throw std::invalid_argument("no usable frames: every frame was rejected by pose normalisation");
    return poses;
}

// Stage 2: the optional PCA, then every pose projected with the runtime's
// projection; returns the projected poses as the columns of a d × n matrix.
Eigen::MatrixXd fit_projection(ModelData& m, const std::vector<float>& poses, const TrainingOptions& options) {
    const std::size_t D = m.view().input_dim(), n = poses.size() / D;
    std::size_t d = D;
    if (options.pca_dim > 0) {
        Eigen::MatrixXd x(static_cast<Eigen::Index>(D), static_cast<Eigen::Index>(n));
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t k = 0; k < D; ++k)
                x(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = poses[i * D + k];
        Eigen::VectorXd mean;
        Eigen::MatrixXd axes;
        fit_pca(x, options.pca_dim, mean, axes);
        d = static_cast<std::size_t>(options.pca_dim);
        for (std::size_t k = 0; k < D; ++k)
            m.projection_mean.push_back(static_cast<float>(mean[static_cast<Eigen::Index>(k)]));
        for (std::size_t c = 0; c < D; ++c)
            for (std::size_t row = 0; row < d; ++row)
                m.projection_matrix.push_back(
                    static_cast<float>(axes(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c))));
    }
    if (d > 65535)
        throw std::invalid_argument("the pose has " + std::to_string(d) +
                                    " dimensions; at most 65535 are supported (use --pca)");
    m.feature_dim = static_cast<std::uint16_t>(d);
    std::vector<float> feature(d);
    Eigen::MatrixXd samples(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(n));
    const ModelView view = m.view();
    for (std::size_t i = 0; i < n; ++i) {
        project_pose(view, poses.data() + i * D, feature.data());
        for (std::size_t k = 0; k < d; ++k)
            samples(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = feature[k];
    }
    return samples;
}

// The vectors the cluster tree is built on: `dim` floats per training pose.
struct TreeFeatures {
    std::vector<float> values;
    std::size_t dim = 0;
};

// Stage 3 without a GMM (the paper's "PCA only" characters): the projected
// poses themselves, the projection scaled so every training feature lies
// within L1 distance 1 of the projected mean pose. The tree's features then
// span an L1 diameter of at most 2, as posteriors do, and ε, σ, W and the
// online penalties keep the scale they have with a GMM.
TreeFeatures projected_features(ModelData& m, const std::vector<float>& poses, const Eigen::MatrixXd& samples) {
    if (!m.view().has_projection()) throw std::invalid_argument("components 0 (no GMM) needs a projection: set --pca");
    double largest = 0.0;
    for (Eigen::Index i = 0; i < samples.cols(); ++i) largest = std::max(largest, samples.col(i).lpNorm<1>());
    if (!(largest > 0.0)) throw std::invalid_argument("every training pose projects to the same point");
    for (float& value : m.projection_matrix) value = static_cast<float>(static_cast<double>(value) / largest);
    const ModelView view = m.view();
    const std::size_t D = view.input_dim(), d = view.feature_dim, n = poses.size() / D;
    TreeFeatures features{std::vector<float>(n * d), d};
    for (std::size_t i = 0; i < n; ++i) project_pose(view, poses.data() + i * D, features.values.data() + i * d);
    return features;
}

// Stage 3 with a GMM: EM. Restarts run in parallel; each is independent and
// the choice is fixed (highest final objective, earliest on ties), so threads
// change nothing.
void fit_gmm_tables(ModelData& m, const Eigen::MatrixXd& samples, const TrainingOptions& options, TrainingReport& r) {
    // One restart: its components go to the workers; several: the restarts do
    // (a nested parallel_for runs inline). Either way the fits are the same.
    std::vector<GmmFit> fits(static_cast<std::size_t>(options.em_restarts));
    const std::size_t workers = hardware_workers();
    parallel_for(fits.size(), std::min<std::size_t>(2, workers), [&](std::size_t k) {
        std::function<void(const EmProgress&)> progress;
        if (options.em_progress)
            progress = [&options, k](const EmProgress& step) { options.em_progress(static_cast<int>(k), step); };
        fits[k] = fit_gmm(samples, options.components, options.covariance, options.covariance_floor,
                          options.em_max_iterations, options.em_tolerance, options.seed + static_cast<std::uint32_t>(k),
                          workers, progress);
    });
    std::size_t chosen = 0;
    for (std::size_t k = 0; k < fits.size(); ++k) {
        r.em_restart_objectives.push_back(fits[k].report.objective.back());
        if (fits[k].report.objective.back() > fits[chosen].report.objective.back()) chosen = k;
    }
    r.em_restart_chosen = static_cast<int>(chosen);
    const GmmFit& fit = fits[chosen];
    set_gmm(m, fit.means, fit.covariances, fit.weights, options.covariance);
    // Components live on the same poses go to the same block, so the
    // runtime's blocks stop early more often (gmm_order.hpp): the same mixture.
    const std::vector<std::size_t> order = gmm_block_order(m.view(), samples);
    GmmFit ordered;
    for (const std::size_t j : order) {
        ordered.means.push_back(fit.means[j]);
        ordered.covariances.push_back(fit.covariances[j]);
        ordered.weights.push_back(fit.weights[j]);
    }
    set_gmm(m, ordered.means, ordered.covariances, ordered.weights, options.covariance);
    r.em = fit.report;
}

// Every training pose's GMM posterior, through the runtime.
TreeFeatures posterior_features(const ModelData& m, const std::vector<float>& poses) {
    const ModelView view = m.view();
    const std::size_t D = view.input_dim(), J = view.component_count, n = poses.size() / D;
    TreeFeatures features{std::vector<float>(n * J), J};
    std::vector<float> feature(view.feature_dim), scratch(gmm_scratch_floats(view));
    // Poses come clip by clip, frame by frame, so the last pose's most probable
    // component is where the next posterior's search starts (same bits, sooner).
    std::size_t most_probable = 0;
    for (std::size_t i = 0; i < n; ++i) {
        project_pose(view, poses.data() + i * D, feature.data());
        if (gmm_posterior(view, feature.data(), features.values.data() + i * J, scratch.data(), nullptr,
                          &most_probable) != Status::ok)
            throw std::runtime_error("a training pose fell outside the GMM's float range");
    }
    return features;
}

// Stage 4: the ε cluster tree, its leaves the characters, and W between them.
void build_characters(ModelData& m, const TreeFeatures& features, const TrainingOptions& options, TrainingReport& r) {
    const ClusterTree tree =
        build_cluster_tree(features.values, features.dim, options.epsilon, options.max_characters, options.seed);
    m.node_centroids = tree.centroids;
    m.node_children = tree.children;
    m.node_characters = tree.characters;
    m.character_count = static_cast<std::uint16_t>(tree.character_count);
    set_character_distances_from_leaves(m);
    r.characters = tree.character_count;
}

// Stage 6: the label names, and the medoids of the agglomerated training
// strings as representatives, each with its cluster's majority label. Returns,
// per training clip, the representative made from it (or −1).
std::vector<long> choose_representatives(ModelData& m, const std::vector<LabelledClip>& clips,
                                         const std::vector<std::vector<Character>>& strings,
                                         const TrainingOptions& options, TrainingReport& r) {
    std::vector<long> own(clips.size(), -1);
    std::set<std::string> label_set;
    for (const LabelledClip& c : clips) label_set.insert(c.label);
    m.label_names.assign(label_set.begin(), label_set.end());
    std::map<std::string, LabelId> label_index;
    for (std::size_t l = 0; l < m.label_names.size(); ++l) label_index[m.label_names[l]] = static_cast<LabelId>(l);
    // The representatives' characters if the clusters stopped here: each kept
    // cluster's medoid (singletons only when kept).
    const auto medoid_chars = [&](const std::vector<std::vector<std::size_t>>& clusters,
                                  const std::vector<std::size_t>& medoids) {
        std::size_t chars = 0;
        for (std::size_t c = 0; c < clusters.size(); ++c)
            if (clusters[c].size() >= 2 || options.keep_singletons) chars += strings[medoids[c]].size();
        return chars;
    };
    // A cluster's label: the majority of its members' (the lowest label on ties).
    const auto majority = [&](const std::vector<std::size_t>& cluster) {
        std::vector<int> votes(m.label_names.size(), 0);
        for (std::size_t member : cluster) ++votes[label_index[clips[member].label]];
        return static_cast<LabelId>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    };
    // Past σ, the budget merges only clusters of one label, so every label
    // that has a representative keeps one (merging two clusters whose
    // majority is l leaves l the majority).
    // A share is of what σ's clusters leave: fixed at the first look past σ
    // (agglomerate() asks only once σ's merges are done), then a count like any.
    std::size_t budget = static_cast<std::size_t>(options.max_representative_chars);
    const double share = options.max_representative_share;
    bool share_fixed = false;
    ClusterBudget bound;
    if (budget > 0 || share > 0) {
        bound.over = [&](const std::vector<std::vector<std::size_t>>& clusters,
                         const std::vector<std::size_t>& medoids) {
            const std::size_t chars = medoid_chars(clusters, medoids);
            if (share > 0 && !share_fixed) {
                share_fixed = true;
                const auto of_share = static_cast<std::size_t>(std::ceil(share * static_cast<double>(chars)));
                budget = budget > 0 ? std::min(budget, of_share) : of_share;
                r.representative_budget = budget;
            }
            return chars > budget;
        };
        bound.may_merge = [&](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) {
            return majority(a) == majority(b);
        };
    }
    const auto clusters =
        agglomerate(pairwise_string_distances(m.view(), strings, MatchOptions{options.variant, options.normalization},
                                          hardware_workers()),
                    options.sigma, bound, &r.budget_merge_distance);
    if (!(r.budget_merge_distance > options.sigma)) r.budget_merge_distance = 0;
    r.representatives_per_label.assign(m.label_names.size(), 0);
    for (const auto& cluster : clusters) {
        if (cluster.size() < 2 && !options.keep_singletons) continue;
        const LabelId label = majority(cluster);
        if (strings[cluster.front()].empty()) continue;
        own[cluster.front()] = static_cast<long>(m.representative_labels.size());
        m.add_representative(strings[cluster.front()], label);
        ++r.representatives_per_label[label];
    }
    r.representatives = static_cast<int>(m.representative_labels.size());
    r.representative_chars = m.representative_chars.size();
    if (budget > 0 && r.representative_chars > budget)
        throw std::invalid_argument((share_fixed ? "max-representative-share " + setting_value_text(share) + " (" +
                                                       std::to_string(budget) + " characters)"
                                                 : "max-representative-chars " + std::to_string(budget)) +
                                    " is below what one representative per label needs (" +
                                    std::to_string(r.representative_chars) + " characters): raise it");
    if (r.representatives == 0)
        throw std::invalid_argument("σ = " + std::to_string(options.sigma) +
                                    " merges no two training strings, so there is no representative: raise --sigma "
                                    "or use --keep-singletons");
    return own;
}

// Stage 6b: the characters' label votes, log P(c | label): each training
// clip adds its characters' shares (1 / its length each, so long clips weigh
// as much as short ones), α smooths, and the table is stored label by label.
void set_votes(ModelData& m, const std::vector<LabelledClip>& clips,
               const std::vector<std::vector<Character>>& strings, const TrainingOptions& options) {
    m.vote_weight = static_cast<float>(options.vote_weight);
    m.character_votes.clear();
    if (!(options.vote_weight > 0)) return;
    const std::size_t K = m.character_count, L = m.label_names.size();
    std::map<std::string, std::size_t> label_index;
    for (std::size_t l = 0; l < L; ++l) label_index[m.label_names[l]] = l;
    std::vector<double> counts(L * K, 0.0), clips_of(L, 0.0);
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const std::vector<Character>& s = strings[i];
        if (s.empty()) continue;
        const std::size_t l = label_index.at(clips[i].label);
        for (const Character c : s) counts[l * K + c] += 1.0 / static_cast<double>(s.size());
        clips_of[l] += 1.0;
    }
    const double alpha = options.vote_smoothing;
    for (std::size_t l = 0; l < L; ++l)
        for (std::size_t c = 0; c < K; ++c) {
            const double p = (counts[l * K + c] + alpha) / (clips_of[l] + alpha * static_cast<double>(K));
            m.character_votes.push_back(static_cast<float>(std::max(std::log(p), static_cast<double>(min_log_weight))));
        }
}

// Stage 6c: log P(c | no action) from stretches that are no action (their
// strings, encoded once by train_model()), each counting as one as a clip does.
void set_no_action_votes(ModelData& m, const std::vector<EncodedClip>& stretches, const TrainingOptions& options,
                         TrainingReport& r) {
    m.has_no_action_votes = 0;
    m.no_action_votes.clear();
    if (!(options.vote_weight > 0)) return;
    const std::size_t K = m.character_count;
    std::vector<double> counts(K, 0.0);
    double used = 0;
    for (const EncodedClip& stretch : stretches) {
        const std::vector<Character>& s = stretch.string;
        if (s.empty()) continue;
        for (const Character c : s) counts[c] += 1.0 / static_cast<double>(s.size());
        used += 1.0;
    }
    r.no_action_stretches = static_cast<int>(used);
    if (used == 0) return;
    const double alpha = options.vote_smoothing;
    for (std::size_t c = 0; c < K; ++c) {
        const double p = (counts[c] + alpha) / (used + alpha * static_cast<double>(K));
        m.no_action_votes.push_back(static_cast<float>(std::max(std::log(p), static_cast<double>(min_log_weight))));
    }
    m.has_no_action_votes = 1;
}

// Stage 8: each label's rejection bound (train/rejection.hpp), from the
// training clips, synthetic negatives and the stretches of no action.
// With exemplars, the bounds see what clip classification sees: each
// character's exemplar distances (rejection.hpp's rows). A clip's rows come
// from centres fitted without its subject's clips, as its string is compared
// only with representatives made from other people's (with one subject in the
// list, from the model's own centres).
// `stretches[i]` is `(*no_action)[i]` encoded (with features when the model has exemplars).
void set_label_bounds(ModelData& m, const std::vector<LabelledClip>& clips, const std::vector<LabelId>& labels,
                      const std::vector<std::vector<Character>>& strings,
                      const std::vector<std::vector<float>>& string_features,
                      const std::vector<std::vector<float>>& string_records,
                      const std::vector<long>& own_representative, const std::vector<LabelledClip>* no_action,
                      const std::vector<EncodedClip>& stretches, const TrainingOptions& options, TrainingReport& r) {
    m.has_label_bounds = 0;
    m.label_bounds.clear();
    const ModelView view = m.view();
    std::vector<std::string> subjects;
    for (const LabelledClip& c : clips) subjects.push_back(c.subject);
    const bool exemplars = view.has_exemplars();
    std::vector<std::vector<Character>> stretch_strings;
    for (const EncodedClip& stretch : stretches) stretch_strings.push_back(stretch.string);
    ExemplarRows rows;
    if (exemplars) {
        // Per subject, centres that leave that subject's clips out (a model of
        // the exemplar tables alone: exemplar_distances() reads nothing else).
        std::map<std::string, ModelData> folds;
        const std::set<std::string> distinct(subjects.begin(), subjects.end());
        if (distinct.size() >= 2)
            for (const std::string& subject : distinct) {
                std::vector<std::vector<float>> features;
                std::vector<LabelId> fold_labels;
                for (std::size_t i = 0; i < clips.size(); ++i)
                    if (subjects[i] != subject)
                        features.push_back(string_features[i]), fold_labels.push_back(labels[i]);
                ModelData fold;
                fold.feature_dim = m.feature_dim;
                fold.label_names = m.label_names;
                set_exemplars(fold, features, fold_labels, static_cast<std::size_t>(options.exemplars),
                              static_cast<std::size_t>(options.exemplar_dims), options.exemplar_weight, options.seed);
                folds.emplace(subject, std::move(fold));
            }
        auto rows_of = [&](const std::vector<float>& features, const std::string& subject) {
            const auto fold = folds.find(subject);
            return exemplar_rows(fold != folds.end() ? fold->second.view() : view, features);
        };
        for (std::size_t i = 0; i < clips.size(); ++i) rows.strings.push_back(rows_of(string_features[i], subjects[i]));
        for (std::size_t i = 0; i < stretches.size(); ++i)
            rows.no_action.push_back(rows_of(stretches[i].features, (*no_action)[i].subject));
    }
    // With a clip descriptor, one fitted without the subjects a sample was made
    // from (one subject for a clip or a stretch, two for a spliced pair), each
    // fitted once, when first asked for.
    // Everything the callbacks below refer to lives until learn_label_bounds() returns.
    const bool described = view.has_descriptor() || view.has_directions();
    DescriptorSamples descriptor;
    std::map<std::set<std::string>, ModelData> descriptor_folds;
    const std::set<std::string> distinct(subjects.begin(), subjects.end());
    // The samples are descriptor_rows(): each character's feature, with motion directions then its record.
    auto penalties_without = [&](const std::vector<float>& sample, std::set<std::string> left) {
        if (distinct.size() < 2) return descriptor_row_penalties(view, sample);  // one subject: its own
        auto fold = descriptor_folds.find(left);
        if (fold == descriptor_folds.end()) {
            std::vector<std::vector<float>> kept, kept_records;
            std::vector<LabelId> kept_labels;
            for (std::size_t i = 0; i < clips.size(); ++i)
                if (left.count(subjects[i]) == 0)
                    kept.push_back(string_features[i]), kept_records.push_back(string_records[i]),
                        kept_labels.push_back(labels[i]);
            ModelData fitted;  // what the descriptors read: the features, the pose joints, the up axis
            fitted.feature_dim = m.feature_dim;
            fitted.label_names = m.label_names;
            fitted.pose_joints = m.pose_joints;
            fitted.up_axis = m.up_axis;
            if (kept.size() >= 2) {  // else none: no opinion
                if (view.has_descriptor())
                    set_descriptor(fitted, kept, kept_labels, static_cast<std::size_t>(options.descriptor_levels),
                                   static_cast<std::size_t>(options.descriptor_dims), options.descriptor_ridge,
                                   options.descriptor_weight);
                if (view.has_directions())
                    set_directions(fitted, kept_records, kept_labels,
                                   static_cast<std::size_t>(options.direction_levels), options.direction_ridge,
                                   options.direction_weight);
            }
            fold = descriptor_folds.emplace(std::move(left), std::move(fitted)).first;
        }
        return descriptor_row_penalties(fold->second.view(), sample);
    };
    if (described) {
        for (std::size_t i = 0; i < clips.size(); ++i)
            descriptor.strings.push_back(descriptor_rows(view, string_features[i], string_records[i]));
        for (const EncodedClip& stretch : stretches)
            descriptor.no_action.push_back(descriptor_rows(view, stretch.features, stretch.records));
        descriptor.width = descriptor_row_width(view);
        descriptor.of_strings = [&](const std::vector<float>& sample, std::size_t first, std::size_t second) {
            return penalties_without(sample, {subjects[first], subjects[second]});
        };
        descriptor.of_stretch = [&](const std::vector<float>& sample, std::size_t stretch) {
            return penalties_without(sample, {(*no_action)[stretch].subject});
        };
    }
    const std::vector<float> bounds = learn_label_bounds(
        view, strings, labels, subjects, own_representative, stretch_strings, options.reject_keep, options.seed,
        &r.label_bounds, exemplars ? &rows : nullptr, described ? &descriptor : nullptr);
    m.label_bounds = bounds;
    m.has_label_bounds = 1;
}

// Stage 7: the matching and labelling settings, in characters.
void set_matching(ModelData& m, const TrainingOptions& options, int representatives) {
    m.variant = options.variant;
    m.normalization = options.normalization;
    m.window_chars =
        static_cast<std::uint16_t>(std::max(1L, std::lround(options.window_seconds * options.string_rate_hz)));
    m.step_chars = static_cast<std::uint16_t>(std::max(1L, std::lround(options.step_seconds * options.string_rate_hz)));
    m.neighbours = static_cast<std::uint16_t>(std::min<int>(options.neighbours, representatives));
    m.unknown_distance =
        options.unknown_distance < 0 ? detail::infinity() : static_cast<float>(options.unknown_distance);
    const SegmenterConfig& online = options.online;
    m.settle_delay_us = static_cast<std::uint32_t>(online.settle_delay_us);
    m.settle_stable_us = static_cast<std::uint32_t>(online.settle_stable_us);
    m.segment_penalty = online.segment_penalty;
    m.stay_penalty = online.stay_penalty;
    m.skip_penalty = online.skip_penalty;
    m.unknown_cost = online.unknown_cost;
    m.segment_vote_weight = online.vote_weight;
    m.segment_exemplar_weight = online.exemplar_weight;
    m.segment_direction_weight = online.direction_weight;
    m.min_action_us = static_cast<std::uint32_t>(options.min_action_us);
    m.label_lead_us = static_cast<std::uint32_t>(options.label_lead_us);
    // The model stores representative indices in 16 bits (0xFFFF means "no action").
    if (representatives >= 0xFFFF)
        throw std::invalid_argument(std::to_string(representatives) +
                                    " representatives are more than a model holds (65534): raise --sigma");
}

}  // namespace

ModelData train_model(const std::vector<LabelledClip>& listed, const TrainingOptions& options, TrainingReport* report,
                      const std::vector<LabelledClip>* no_action) {
    check_options(options);
    TrainingReport local;
    TrainingReport& r = report != nullptr ? *report : local;
    r = TrainingReport{};
    // One skeleton for every clip: the pose joints asked for, or an engine rig's body joints.
    const bool select = !listed.empty() && (!options.pose_joints.empty() || !body_joints(listed.front().clip).empty());
    std::vector<LabelledClip> selected;
    if (select) {
        selected = listed;
        r.skeleton = select_pose_joints(selected, options.pose_joints);
    }
    const std::vector<LabelledClip>& given = select ? selected : listed;
    const std::vector<LabelledClip> mirrored = options.mirror ? with_mirrored(given) : std::vector<LabelledClip>{};
    const std::vector<LabelledClip>& clips = options.mirror ? mirrored : given;
    StageTimer stage(options, r);

    ModelData m = start_model(clips, options, r);

    stage.start("sampling and normalising poses");
    const std::vector<float> poses = sample_training_poses(m, clips, options, r);
    stage.finish("sample and normalise");

    stage.start("projecting (PCA)");
    const Eigen::MatrixXd samples = fit_projection(m, poses, options);
    stage.finish("PCA");

    TreeFeatures features;
    if (options.components == 0) {
        stage.start("building the cluster tree");
        features = projected_features(m, poses, samples);
    } else {
        stage.start("fitting the GMM by EM");
        fit_gmm_tables(m, samples, options, r);
        stage.finish("GMM (EM)");
        stage.start("building the cluster tree");
        features = posterior_features(m, poses);
    }
    build_characters(m, features, options, r);
    stage.finish("cluster tree");

    stage.start("encoding the training strings");
    m.string_period_us = static_cast<std::uint32_t>(std::lround(1e6 / options.string_rate_hz));
    const bool exemplars = options.exemplars > 0 && options.exemplar_weight > 0;
    const bool descriptor = options.descriptor_levels > 0 && options.descriptor_weight > 0;
    const bool directions = options.direction_levels > 0 && options.direction_weight > 0;
    const bool window = options.direction_window_s > 0;
    const bool records = directions || window;
    std::vector<std::vector<Character>> strings;
    std::vector<std::vector<float>> string_features;  // with exemplars or a descriptor: each character's feature
    std::vector<std::vector<float>> string_records;   // with motion directions: each character's pose and facing
    for (const LabelledClip& c : clips) {
        EncodedClip encoded = encode_clip(m.view(), c.clip, exemplars || descriptor || records, records);
        strings.push_back(std::move(encoded.string));
        string_features.push_back(std::move(encoded.features));
        string_records.push_back(std::move(encoded.records));
    }
    r.strings = static_cast<int>(strings.size());
    // The stretches of no action (a list of recordings), encoded once for the
    // votes, the exemplars and the bounds; their joints are read onto the model's.
    std::vector<EncodedClip> stretches;
    if (no_action != nullptr)
        for (const LabelledClip& stretch : *no_action) {
            Clip clip = stretch.clip;
            conform_to_model(m.view(), clip);
            stretches.push_back(encode_clip(m.view(), clip, exemplars || descriptor || records, records));
        }
    stage.finish("training strings");

    stage.start("agglomerating representatives");
    const std::vector<long> own_representative = choose_representatives(m, clips, strings, options, r);
    set_votes(m, clips, strings, options);
    if (!stretches.empty()) set_no_action_votes(m, stretches, options, r);
    stage.finish("representatives");

    std::vector<LabelId> labels;  // each clip's label
    for (const LabelledClip& c : clips)
        labels.push_back(static_cast<LabelId>(
            std::find(m.label_names.begin(), m.label_names.end(), c.label) - m.label_names.begin()));
    if (exemplars) {
        stage.start("clustering each label's exemplars");
        // The labels' features, then no action's (centres of their own) when asked.
        std::vector<std::vector<float>> labelled = string_features;
        std::vector<LabelId> feature_labels = labels;
        if (options.no_action_exemplars)
            for (const EncodedClip& stretch : stretches)
                labelled.push_back(stretch.features), feature_labels.push_back(unknown_label);
        set_exemplars(m, labelled, feature_labels, static_cast<std::size_t>(options.exemplars),
                      static_cast<std::size_t>(options.exemplar_dims), options.exemplar_weight, options.seed);
        stage.finish("exemplars");
    }
    if (descriptor) {
        stage.start("fitting the clip descriptor");
        set_descriptor(m, string_features, labels, static_cast<std::size_t>(options.descriptor_levels),
                       static_cast<std::size_t>(options.descriptor_dims), options.descriptor_ridge,
                       options.descriptor_weight);
        stage.finish("descriptor");
    }
    if (directions) {
        stage.start("fitting the motion directions");
        set_directions(m, string_records, labels, static_cast<std::size_t>(options.direction_levels),
                       options.direction_ridge, options.direction_weight);
        stage.finish("directions");
    }
    if (window) {
        stage.start("fitting the window's directions");
        const long chars = std::max(2L, std::lround(options.direction_window_s * options.string_rate_hz));
        set_window_directions(m, string_records, labels, static_cast<std::size_t>(chars),
                              options.direction_window_ridge);
        stage.finish("window directions");
    }

    set_matching(m, options, r.representatives);
    if (options.reject) {
        stage.start("learning each label's rejection bound");
        set_label_bounds(m, clips, labels, strings, string_features, string_records, own_representative, no_action,
                         stretches, options, r);
        stage.finish("rejection bounds");
    }
    return m;
}

}  // namespace host
}  // namespace actionstring
