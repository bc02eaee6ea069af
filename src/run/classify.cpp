// Labelling whole strings with the runtime's batch distance and kNN.
#include "run/classify.hpp"

#include <limits>

#include "actionstring/descriptor.hpp"
#include "actionstring/exemplars.hpp"
#include "run/encode.hpp"

namespace actionstring {
namespace host {

Classification classify_string(const ModelView& model, const std::vector<Character>& string,
                               const std::vector<std::size_t>& excluded, const float* exemplar_sums,
                               const float* descriptor) {
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
    // classify_distances() passes over NaN distances.
    for (const std::size_t r : excluded)
        if (r < R) distances[r] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> penalties(model.label_count, 0.0f);
    vote_penalties(model, string.data(), string.size(), penalties.data());
    const bool exemplars = model.has_exemplars() && exemplar_sums != nullptr;
    if (exemplars) {
        std::vector<float> more(model.label_count, 0.0f);
        exemplar_penalties(model, exemplar_sums, string.size(), more.data());
        for (std::size_t l = 0; l < penalties.size(); ++l) penalties[l] += more[l];
    }
    const bool described = model.has_descriptor() && descriptor != nullptr;
    if (described)
        for (std::size_t l = 0; l < penalties.size(); ++l) penalties[l] += descriptor[l];
    return classify_distances(model, distances.data(),
                              model.has_votes() || exemplars || described ? penalties.data() : nullptr);
}

std::vector<float> clip_descriptor_penalties(const ModelView& model, const std::vector<float>& features) {
    std::vector<float> penalties(model.label_count, 0.0f);
    if (!model.has_descriptor() || model.feature_dim == 0) return penalties;
    std::vector<float> scratch(model.descriptor_size());
    descriptor_penalties(model, features.data(), features.size() / model.feature_dim, scratch.data(), penalties.data());
    return penalties;
}

std::vector<float> exemplar_rows(const ModelView& model, const std::vector<float>& features) {
    const std::size_t L = model.label_count, d = model.feature_dim;
    std::vector<float> rows;
    if (!model.has_exemplars() || d == 0) return rows;
    rows.reserve(features.size() / d * L);
    std::vector<float> distances(L);
    for (std::size_t at = 0; at + d <= features.size(); at += d) {
        exemplar_distances(model, &features[at], distances.data());
        rows.insert(rows.end(), distances.begin(), distances.end());
    }
    return rows;
}

std::vector<float> sum_exemplar_rows(const std::vector<float>& rows, std::size_t label_count) {
    std::vector<float> sums(label_count, 0.0f);
    if (label_count == 0) return sums;
    for (std::size_t at = 0; at + label_count <= rows.size(); at += label_count)
        for (std::size_t l = 0; l < label_count; ++l) sums[l] += rows[at + l];
    return sums;
}

std::vector<float> exemplar_sums(const ModelView& model, const std::vector<float>& features) {
    return sum_exemplar_rows(exemplar_rows(model, features), model.label_count);
}

Classification classify_clip(const ModelView& model, const Clip& clip) {
    const EncodedClip encoded = encode_clip(model, clip, model.has_exemplars() || model.has_descriptor());
    const std::vector<float> sums = exemplar_sums(model, encoded.features);
    const std::vector<float> described = clip_descriptor_penalties(model, encoded.features);
    return classify_string(model, encoded.string, {}, sums.data(), described.data());
}

ClipScore clip_score(const ModelView& model, const std::vector<LabelledClip>& clips) {
    ClipScore score;
    if (clips.empty()) return score;
    std::size_t right = 0;
    double margin = 0;
    for (const LabelledClip& c : clips) {
        const Classification result = classify_clip(model, c.clip);
        const bool correct = result.label != unknown_label && c.label == model.label_names[result.label];
        right += correct;
        margin += correct ? result.confidence : -static_cast<double>(result.confidence);
    }
    score.accuracy = static_cast<double>(right) / static_cast<double>(clips.size());
    score.margin = margin / static_cast<double>(clips.size());
    return score;
}

double clip_accuracy(const ModelView& model, const std::vector<LabelledClip>& clips) {
    return clip_score(model, clips).accuracy;
}

long nearest_string(const std::vector<Character>& query, const std::vector<std::vector<Character>>& references,
                    const CharacterWeights& weights, const MatchOptions& options,
                    std::vector<detail::Cell>& workspace) {
    float best = detail::infinity();
    long nearest = -1;
    if (query.empty()) return nearest;
    for (std::size_t t = 0; t < references.size(); ++t) {
        const std::vector<Character>& reference = references[t];
        if (reference.empty()) continue;
        workspace.resize(string_distance_cells(query.size(), reference.size()));
        float distance = 0;
        if (string_distance(query.data(), query.size(), reference.data(), reference.size(), weights, options,
                            workspace.data(), &distance) != Status::ok)
            continue;
        if (distance < best) best = distance, nearest = static_cast<long>(t);
    }
    return nearest;
}

}  // namespace host
}  // namespace actionstring
