// Labelling whole strings with the runtime's batch distance and kNN.
#include "run/classify.hpp"

#include <limits>

#include "run/encode.hpp"

namespace actionstring {
namespace host {

Classification classify_string(const ModelView& model, const std::vector<Character>& string,
                               const std::vector<std::size_t>& excluded) {
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
    return classify_distances(model, distances.data(), model.has_votes() ? penalties.data() : nullptr);
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
