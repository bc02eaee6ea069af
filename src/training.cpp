// The training pipeline (DESIGN §1): every per-frame computation goes through
// the runtime's own code on the float tables, so the strings and
// representatives are what the device will see.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <thread>

#include "actionstring/capacity.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/gmm.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/projection.hpp"
#include "actionstring/sampler.hpp"
#include "actionstring/string_distance.hpp"
#include "actionstring_host/clustering.hpp"
#include "actionstring_host/training.hpp"

namespace actionstring {
namespace host {
namespace {

using Clock = std::chrono::steady_clock;

std::int64_t to_us(double seconds) { return static_cast<std::int64_t>(std::llround(seconds * 1e6)); }

void check_options(const TrainingOptions& o) {
    auto require = [](bool ok, const char* what) {
        if (!ok) throw std::invalid_argument(what);
    };
    require(o.components >= 0 && o.components <= static_cast<int>(HostCapacity::max_components),
            "components (J) must be between 0 (no GMM) and 64");
    require(o.covariance_floor > 0, "the covariance floor must be positive");
    require(o.pca_dim >= 0, "the PCA dimension must be ≥ 0");
    require(o.feature_rate_hz > 0 && o.string_rate_hz > 0, "rates must be positive");
    require(o.epsilon > 0, "ε must be positive");
    require(o.sigma >= 0, "σ must be ≥ 0");
    require(o.neighbours >= 1, "k must be ≥ 1");
    require(o.window_seconds > 0 && o.step_seconds > 0, "window and step must be positive");
    require(o.em_max_iterations >= 1, "EM needs at least one iteration");
    require(o.em_restarts >= 1 && o.em_restarts <= 64, "EM restarts must be between 1 and 64");
    require(o.max_characters >= 1 && o.max_characters <= 4096, "the character limit must be between 1 and 4096");
}

// Per clip: the normalised poses nearest to each tick of a clock at `rate_hz`,
// picked with the runtime's own sampler.
void sample_poses(const ModelView& view, const Clip& clip, double rate_hz, std::vector<float>& poses, std::size_t& rejected) {
    StringSampler sampler;
    sampler.configure(static_cast<std::uint32_t>(std::lround(1e6 / rate_hz)), std::int64_t{1} << 62);
    const std::size_t D = view.pose_dim();
    std::vector<float> previous(D), current(D);
    bool has_previous = false;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (normalize_pose(view, clip.frame(f), current.data()) != Status::ok) {
            ++rejected;
            continue;
        }
        const SamplePlan plan = sampler.advance(to_us(clip.times[f]));
        if (plan.status == Status::time_went_backwards) continue;
        for (std::uint32_t i = 0; i < plan.from_previous && has_previous; ++i) poses.insert(poses.end(), previous.begin(), previous.end());
        for (std::uint32_t i = 0; i < plan.from_current; ++i) poses.insert(poses.end(), current.begin(), current.end());
        std::swap(previous, current);
        has_previous = true;
    }
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

std::vector<Character> clip_string(const ModelView& model, const Clip& clip) {
    auto encoder = std::make_unique<StringEncoder<HostCapacity>>();
    const Status status = encoder->init(model, std::int64_t{1} << 62);
    if (status != Status::ok) throw std::invalid_argument(std::string("model rejected by the encoder: ") + status_name(status));
    std::vector<Character> string;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const EncodedFrame e = encoder->push_frame(to_us(clip.times[f]), clip.frame(f));
        string.insert(string.end(), e.from_previous, e.previous);
        string.insert(string.end(), e.from_current, e.current);
    }
    return string;
}

ModelData train_model(const std::vector<LabelledClip>& clips, const TrainingOptions& options, TrainingReport* report) {
    check_options(options);
    TrainingReport local;
    TrainingReport& r = report != nullptr ? *report : local;
    r = TrainingReport{};
    if (clips.empty()) throw std::invalid_argument("no training clips");
    const Clip& first = clips.front().clip;
    for (const LabelledClip& c : clips) {
        if (c.clip.joint_names != first.joint_names)
            throw std::invalid_argument(c.clip.source + ": its joints differ from " + first.source + "'s; train on one skeleton");
        r.frames_read += c.clip.frame_count();
    }
    if (!first.roles.complete())
        throw std::invalid_argument(first.source + ": root and hip joints unknown; name them (--roles ROOT,LEFT_HIP,RIGHT_HIP)");

    ModelData m;
    m.joint_count = static_cast<std::uint16_t>(first.joint_count());
    m.root_joint = static_cast<std::uint16_t>(first.roles.root);
    m.left_hip_joint = static_cast<std::uint16_t>(first.roles.left_hip);
    m.right_hip_joint = static_cast<std::uint16_t>(first.roles.right_hip);
    m.up_axis = static_cast<std::uint8_t>(first.up_axis);
    for (std::size_t j = 0; j < first.joint_count(); ++j)
        if (static_cast<int>(j) != first.roles.root) m.pose_joints.push_back(static_cast<std::uint16_t>(j));
    const std::size_t D = 3 * m.pose_joints.size();
    if (m.pose_joints.size() > HostCapacity::max_pose_dim / 3)
        throw std::invalid_argument("the skeleton has " + std::to_string(m.pose_joints.size()) + " joints besides the root; at most " +
                                    std::to_string(HostCapacity::max_pose_dim / 3) + " are supported");
    m.scale_mode = options.scale_mode;
    if (options.scale_mode == ScaleMode::hip_width) {
        // The reference hip width: median over the first clip's frames.
        std::vector<double> widths;
        for (std::size_t f = 0; f < first.frame_count(); ++f) {
            const float* p = first.frame(f);
            const auto l = static_cast<std::size_t>(first.roles.left_hip) * 3, rr = static_cast<std::size_t>(first.roles.right_hip) * 3;
            widths.push_back(std::sqrt(std::pow(p[l] - p[rr], 2.0) + std::pow(p[l + 1] - p[rr + 1], 2.0) + std::pow(p[l + 2] - p[rr + 2], 2.0)));
        }
        std::nth_element(widths.begin(), widths.begin() + static_cast<long>(widths.size() / 2), widths.end());
        m.reference_scale = static_cast<float>(widths[widths.size() / 2]);
        if (!(m.reference_scale > 0)) throw std::invalid_argument("hip width is zero: cannot scale by it");
    }

    // 1. Poses at the feature rate.
    if (options.progress) options.progress("sampling and normalising poses");
    auto stage = Clock::now();
    std::vector<float> poses;
    for (const LabelledClip& c : clips) sample_poses(m.view(), c.clip, options.feature_rate_hz, poses, r.frames_rejected);
    const std::size_t n = poses.size() / D;
    r.feature_samples = n;
    r.frames_used = r.frames_read - r.frames_rejected;
    if (n == 0) throw std::invalid_argument("no usable frames: every frame was rejected by pose normalisation");
    r.stage_seconds.emplace_back("sample and normalise", seconds_since(stage));

    // 2. Optional PCA, applied with the runtime's projection.
    if (options.progress) options.progress("projecting (PCA)");
    stage = Clock::now();
    std::size_t d = D;
    if (options.pca_dim > 0) {
        Eigen::MatrixXd x(static_cast<Eigen::Index>(D), static_cast<Eigen::Index>(n));
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t k = 0; k < D; ++k) x(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = poses[i * D + k];
        Eigen::VectorXd mean;
        Eigen::MatrixXd axes;
        fit_pca(x, options.pca_dim, mean, axes);
        d = static_cast<std::size_t>(options.pca_dim);
        for (std::size_t k = 0; k < D; ++k) m.projection_mean.push_back(static_cast<float>(mean[static_cast<Eigen::Index>(k)]));
        for (std::size_t c = 0; c < D; ++c)
            for (std::size_t row = 0; row < d; ++row)
                m.projection_matrix.push_back(static_cast<float>(axes(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c))));
    }
    if (d > HostCapacity::max_feature_dim)
        throw std::invalid_argument("the pose has " + std::to_string(d) + " dimensions; at most " +
                                    std::to_string(HostCapacity::max_feature_dim) + " are supported (use --pca)");
    m.feature_dim = static_cast<std::uint16_t>(d);
    std::vector<float> feature(d);
    Eigen::MatrixXd samples(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(n));
    {
        const ModelView view = m.view();
        for (std::size_t i = 0; i < n; ++i) {
            project_pose(view, poses.data() + i * D, feature.data());
            for (std::size_t k = 0; k < d; ++k) samples(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = feature[k];
        }
    }
    r.stage_seconds.emplace_back("PCA", seconds_since(stage));

    // 3. GMM by EM (none with components = 0: the "PCA only" characters).
    std::size_t J = 0;  // the tree's dimension: components kept by EM, or d without a GMM
    std::vector<float> features;
    if (options.components == 0) {
        if (options.progress) options.progress("building the cluster tree");
        stage = Clock::now();
        if (!m.view().has_projection()) throw std::invalid_argument("components 0 (no GMM) needs a projection: set --pca");
        // Scale the projection so every training feature lies within L1 distance 1
        // of the projected mean pose: the tree's features then span an L1 diameter
        // of at most 2, as posteriors do, and ε, σ, W and the online penalties keep
        // the scale they have with a GMM.
        double largest = 0.0;
        for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, samples.col(static_cast<Eigen::Index>(i)).lpNorm<1>());
        if (!(largest > 0.0)) throw std::invalid_argument("every training pose projects to the same point");
        for (float& value : m.projection_matrix) value = static_cast<float>(static_cast<double>(value) / largest);
        features.resize(n * d);
        const ModelView view = m.view();
        for (std::size_t i = 0; i < n; ++i) project_pose(view, poses.data() + i * D, features.data() + i * d);
        J = d;
    } else {
        if (options.progress) options.progress("fitting the GMM by EM");
        stage = Clock::now();
        // Restarts run in parallel; each is independent and the choice is fixed
        // (highest final objective, earliest on ties), so threads change nothing.
        std::vector<GmmFit> fits(static_cast<std::size_t>(options.em_restarts));
        std::vector<std::exception_ptr> failures(fits.size());
        const std::size_t workers = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
        for (std::size_t batch = 0; batch < fits.size(); batch += workers) {
            std::vector<std::thread> threads;
            for (std::size_t k = batch; k < std::min(fits.size(), batch + workers); ++k)
                threads.emplace_back([&, k] {
                    try {
                        fits[k] = fit_gmm(samples, options.components, options.covariance, options.covariance_floor,
                                          options.em_max_iterations, options.em_tolerance, options.seed + static_cast<std::uint32_t>(k));
                    } catch (...) {
                        failures[k] = std::current_exception();
                    }
                });
            for (std::thread& t : threads) t.join();
        }
        for (const auto& failure : failures)
            if (failure) std::rethrow_exception(failure);
        std::size_t chosen = 0;
        for (std::size_t k = 0; k < fits.size(); ++k) {
            r.em_restart_objectives.push_back(fits[k].report.objective.back());
            if (fits[k].report.objective.back() > fits[chosen].report.objective.back()) chosen = k;
        }
        r.em_restart_chosen = static_cast<int>(chosen);
        const GmmFit& fit = fits[chosen];
        set_gmm(m, fit.means, fit.covariances, fit.weights, options.covariance);
        r.em = fit.report;
        r.stage_seconds.emplace_back("GMM (EM)", seconds_since(stage));

        // 4. Posterior features through the runtime, then the ε tree.
        if (options.progress) options.progress("building the cluster tree");
        stage = Clock::now();
        J = fit.means.size();
        features.resize(n * J);
        {
            const ModelView view = m.view();
            for (std::size_t i = 0; i < n; ++i) {
                project_pose(view, poses.data() + i * D, feature.data());
                if (gmm_posterior<HostCapacity::max_feature_dim>(view, feature.data(), features.data() + i * J) != Status::ok)
                    throw std::runtime_error("a training pose fell outside the GMM's float range");
            }
        }
    }
    const ClusterTree tree = build_cluster_tree(features, J, options.epsilon, options.max_characters, options.seed);
    m.node_centroids = tree.centroids;
    m.node_children = tree.children;
    m.node_characters = tree.characters;
    m.character_count = static_cast<std::uint16_t>(tree.character_count);
    set_character_distances_from_leaves(m);
    r.characters = tree.character_count;
    r.stage_seconds.emplace_back("cluster tree", seconds_since(stage));

    // 5. Strings of the training clips through the runtime's encoder.
    if (options.progress) options.progress("encoding the training strings");
    stage = Clock::now();
    m.string_period_us = static_cast<std::uint32_t>(std::lround(1e6 / options.string_rate_hz));
    std::vector<std::vector<Character>> strings;
    for (const LabelledClip& c : clips) strings.push_back(clip_string(m.view(), c.clip));
    r.strings = static_cast<int>(strings.size());
    r.stage_seconds.emplace_back("training strings", seconds_since(stage));

    // 6. Representatives: agglomerate with the runtime's string distance.
    if (options.progress) options.progress("agglomerating representatives");
    stage = Clock::now();
    std::set<std::string> label_set;
    for (const LabelledClip& c : clips) label_set.insert(c.label);
    m.label_names.assign(label_set.begin(), label_set.end());
    std::map<std::string, LabelId> label_index;
    for (std::size_t l = 0; l < m.label_names.size(); ++l) label_index[m.label_names[l]] = static_cast<LabelId>(l);
    const ModelView view = m.view();
    const CharacterWeights weights = character_weights(view);
    const MatchOptions match{options.variant, options.normalization};
    std::vector<std::vector<double>> distance(strings.size(), std::vector<double>(strings.size(), 0.0));
    std::vector<detail::Cell> workspace;
    auto measure = [&](const std::vector<Character>& a, const std::vector<Character>& b) {
        if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
        workspace.resize(string_distance_cells(a.size(), b.size()));
        float value = 0;
        if (string_distance(a.data(), a.size(), b.data(), b.size(), weights, match, workspace.data(), &value) != Status::ok)
            throw std::invalid_argument("a training string is too long to compare");
        return static_cast<double>(value);
    };
    for (std::size_t a = 0; a < strings.size(); ++a)
        for (std::size_t b = a + 1; b < strings.size(); ++b)
            distance[a][b] = distance[b][a] = 0.5 * (measure(strings[a], strings[b]) + measure(strings[b], strings[a]));
    const auto clusters = agglomerate(distance, options.sigma);
    r.representatives_per_label.assign(m.label_names.size(), 0);
    for (const auto& cluster : clusters) {
        if (cluster.size() < 2 && !options.keep_singletons) continue;
        std::vector<int> votes(m.label_names.size(), 0);
        for (std::size_t member : cluster) ++votes[label_index[clips[member].label]];
        const auto label = static_cast<LabelId>(std::max_element(votes.begin(), votes.end()) - votes.begin());
        if (strings[cluster.front()].empty()) continue;
        m.add_representative(strings[cluster.front()], label);
        ++r.representatives_per_label[label];
    }
    r.representatives = static_cast<int>(m.representative_labels.size());
    if (r.representatives == 0)
        throw std::invalid_argument("σ = " + std::to_string(options.sigma) +
                                    " merges no two training strings, so there is no representative: raise --sigma or use --keep-singletons");
    r.stage_seconds.emplace_back("representatives", seconds_since(stage));

    m.variant = options.variant;
    m.normalization = options.normalization;
    m.window_chars = static_cast<std::uint16_t>(std::max(1L, std::lround(options.window_seconds * options.string_rate_hz)));
    m.step_chars = static_cast<std::uint16_t>(std::max(1L, std::lround(options.step_seconds * options.string_rate_hz)));
    m.neighbours = static_cast<std::uint16_t>(std::min<int>(options.neighbours, r.representatives));
    m.unknown_distance = options.unknown_distance < 0 ? detail::infinity() : static_cast<float>(options.unknown_distance);
    if (!HostCapacity::fits(m.view()))
        throw std::invalid_argument(std::to_string(r.representatives) + " representatives of " +
                                    std::to_string(m.view().total_representative_chars()) +
                                    " characters in all exceed what the host tools can run (" +
                                    std::to_string(HostCapacity::max_representatives) + " and " +
                                    std::to_string(HostCapacity::max_representative_chars) +
                                    "): raise --sigma, or lower --string-rate");
    return m;
}

}  // namespace host
}  // namespace actionstring

namespace actionstring {
namespace host {

Classification classify_string(const ModelView& model, const std::vector<Character>& string) {
    const std::size_t R = model.representative_count;
    std::vector<float> distances(R, detail::infinity());
    if (!string.empty()) {
        std::vector<detail::Cell> workspace;
        for (std::size_t r = 0; r < R; ++r) {
            const Character* rep = model.representative_chars + model.representative_offsets[r];
            const std::size_t length = model.representative_length(r);
            workspace.resize(string_distance_cells(string.size(), length));
            string_distance(string.data(), string.size(), rep, length, character_weights(model),
                            MatchOptions{model.variant, model.normalization}, workspace.data(), &distances[r]);
        }
    }
    return classify_distances<4096>(model, distances.data());
}

double clip_accuracy(const ModelView& model, const std::vector<LabelledClip>& clips) {
    if (clips.empty()) return 0.0;
    std::size_t right = 0;
    for (const LabelledClip& c : clips) {
        const Classification result = classify_string(model, clip_string(model, c.clip));
        right += result.label != unknown_label && c.label == model.label_names[result.label];
    }
    return static_cast<double>(right) / static_cast<double>(clips.size());
}

}  // namespace host
}  // namespace actionstring
