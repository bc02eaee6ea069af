// Labelling whole strings with the runtime's batch distance and kNN.
#include "run/classify.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "actionstring/clip.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/exemplars.hpp"
#include "run/encode.hpp"

namespace actionstring {
namespace host {

Classification classify_string(const ModelView& model, const std::vector<Character>& string,
                               const std::vector<std::size_t>& excluded, const float* exemplar_sums,
                               const float* descriptor) {
    // The runtime's stages (clip.hpp), with training's exclusions between them.
    std::vector<float> distances(model.representative_count);
    std::vector<detail::Cell> cells(clip_cells(model, string.size()));
    representative_distances(model, string.data(), string.size(), cells.data(), distances.data());
    // classify_distances() passes over NaN distances.
    for (const std::size_t r : excluded)
        if (r < distances.size()) distances[r] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> row(model.label_count), penalties(model.label_count);
    const bool any =
        clip_penalties(model, string.data(), string.size(), exemplar_sums, descriptor, row.data(), penalties.data());
    return classify_distances(model, distances.data(), any ? penalties.data() : nullptr);
}

std::vector<float> clip_descriptor_penalties(const ModelView& model, const std::vector<float>& features,
                                             const std::vector<float>& records) {
    std::vector<float> penalties(model.label_count, 0.0f);
    if (model.feature_dim == 0) return penalties;
    const std::size_t n = features.size() / model.feature_dim;
    if (model.has_directions() && records.size() != n * model.direction_record_floats())
        throw std::logic_error("clip_descriptor_penalties: the motion directions need every character's record");
    std::vector<float> scratch(std::max(model.descriptor_size(), model.direction_size())), row(model.label_count);
    clip_summary_penalties(model, features.data(), records.empty() ? nullptr : records.data(), n, scratch.data(),
                           row.data(), penalties.data());
    return penalties;
}

std::size_t descriptor_row_width(const ModelView& model) {
    return model.feature_dim + (model.has_directions() ? model.direction_record_floats() : 0u);
}

std::vector<float> descriptor_rows(const ModelView& model, const std::vector<float>& features,
                                   const std::vector<float>& records) {
    const std::size_t d = model.feature_dim, width = descriptor_row_width(model), extra = width - d;
    const std::size_t n = d == 0 ? 0 : features.size() / d;
    if (extra != 0 && records.size() != n * extra)
        throw std::logic_error("descriptor_rows: the motion directions need every character's record");
    std::vector<float> rows;
    rows.reserve(n * width);
    for (std::size_t t = 0; t < n; ++t) {
        rows.insert(rows.end(), features.begin() + static_cast<std::ptrdiff_t>(t * d),
                    features.begin() + static_cast<std::ptrdiff_t>((t + 1) * d));
        rows.insert(rows.end(), records.begin() + static_cast<std::ptrdiff_t>(t * extra),
                    records.begin() + static_cast<std::ptrdiff_t>((t + 1) * extra));
    }
    return rows;
}

std::vector<float> descriptor_row_penalties(const ModelView& model, const std::vector<float>& rows) {
    const std::size_t d = model.feature_dim, width = descriptor_row_width(model);
    if (width == 0) return std::vector<float>(model.label_count, 0.0f);
    std::vector<float> features, records;
    for (std::size_t at = 0; at + width <= rows.size(); at += width) {
        features.insert(features.end(), rows.begin() + static_cast<std::ptrdiff_t>(at),
                        rows.begin() + static_cast<std::ptrdiff_t>(at + d));
        records.insert(records.end(), rows.begin() + static_cast<std::ptrdiff_t>(at + d),
                       rows.begin() + static_cast<std::ptrdiff_t>(at + width));
    }
    return clip_descriptor_penalties(model, features, records);
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
    std::vector<float> sums(model.label_count, 0.0f), row(model.label_count);
    if (model.feature_dim == 0) return sums;
    actionstring::exemplar_sums(model, features.data(), features.size() / model.feature_dim, row.data(), sums.data());
    return sums;
}

namespace {

// A clip encoded as the model reads it, with the runtime's scratch and cells
// for its whole-clip stages (classify_clip(), clip_label_distances()).
struct ClipWork {
    EncodedClip encoded;
    std::vector<float> scratch;
    std::vector<detail::Cell> cells;
    ClipWork(const ModelView& model, const Clip& clip)
        : encoded(encode_clip(model, clip, model.has_exemplars() || model.has_descriptor(), model.has_directions())),
          scratch(clip_scratch_floats(model)),
          cells(clip_cells(model, encoded.string.size())) {}
    const float* features() const { return encoded.features.empty() ? nullptr : encoded.features.data(); }
    const float* records() const { return encoded.records.empty() ? nullptr : encoded.records.data(); }
};

}  // namespace

Classification classify_clip(const ModelView& model, const Clip& clip) {
    ClipWork work(model, clip);
    return actionstring::classify_clip(model, work.encoded.string.data(), work.features(), work.records(),
                                       work.encoded.string.size(), work.scratch.data(), work.cells.data());
}

ScoredClip score_clip(const ModelView& model, const Clip& clip) {
    // One encoding and one pass of the stages for both (classify_clip() and
    // clip_label_distances() would each redo the string distances).
    ClipWork work(model, clip);
    const float* const penalties =
        detail::clip_scores(model, work.encoded.string.data(), work.features(), work.records(),
                            work.encoded.string.size(), work.scratch.data(), work.cells.data());
    ScoredClip out;
    out.classification = classify_distances(model, work.scratch.data(), penalties);
    out.label_distances.resize(model.label_count);
    actionstring::label_distances(model, work.scratch.data(), penalties, out.label_distances.data());
    return out;
}

std::vector<float> label_distances(const ModelView& model, const Clip& clip) {
    return score_clip(model, clip).label_distances;
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
