// actionstring — stage 4: descent of the cluster tree to a character (design.md §1.4).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "actionstring/detail/lanes.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {

/// Squared Euclidean distances between a pose feature and two node centroids
/// (a node's children), the metric of the 2-means split that built them.
///
/// Each sum is taken in four parts, part k adding the terms of j ≡ k (mod 4) in
/// increasing j, and ends as (part 0 + part 1) + (part 2 + part 3). That order is
/// the definition, the same on every target: with SSE the parts are the four
/// lanes of one register, on a Cortex-M4 four registers. One chain of additions
/// per sum would wait an add's latency per term (40 terms at J = 40, at every
/// level of the tree); four chains, and the two children's sums side by side,
/// keep the pipeline full.
inline void node_distances_sq(const ModelView& model, std::size_t first, std::size_t second, const float* feature,
                              float& to_first, float& to_second) noexcept {
    const std::size_t dim = model.tree_dim();
    const float* a = model.node_centroids + first * dim;
    const float* b = model.node_centroids + second * dim;
    std::size_t j = 0;
#if ACTIONSTRING_DETAIL_LANES == 4
    detail::Lanes sa = detail::broadcast(0.0f), sb = detail::broadcast(0.0f);
    for (; j + 4 <= dim; j += 4) {
        const detail::Lanes f = detail::load_lanes(feature + j);
        const detail::Lanes da = f - detail::load_lanes(a + j), db = f - detail::load_lanes(b + j);
        sa = sa + da * da;
        sb = sb + db * db;
    }
    if (j == dim) {
        // Both sums' last additions in the registers: lanes (a0 + a1, a2 + a3,
        // b0 + b1, b2 + b3), then each pair added, the same additions as below.
        const __m128 pairs = _mm_add_ps(_mm_shuffle_ps(sa.v, sb.v, _MM_SHUFFLE(2, 0, 2, 0)),
                                        _mm_shuffle_ps(sa.v, sb.v, _MM_SHUFFLE(3, 1, 3, 1)));
        const __m128 sums = _mm_add_ps(pairs, _mm_shuffle_ps(pairs, pairs, _MM_SHUFFLE(2, 3, 0, 1)));
        to_first = _mm_cvtss_f32(sums);
        to_second = _mm_cvtss_f32(_mm_movehl_ps(sums, sums));
        return;
    }
    float pa[4], pb[4];
    detail::store_lanes(pa, sa);
    detail::store_lanes(pb, sb);
    for (std::size_t k = 0; j < dim; ++j, ++k) {  // the last dim mod 4 terms, into parts 0, 1, 2
        const float da = feature[j] - a[j], db = feature[j] - b[j];
        pa[k] += da * da;
        pb[k] += db * db;
    }
    to_first = (pa[0] + pa[1]) + (pa[2] + pa[3]);
    to_second = (pb[0] + pb[1]) + (pb[2] + pb[3]);
#else
    // Eight accumulators in registers (a Cortex-M4 has 32 single-precision ones).
    float a0 = 0.0f, a1 = 0.0f, a2 = 0.0f, a3 = 0.0f, b0 = 0.0f, b1 = 0.0f, b2 = 0.0f, b3 = 0.0f;
    auto term = [feature, a, b](std::size_t i, float& part_a, float& part_b) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
        const float da = feature[i] - a[i], db = feature[i] - b[i];
        part_a += da * da;
        part_b += db * db;
    };
    for (; j + 4 <= dim; j += 4) {
        term(j, a0, b0);
        term(j + 1, a1, b1);
        term(j + 2, a2, b2);
        term(j + 3, a3, b3);
    }
    if (j < dim) term(j, a0, b0);  // the last dim mod 4 terms, into parts 0, 1, 2
    if (j + 1 < dim) term(j + 1, a1, b1);
    if (j + 2 < dim) term(j + 2, a2, b2);
    to_first = (a0 + a1) + (a2 + a3);
    to_second = (b0 + b1) + (b2 + b3);
#endif
}

/// Descends from the root to a leaf, at each internal node moving to the child
/// whose centroid is nearer (the left child on a tie), and returns the leaf's
/// character. Children always have larger indices than their parent
/// (validate_model checks it), so the loop ends within node_count steps.
/// @param feature tree_dim() floats (a posterior, or the projected pose of a
///                model without a GMM); read only during the call
inline Character descend_tree(const ModelView& model, const float* feature) noexcept {
    std::size_t node = 0;
    for (;;) {
        const int left = model.node_children[2 * node];
        const int right = model.node_children[2 * node + 1];
        if (left < 0) return model.node_characters[node];
        float to_left = 0.0f, to_right = 0.0f;
        node_distances_sq(model, static_cast<std::size_t>(left), static_cast<std::size_t>(right), feature, to_left,
                          to_right);
        node = static_cast<std::size_t>(to_right < to_left ? right : left);
    }
}

/// Floats tree_node_norms() writes: one per node.
constexpr std::size_t tree_norm_floats(const ModelView& model) noexcept { return model.node_count; }

/// Each node centroid's squared norm, for descend_tree_sparse(): the squares of
/// its coordinates added in increasing order. Exactness does not depend on
/// this order (the descent's error bound covers any).
/// @param norms receives tree_norm_floats(model) floats (caller-owned)
inline void tree_node_norms(const ModelView& model, float* norms) noexcept {
    const std::size_t dim = model.tree_dim();
    for (std::size_t n = 0; n < model.node_count; ++n) {
        const float* c = model.node_centroids + n * dim;
        float sum = 0.0f;
        for (std::size_t j = 0; j < dim; ++j) sum += c[j] * c[j];
        norms[n] = sum;
    }
}

/// descend_tree() for a feature with few non-zero coordinates (a GMM posterior:
/// at J = 40 on HDM05, 5 of 40 on average), with the same result, bit for bit.
///
/// ‖t − b‖² − ‖t − a‖² = ‖b‖² − ‖a‖² − 2 Σ t_j (b_j − a_j), and the sum needs only
/// the j where t_j ≠ 0. descend_tree() compares the two distances as computed in
/// float (node_distances_sq(): each within (dim/4 + 5)·u of its exact value,
/// relatively, u = 2⁻²⁴, all terms being ≥ 0). So when this difference, computed
/// here in float with its own rounding bounded the same way, lies further from 0
/// than γ·B — B bounding both distances (‖a‖² + ‖b‖² + 2‖t‖² + 2 Σ |t_j|(|a_j| + |b_j|)),
/// γ = 16 (dim + 8) u, several times what the two computations' errors need, plus
/// 10⁻³⁰ for flushed subnormals — both computations see the same sign and no tie,
/// and the sparse one decides. Otherwise (near a tie, or a NaN) the node falls
/// back to node_distances_sq(). On HDM05's val.tsv at J = 20, 40 and 80 no node
/// falls back, and a descent costs 0.67, 0.50 and 0.28 of descend_tree()'s time.
/// A feature with more than half of its coordinates non-zero goes to
/// descend_tree() at once.
/// @param feature  tree_dim() floats; read only during the call
/// @param norms    tree_node_norms() of this model (node_count floats)
/// @param nonzero  scratch of tree_dim() entries (caller-owned)
inline Character descend_tree_sparse(const ModelView& model, const float* feature, const float* norms,
                                     std::uint16_t* nonzero) noexcept {
    const std::size_t dim = model.tree_dim();
    std::size_t count = 0;
    float feature_norm = 0.0f;
    for (std::size_t j = 0; j < dim; ++j) {
        if (feature[j] != 0.0f) {
            nonzero[count++] = static_cast<std::uint16_t>(j);
            feature_norm += feature[j] * feature[j];
        }
    }
    if (2 * count > dim) return descend_tree(model, feature);
    const float gamma = 16.0f * static_cast<float>(dim + 8) * 5.9604645e-8f;  // 16 (dim + 8) · 2⁻²⁴
    std::size_t node = 0;
    for (;;) {
        const int left = model.node_children[2 * node];
        const int right = model.node_children[2 * node + 1];
        if (left < 0) return model.node_characters[node];
        const float* a = model.node_centroids + static_cast<std::size_t>(left) * dim;
        const float* b = model.node_centroids + static_cast<std::size_t>(right) * dim;
        float dot = 0.0f, spread = 0.0f;
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t j = nonzero[k];
            const float t = feature[j];
            dot += t * (b[j] - a[j]);
            spread += std::fabs(t) * (std::fabs(a[j]) + std::fabs(b[j]));
        }
        const float difference = (norms[right] - norms[left]) - 2.0f * dot;  // ≈ ‖t − b‖² − ‖t − a‖²
        const float bound =
            gamma * (((norms[left] + norms[right]) + 2.0f * feature_norm) + 2.0f * spread) + 1.0e-30f;
        if (difference > bound) {
            node = static_cast<std::size_t>(left);
        } else if (difference < -bound) {
            node = static_cast<std::size_t>(right);
        } else {
            float to_left = 0.0f, to_right = 0.0f;
            node_distances_sq(model, static_cast<std::size_t>(left), static_cast<std::size_t>(right), feature, to_left,
                              to_right);
            node = static_cast<std::size_t>(to_right < to_left ? right : left);
        }
    }
}

}  // namespace actionstring
