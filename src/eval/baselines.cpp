// Baselines computed by the same tool on the same split.
#include "eval/baselines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "actionstring/projection.hpp"
#include "actionstring/tree.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/stream_labels.hpp"
#include "train/clustering.hpp"

namespace actionstring {
namespace host {
namespace {

// DTW between two pose sequences (D floats a pose), Euclidean frame distance,
// whole-to-whole boundaries; gives up (infinity) once every path costs more than `cutoff`.
double pose_dtw(const std::vector<float>& a_poses, const std::vector<float>& b_poses, std::size_t D, double cutoff) {
    const std::size_t a_size = a_poses.size() / D, b_size = b_poses.size() / D;
    if (a_size == 0 || b_size == 0) return std::numeric_limits<double>::infinity();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> previous(b_size + 1, inf), current(b_size + 1, inf);
    previous[0] = 0;
    for (std::size_t i = 1; i <= a_size; ++i) {
        current[0] = inf;
        double row_best = inf;
        for (std::size_t j = 1; j <= b_size; ++j) {
            double sum = 0;
            const float* p = a_poses.data() + (i - 1) * D;
            const float* q = b_poses.data() + (j - 1) * D;
            for (std::size_t k = 0; k < D; ++k) {
                const double d = static_cast<double>(p[k]) - static_cast<double>(q[k]);
                sum += d * d;
            }
            current[j] = std::sqrt(sum) + std::min({previous[j - 1], previous[j], current[j - 1]});
            row_best = std::min(row_best, current[j]);
        }
        if (row_best > cutoff) return inf;  // every path already costs more than the best match so far
        std::swap(previous, current);
    }
    return previous[b_size];
}

// 1-NN over reference strings: each query's prediction is its nearest training clip's label.
void predict_nearest(ClipResults& r, const std::vector<std::vector<Character>>& queries,
                     const std::vector<std::vector<Character>>& references, const std::vector<LabelledClip>& train,
                     const CharacterWeights& weights, const ModelView& model) {
    std::vector<detail::Cell> workspace;
    const MatchOptions options{model.variant, model.normalization};
    for (const std::vector<Character>& query : queries) {
        const long nearest = nearest_string(query, references, weights, options, workspace);
        r.predictions.push_back(nearest < 0 ? unknown_frame
                                            : label_index(r.labels, train[static_cast<std::size_t>(nearest)].label));
    }
}

}  // namespace

ClipResults evaluate_all_strings(const ModelView& model, const std::vector<LabelledClip>& train,
                                 const std::vector<LabelledClip>& clips) {
    ClipResults r = start_results("1-NN over all training strings", model, clips);
    std::vector<std::vector<Character>> references;
    for (const LabelledClip& t : train) references.push_back(clip_string(model, t.clip));
    std::vector<std::vector<Character>> queries;
    for (const LabelledClip& c : clips) queries.push_back(clip_string(model, c.clip));
    predict_nearest(r, queries, references, train, character_weights(model), model);
    summarise(r, clips);
    return r;
}

ClipResults evaluate_pca_characters(const ModelView& model, const std::vector<LabelledClip>& train,
                                    const std::vector<LabelledClip>& clips, std::uint32_t seed) {
    ClipResults r = start_results("1-NN, PCA-only characters (no GMM)", model, clips);
    const std::size_t d = model.feature_dim;
    const double rate_hz = 1e6 / static_cast<double>(model.string_period_us);
    // Features: the runtime's normalisation and projection at the string rate.
    auto features_of = [&](const Clip& clip) {
        std::vector<float> poses;
        sample_poses(model, clip, rate_hz, poses);
        const std::size_t D = model.input_dim();
        std::vector<float> out(poses.size() / D * d);
        for (std::size_t i = 0; i < poses.size() / D; ++i)
            project_pose(model, poses.data() + i * D, out.data() + i * d);
        return out;
    };
    std::vector<std::vector<float>> train_features;
    std::vector<float> pooled;
    for (const LabelledClip& t : train) {
        train_features.push_back(features_of(t.clip));
        pooled.insert(pooled.end(), train_features.back().begin(), train_features.back().end());
    }
    if (pooled.empty()) throw std::invalid_argument("PCA-only baseline: no usable training frames");
    // The same top-down 2-means tree with as many leaves as the model has
    // characters, built on projected poses instead of GMM posteriors; ε is
    // tiny so the leaf count, not the diameter, ends the splitting.
    const ClusterTree tree = build_cluster_tree(pooled, d, 1e-9, model.character_count, seed);
    const std::size_t K = static_cast<std::size_t>(tree.character_count);
    std::vector<const float*> leaf(K, nullptr);
    for (std::size_t n = 0; n < tree.characters.size(); ++n)
        if (tree.children[2 * n] < 0) leaf[tree.characters[n]] = &tree.centroids[n * d];
    std::vector<float> distances(K * K, 0.0f);
    for (std::size_t a = 0; a < K; ++a)
        for (std::size_t b = 0; b < K; ++b) {
            double sum = 0;
            for (std::size_t k = 0; k < d; ++k) sum += std::pow(double(leaf[a][k]) - double(leaf[b][k]), 2.0);
            distances[a * K + b] = static_cast<float>(std::sqrt(sum));
        }
    // The runtime's descent over this tree: a view whose "components" are the projected coordinates.
    ModelView pca_view = model;
    pca_view.component_count = static_cast<std::uint16_t>(d);
    pca_view.node_count = static_cast<std::uint16_t>(tree.characters.size());
    pca_view.node_centroids = tree.centroids.data();
    pca_view.node_children = tree.children.data();
    pca_view.node_characters = tree.characters.data();
    const CharacterWeights weights{distances.data(), K};
    auto string_of = [&](const std::vector<float>& features) {
        std::vector<Character> string;
        for (std::size_t i = 0; i + d <= features.size(); i += d)
            string.push_back(descend_tree(pca_view, features.data() + i));
        return string;
    };
    std::vector<std::vector<Character>> references;
    for (const auto& f : train_features) references.push_back(string_of(f));
    std::vector<std::vector<Character>> queries;
    for (const LabelledClip& c : clips) queries.push_back(string_of(features_of(c.clip)));
    predict_nearest(r, queries, references, train, weights, model);
    summarise(r, clips);
    return r;
}

ClipResults evaluate_pose_dtw(const ModelView& model, const std::vector<LabelledClip>& train,
                              const std::vector<LabelledClip>& clips, double rate_hz) {
    ClipResults r = start_results("DTW 1-NN on normalised poses", model, clips);
    const std::size_t D = model.input_dim();
    auto poses_of = [&](const Clip& clip) {
        std::vector<float> poses;
        sample_poses(model, clip, rate_hz, poses);
        return poses;
    };
    std::vector<std::vector<float>> references;
    for (const LabelledClip& t : train) references.push_back(poses_of(t.clip));
    for (const LabelledClip& c : clips) {
        const std::vector<float> query = poses_of(c.clip);
        double best = std::numeric_limits<double>::infinity();
        int label = unknown_frame;
        for (std::size_t t = 0; t < train.size(); ++t) {
            const double d = pose_dtw(query, references[t], D, best);
            if (d < best) best = d, label = label_index(r.labels, train[t].label);
        }
        r.predictions.push_back(label);
    }
    summarise(r, clips);
    return r;
}

}  // namespace host
}  // namespace actionstring
