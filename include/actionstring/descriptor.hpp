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
//
// Beside it, the clip's motion directions (below): which way each pose joint
// steps, part by part, scored by a second linear classifier.
#pragma once

#include <cmath>
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

namespace detail {

/// Per label l < `labels`, bias[l] + Σ_p weights[l · P + p] · x[p], summed in p order.
inline void linear_scores(const float* weights, const float* bias, const float* x, std::size_t P, std::size_t labels,
                          float* scores) noexcept {
    for (std::size_t l = 0; l < labels; ++l) {
        const float* w = weights + l * P;
        float sum = bias[l];
        for (std::size_t p = 0; p < P; ++p) sum += w[p] * x[p];
        scores[l] = sum;
    }
}

/// Scores turned in place into what they add to each label's distance:
/// weight · (best score − score), so ≥ 0 and 0 for the best; all 0 when any
/// score is not finite (no opinion).
inline void shortfall_penalties(float weight, std::size_t labels, float* scores) noexcept {
    float best = -infinity();
    bool finite = true;
    for (std::size_t l = 0; l < labels; ++l) {
        finite = finite && is_finite(scores[l]);
        if (scores[l] > best) best = scores[l];
    }
    for (std::size_t l = 0; l < labels; ++l) scores[l] = finite ? weight * (best - scores[l]) : 0.0f;
}

}  // namespace detail

/// Per label, the linear classifier's score of a descriptor (descriptor_size()
/// floats): descriptor_bias[l] + Σ_p descriptor_weights[l · P + p] · descriptor[p],
/// summed in p order. label_count floats; nothing without a descriptor.
/// @param descriptor read only during the call
/// @param scores     receives label_count floats (caller-owned)
inline void descriptor_scores(const ModelView& model, const float* descriptor, float* scores) noexcept {
    if (scores == nullptr || descriptor == nullptr || model.descriptor_levels == 0 ||
        model.descriptor_weights == nullptr || model.descriptor_bias == nullptr)
        return;
    detail::linear_scores(model.descriptor_weights, model.descriptor_bias, descriptor, model.descriptor_size(),
                          model.label_count, scores);
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
    detail::shortfall_penalties(model.descriptor_weight, L, penalties);
}

// ---- The clip's motion directions ------------------------------------------
//
// The descriptor's covariances see which coordinates move together, not which
// way: a motion and its reverse share them. The direction histograms see that
// (as the histograms of oriented displacements of skeleton action
// recognition): per part of a temporal pyramid, for each pose joint and each
// coordinate plane, how far the joint stepped in each of eight directions. A
// second linear classifier scores them beside the descriptor's.
//
// The pose each frame gives has its facing taken out (normalize_pose()); the
// facing's frame-to-frame jitter would turn every joint a little each step.
// So each pose is turned back to the facing of the clip's first character
// (its record keeps the turn that was taken out): the clip keeps one frame,
// whichever way it was performed, and a stream knows it from the start.

/// The sector of a step (u, v) in its plane: 0 … 7 for the angles [0°, 45°),
/// [45°, 90°), … counter-clockwise from +u, decided by comparisons alone (no
/// trigonometry), so every platform bins alike. (0, 0), which adds nothing
/// (its length is 0), falls in sector 3.
constexpr std::size_t direction_sector(float u, float v) noexcept {
    return v < 0.0f ? 4u + direction_sector(-u, -v) : (u > 0.0f ? (v < u ? 0u : 1u) : (v > -u ? 2u : 3u));
}

/// The direction histograms of a clip of `n` records (each
/// direction_record_floats(): 3 × `joints` pose coordinates, x y z per
/// joint, then the facing turn {cos, sin} taken out of that pose): for level
/// v = 1 … `levels` and part i = 0 … v − 1 (the parts of clip_descriptor()),
/// for each joint and each plane (xy, yz, xz, in that order), every step of
/// the part (record t − 1 → t for its t ≥ 1), both poses turned about
/// `up_axis` to the facing of record 0, adds its length in the plane to its
/// direction's sector (direction_sector()); every histogram is then divided
/// by its sum (left 0 when the joint does not move there). Sums in order.
/// All zeros when n < 2.
/// @param records n × (3 × joints + 2) floats; read only during the call
/// @param out     receives descriptor_parts(levels) × joints × 3 × 8 floats (caller-owned)
inline void clip_directions(const float* records, std::size_t n, std::size_t joints, std::size_t up_axis,
                            std::size_t levels, float* out) noexcept {
    if (out == nullptr) return;
    constexpr std::size_t bins = ModelView::direction_bins;
    constexpr std::size_t planes[3][2] = {{0, 1}, {1, 2}, {0, 2}};
    const std::size_t stride = 3u * joints + 2u, part_size = joints * 3u * bins;
    const std::size_t h1 = (up_axis + 1u) % 3u, h2 = (up_axis + 2u) % 3u;
    // Record t as it faced at record 0: the turn taken out of it
    // (normalize_pose() turned by −θ_t) put back, then record 0's taken out,
    // one turn by θ_t − θ_0, {cos, sin}; the same for each of its joints.
    struct Turn {
        const float* pose;
        float c, s;
    };
    auto turn_of = [&](std::size_t t) {
        const float* record = records + t * stride;
        const float* facing = record + 3u * joints;
        const float* first = records + 3u * joints;  // record 0's facing
        return Turn{record, facing[0] * first[0] + facing[1] * first[1], facing[1] * first[0] - facing[0] * first[1]};
    };
    auto turned = [&](const Turn& turn, std::size_t j, float* v) {
        const float* p = turn.pose + 3u * j;
        v[up_axis] = p[up_axis];
        v[h1] = turn.c * p[h1] - turn.s * p[h2];
        v[h2] = turn.s * p[h1] + turn.c * p[h2];
    };
    for (std::size_t level = 1; level <= levels; ++level)
        for (std::size_t part = 0; part < level; ++part, out += part_size) {
            for (std::size_t k = 0; k < part_size; ++k) out[k] = 0.0f;
            if (n < 2 || records == nullptr || up_axis > 2) continue;
            const std::size_t begin = descriptor_part_begin(n, level, part), end = descriptor_part_end(n, level, part);
            for (std::size_t t = begin > 0 ? begin : 1u; t < end; ++t) {
                const Turn at = turn_of(t), last = turn_of(t - 1u);
                float* histogram = out;
                for (std::size_t j = 0; j < joints; ++j) {
                    float now[3], before[3];
                    turned(at, j, now);
                    turned(last, j, before);
                    for (const auto& plane : planes) {
                        const float u = now[plane[0]] - before[plane[0]], v = now[plane[1]] - before[plane[1]];
                        histogram[direction_sector(u, v)] += std::sqrt(u * u + v * v);
                        histogram += bins;
                    }
                }
            }
            for (float* histogram = out; histogram < out + part_size; histogram += bins) {
                float sum = 0.0f;
                for (std::size_t b = 0; b < bins; ++b) sum += histogram[b];
                if (sum > 0.0f)
                    for (std::size_t b = 0; b < bins; ++b) histogram[b] /= sum;
            }
        }
}

/// What the motion directions add to the distance of each label's
/// representatives, from a clip's `n` records (direction_record_floats()
/// each: EncodedFrame's previous_pose / current_pose, its first pose_dim()
/// floats, then previous_facing / current_facing):
///   direction_weight · (max over labels of score − score(label)),
/// score(l) = direction_bias[l] + Σ_p direction_weights[l · P + p] · h[p] over
/// the clip's clip_directions() h, summed in p order. ≥ 0, and 0 for the label
/// scored highest. All 0 without directions or records, or when a score is
/// not finite (no opinion).
/// @param records   n × direction_record_floats() floats; read only during the call
/// @param scratch   direction_size() floats (caller-owned), overwritten
/// @param penalties receives label_count floats (caller-owned)
inline void direction_penalties(const ModelView& model, const float* records, std::size_t n, float* scratch,
                                float* penalties) noexcept {
    if (penalties == nullptr) return;
    const std::size_t L = model.label_count;
    for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
    if (!model.has_directions() || records == nullptr || n == 0 || scratch == nullptr) return;
    clip_directions(records, n, model.pose_joint_count, model.up_axis, model.direction_levels, scratch);
    detail::linear_scores(model.direction_weights, model.direction_bias, scratch, model.direction_size(), L, penalties);
    detail::shortfall_penalties(model.direction_weight, L, penalties);
}

/// What the motion directions of a stream's last characters add to the cost
/// of each label's explanations in the segmenter (segmenter.hpp): the
/// histograms of clip_directions() over one level of the `n` records (the
/// newest at most window_direction_chars, oldest first, turned to the facing
/// of the oldest), scored per label by the window's own classifier,
/// score(l) = window_direction_bias[l] + Σ_p window_direction_weights[l · P + p] · h[p]
/// summed in p order, then weight · (max over labels of score − score(l)).
/// ≥ 0, and 0 for the label scored highest. All 0 without window directions,
/// with fewer than two records (no step yet), or when a score is not finite.
/// The directions see which way the joints move, which the exemplars' poses
/// and the characters do not: a push and a pull pass through the same poses.
/// @param records   n × direction_record_floats() floats; read only during the call
/// @param scratch   window_direction_size() floats (caller-owned), overwritten
/// @param penalties receives label_count floats (caller-owned)
inline void window_direction_penalties(const ModelView& model, const float* records, std::size_t n, float weight,
                                       float* scratch, float* penalties) noexcept {
    if (penalties == nullptr) return;
    const std::size_t L = model.label_count;
    for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
    if (!model.has_window_directions() || records == nullptr || n < 2 || scratch == nullptr) return;
    clip_directions(records, n, model.pose_joint_count, model.up_axis, 1, scratch);
    detail::linear_scores(model.window_direction_weights, model.window_direction_bias, scratch,
                          model.window_direction_size(), L, penalties);
    detail::shortfall_penalties(weight, L, penalties);
}

/// What the clip's two summaries add together to each label's distance:
/// descriptor_penalties() of `features`, then direction_penalties() of
/// `records` added, each only when the model has it and its input is given
/// (what classify_clip() adds beside the votes and the exemplars). Returns
/// whether either applied; `penalties` is all 0 when neither did.
/// @param features  n × feature_dim floats, or null; read only during the call
/// @param records   n × direction_record_floats() floats, or null; read only during the call
/// @param scratch   max(descriptor_size(), direction_size()) floats (caller-owned), overwritten
/// @param row       label_count floats of scratch (caller-owned), overwritten
/// @param penalties receives label_count floats (caller-owned)
inline bool clip_summary_penalties(const ModelView& model, const float* features, const float* records, std::size_t n,
                                   float* scratch, float* row, float* penalties) noexcept {
    if (penalties == nullptr) return false;
    const bool described = model.has_descriptor() && features != nullptr;
    const bool directed = model.has_directions() && records != nullptr && row != nullptr;
    for (std::size_t l = 0; l < model.label_count; ++l) penalties[l] = 0.0f;
    if (described) descriptor_penalties(model, features, n, scratch, penalties);
    if (directed) {
        direction_penalties(model, records, n, scratch, row);
        for (std::size_t l = 0; l < model.label_count; ++l) penalties[l] += row[l];
    }
    return described || directed;
}

}  // namespace actionstring
