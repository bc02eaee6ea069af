// actionstring — the clip descriptor: a clip's features summarised over time,
// scored by a linear classifier, beside the strings (design.md §1.8).
//
// The strings compare key-poses in order and the exemplars compare poses one
// at a time; neither sees how the whole clip's poses vary together, or how
// that changes from its beginning to its end. The descriptor does: the clip
// (its characters' features, the projected poses and velocities the strings
// were made from) is cut into 1, 2, … descriptor_levels equal parts (a
// temporal pyramid), and each part is summarised by its mean and its
// covariance (as the covariance descriptors of skeleton action recognition
// do). A linear classifier, fitted at training by ridge regression on the
// training clips' descriptors (src/train/descriptor.*), scores every label;
// each label's shortfall from the best score, times descriptor_weight, is
// added to its representatives' distances beside the votes and the
// exemplars. A clip's parts depend on its length, so the descriptor labels a
// whole clip (clip classification), not a running stream.
//
// Work per clip: descriptor_size() floats of summary, computed in one pass per
// part, then label_count × descriptor_size() multiply-adds. Every sum has one
// fixed order, so a generated header, a loaded model, a host and a Cortex-M4
// give the same bits, and the trainer, which calls clip_descriptor() itself,
// fits the classifier on exactly what the runtime computes.
#pragma once

#include <cstddef>

#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {

/// Parts of a pyramid of `levels` levels: 1 + 2 + … + levels.
constexpr std::size_t descriptor_parts(std::size_t levels) noexcept { return levels * (levels + 1u) / 2u; }

/// Floats of one part's summary over K coordinates: the mean, then the
/// covariance's upper triangle.
constexpr std::size_t descriptor_part_size(std::size_t dims) noexcept { return dims + dims * (dims + 1u) / 2u; }

/// The first character of part `part` of level `level` (0-based, part <
/// level) of a clip of `n` characters, and the one past its last: the
/// clip cut in `level` parts as equal as whole characters allow,
/// [part · n / level, (part + 1) · n / level), and never empty when n > 0 (a
/// clip shorter than its level repeats characters across parts).
constexpr std::size_t descriptor_part_begin(std::size_t n, std::size_t level, std::size_t part) noexcept {
    return part * n / level;
}
constexpr std::size_t descriptor_part_end(std::size_t n, std::size_t level, std::size_t part) noexcept {
    const std::size_t begin = descriptor_part_begin(n, level, part), end = (part + 1u) * n / level;
    return end > begin || n == 0 ? end : begin + 1u;  // begin < n whenever n > 0, as part < level
}

/// The clip descriptor of `n` features (each `stride` floats apart; its
/// first `dims` coordinates are read): for level v = 1 … `levels` and part
/// i = 0 … v − 1 in that order, the part's mean (sum in character order,
/// divided by its length), then its covariance's upper triangle row by row,
/// entry (j, k ≥ j) the sum in character order of (x_j − mean_j)(x_k − mean_k)
/// divided by the length. All zeros when n is 0.
/// @param features n × stride floats; read only during the call
/// @param out      receives descriptor_parts(levels) × descriptor_part_size(dims) floats (caller-owned)
inline void clip_descriptor(const float* features, std::size_t n, std::size_t stride, std::size_t dims,
                            std::size_t levels, float* out) noexcept {
    if (out == nullptr) return;
    const std::size_t part_size = descriptor_part_size(dims);
    for (std::size_t level = 1; level <= levels; ++level)
        for (std::size_t part = 0; part < level; ++part, out += part_size) {
            for (std::size_t k = 0; k < part_size; ++k) out[k] = 0.0f;
            if (n == 0 || features == nullptr) continue;
            const std::size_t begin = descriptor_part_begin(n, level, part), end = descriptor_part_end(n, level, part);
            const float count = static_cast<float>(end - begin);
            float* const mean = out;
            for (std::size_t t = begin; t < end; ++t)
                for (std::size_t j = 0; j < dims; ++j) mean[j] += features[t * stride + j];
            for (std::size_t j = 0; j < dims; ++j) mean[j] /= count;
            float* covariance = out + dims;
            for (std::size_t t = begin; t < end; ++t) {
                const float* x = features + t * stride;
                float* entry = covariance;
                for (std::size_t j = 0; j < dims; ++j) {
                    const float dj = x[j] - mean[j];
                    for (std::size_t k = j; k < dims; ++k) *entry++ += dj * (x[k] - mean[k]);
                }
            }
            for (std::size_t k = 0; k < dims * (dims + 1u) / 2u; ++k) covariance[k] /= count;
        }
}

/// Per label, the linear classifier's score of a descriptor (descriptor_size()
/// floats): descriptor_bias[l] + Σ_p descriptor_weights[l · P + p] · descriptor[p],
/// summed in p order. label_count floats; nothing without a descriptor.
/// @param descriptor read only during the call
/// @param scores     receives label_count floats (caller-owned)
inline void descriptor_scores(const ModelView& model, const float* descriptor, float* scores) noexcept {
    if (scores == nullptr || descriptor == nullptr || model.descriptor_levels == 0 ||
        model.descriptor_weights == nullptr || model.descriptor_bias == nullptr)
        return;
    const std::size_t P = model.descriptor_size();
    for (std::size_t l = 0; l < model.label_count; ++l) {
        const float* w = model.descriptor_weights + l * P;
        float sum = model.descriptor_bias[l];
        for (std::size_t p = 0; p < P; ++p) sum += w[p] * descriptor[p];
        scores[l] = sum;
    }
}

/// What the clip descriptor adds to the distance of each label's
/// representatives, from a clip's `n` features (feature_dim floats each, the
/// characters' features, EncodedFrame's previous_feature / current_feature):
///   descriptor_weight · (max over labels of score − score(label)),
/// so ≥ 0, and 0 for the label the classifier scores highest. All 0 without
/// a descriptor or characters, or when a score is not finite (no opinion).
/// @param features  n × feature_dim floats; read only during the call
/// @param scratch   descriptor_size() floats (caller-owned), overwritten
/// @param penalties receives label_count floats (caller-owned)
inline void descriptor_penalties(const ModelView& model, const float* features, std::size_t n, float* scratch,
                                 float* penalties) noexcept {
    if (penalties == nullptr) return;
    const std::size_t L = model.label_count;
    for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
    if (!model.has_descriptor() || features == nullptr || n == 0 || scratch == nullptr) return;
    clip_descriptor(features, n, model.feature_dim, model.descriptor_dims(), model.descriptor_levels, scratch);
    descriptor_scores(model, scratch, penalties);
    float best = -detail::infinity();
    bool finite = true;
    for (std::size_t l = 0; l < L; ++l) {
        finite = finite && detail::is_finite(penalties[l]);
        if (penalties[l] > best) best = penalties[l];
    }
    for (std::size_t l = 0; l < L; ++l) penalties[l] = finite ? model.descriptor_weight * (best - penalties[l]) : 0.0f;
}

}  // namespace actionstring
