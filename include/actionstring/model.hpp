// actionstring — the model view: every table the runtime reads.
//
// A generated header fills a `constexpr ModelView` whose pointers refer to
// `constexpr` arrays; host tools fill one that points into a loaded artifact.
// Both drive the same per-frame code, so they agree bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/detail/math.hpp"
#include "actionstring/model_schema.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// One symbol of an action string: the index of a leaf of the cluster tree.
using Character = std::uint16_t;
/// Index into the model's label names.
using LabelId = std::uint16_t;
/// Returned instead of a label when no representative is close enough.
constexpr LabelId unknown_label = 0xFFFF;

/// Shape of each GMM component's covariance.
enum class Covariance : std::uint8_t { full = 0, diagonal = 1 };

/// Boundary conditions of the string distance (design.md §1.6).
enum class MatchVariant : std::uint8_t {
    /// Qi et al. eqs. 6–7 as printed: row 0 is 0, column 0 holds W[A1(i)][A2(1)].
    paper = 0,
    /// Classic DTW: D[0][0] = 0, the rest of row 0 and column 0 infinite.
    whole = 1,
    /// The shorter string matches anywhere inside the longer one:
    /// row 0 free, column 0 infinite, minimum over the last row.
    subsequence = 2,
};

/// What the accumulated string distance is divided by.
enum class LengthNormalization : std::uint8_t {
    none = 0,
    /// Number of cells on the optimal warping path.
    path = 1,
    /// Length of the query (the first argument; the window when streaming).
    query = 2,
};

/// Optional size normalisation of the pose vector.
enum class ScaleMode : std::uint8_t {
    none = 0,
    /// Divide by the 3-D hip width and multiply by `reference_scale`, so poses
    /// of actors of different size map to the same units.
    hip_width = 1,
    /// Rebuild the skeleton with the model's reference bone lengths: every
    /// bone keeps its direction and takes the training mean length, walking
    /// the kinematic tree from its roots, so a child and an adult doing the
    /// same thing give the same pose.
    bone_lengths = 2,
    /// Scale the whole pose by one factor per frame: the training mean length
    /// of the torso's bones (the hips', the spine's up to the chest, and the
    /// chest's children: neck and shoulders) over this frame's. Only the
    /// body's size is taken out; its proportions and every limb stay as
    /// tracked. Depth sensors track the torso well and the limbs poorly (an
    /// occluded or foreshortened leg rebuilt at full length moves the foot far
    /// from where it was), so on Kinect data this holds up where
    /// bone_lengths does not (models/README.md, "Size on UTKinect").
    /// bone_lengths holds the torso bones' reference lengths, 0 for the others.
    torso = 3,
};

/// Most joints a model scaled by bone lengths may have (its validation is
/// quadratic in them); larger rigs train on a body subset.
constexpr std::size_t max_bone_joints = 256;

/// Whether a model's scale mode rebuilds the skeleton bone by bone (and so
/// needs a scratch skeleton, normalize_pose()).
constexpr bool uses_bones(ScaleMode mode) noexcept { return mode == ScaleMode::bone_lengths; }

/// Whether a model's scale mode needs its kinematic tree (joint_parents,
/// bone_order, bone_lengths).
constexpr bool uses_kinematic_tree(ScaleMode mode) noexcept {
    return mode == ScaleMode::bone_lengths || mode == ScaleMode::torso;
}

/// Names (of joints, of labels) packed end to end, each NUL-terminated: name
/// i starts at text + offsets[i], and a table of n names has n + 1 offsets
/// (the last is the packed length). One form for a generated header's
/// constexpr arrays, a host model and a binary model read in place. Not owned.
struct NameTable {
    const char* text = nullptr;
    const std::uint32_t* offsets = nullptr;

    constexpr const char* operator[](std::size_t i) const noexcept { return text + offsets[i]; }
    constexpr bool present() const noexcept { return text != nullptr && offsets != nullptr; }
};

/// Non-owning view of a trained model. All pointers refer to storage that must
/// outlive every state object initialised from this view (a generated header's
/// `constexpr` arrays live forever; a host artifact must outlive its users).
///
/// Its fields are those of ACTIONSTRING_MODEL_FIELDS (model_schema.hpp), in
/// that order: scalars by value, each table as a pointer (null when absent)
/// with its element count where the schema names one.
struct ModelView {
#define ACTIONSTRING_VIEW_SCALAR(T, FIELD, INITIAL, LOW, HIGH) T FIELD = INITIAL;
#define ACTIONSTRING_VIEW_COUNT(T, FIELD, TABLE) T FIELD = 0;
#define ACTIONSTRING_VIEW_TABLE(T, FIELD, SIZE, LOW, HIGH) const T* FIELD = nullptr;
#define ACTIONSTRING_VIEW_NAMES(FIELD, COUNT) NameTable FIELD;
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_VIEW_SCALAR, ACTIONSTRING_VIEW_COUNT, ACTIONSTRING_VIEW_TABLE,
                              ACTIONSTRING_VIEW_NAMES)
#undef ACTIONSTRING_VIEW_SCALAR
#undef ACTIONSTRING_VIEW_COUNT
#undef ACTIONSTRING_VIEW_TABLE
#undef ACTIONSTRING_VIEW_NAMES

    /// D, the length of the normalised pose vector.
    constexpr std::size_t pose_dim() const noexcept { return 3u * pose_joint_count; }
    /// Whether the pose's velocity is part of the input (motion.hpp).
    constexpr bool has_velocity() const noexcept { return velocity_weight > 0.0f; }
    /// Whether the change of that velocity across the span is (motion.hpp).
    constexpr bool has_acceleration() const noexcept { return acceleration_weight > 0.0f; }
    /// Whether the input holds any motion, so the motion ring is needed.
    constexpr bool has_motion() const noexcept { return has_velocity() || has_acceleration(); }
    /// Length of what the projection reads: the pose (D), then with velocity
    /// its weighted velocity (D more), then with acceleration its weighted
    /// acceleration (D more).
    constexpr std::size_t input_dim() const noexcept {
        return pose_dim() * (1u + (has_velocity() ? 1u : 0u) + (has_acceleration() ? 1u : 0u));
    }
    constexpr bool has_projection() const noexcept { return projection_matrix != nullptr; }
    constexpr bool has_gmm() const noexcept { return component_count > 0; }
    /// Whether clip classification adds the characters' label votes to DTW.
    constexpr bool has_votes() const noexcept { return vote_weight > 0.0f && character_votes != nullptr; }
    /// Whether clip classification adds the exemplars' penalties (exemplars.hpp).
    constexpr bool has_exemplars() const noexcept {
        return exemplar_weight > 0.0f && exemplar_count > 0 && exemplars != nullptr;
    }
    /// Coordinates of each exemplar centre: the feature's first
    /// exemplar_dim (a PCA feature's leading ones hold most of its variance,
    /// so a model can trade distance work for accuracy), or all of them.
    constexpr std::size_t exemplar_dims() const noexcept {
        return exemplar_dim == 0 ? std::size_t{feature_dim} : std::size_t{exemplar_dim};
    }
    /// Whether clip classification adds the clip descriptor's penalties (descriptor.hpp).
    constexpr bool has_descriptor() const noexcept {
        return descriptor_weight > 0.0f && descriptor_levels > 0 && descriptor_weights != nullptr &&
               descriptor_bias != nullptr;
    }
    /// Coordinates of the feature the clip descriptor reads: its first
    /// descriptor_dim, or all of them.
    constexpr std::size_t descriptor_dims() const noexcept {
        return descriptor_dim == 0 ? std::size_t{feature_dim} : std::size_t{descriptor_dim};
    }
    /// Floats of one clip descriptor: per part of every level (1 + 2 + … +
    /// descriptor_levels parts), the part's mean (K) and its covariance's upper
    /// triangle (K (K + 1) / 2), K = descriptor_dims(); 0 without levels.
    constexpr std::size_t descriptor_size() const noexcept {
        return std::size_t{descriptor_levels} * (descriptor_levels + 1u) / 2u *
               (descriptor_dims() + descriptor_dims() * (descriptor_dims() + 1u) / 2u);
    }
    /// Whether clip classification adds the motion directions' penalties (descriptor.hpp).
    constexpr bool has_directions() const noexcept {
        return direction_weight > 0.0f && direction_levels > 0 && direction_weights != nullptr &&
               direction_bias != nullptr;
    }
    /// Sectors of a step direction's histogram (descriptor.hpp): 45° each.
    static constexpr std::size_t direction_bins = 8;
    /// Floats per character the motion directions read (clip_directions()):
    /// its normalised pose (pose_dim()), then the facing turn taken out of it ({cos, sin}).
    constexpr std::size_t direction_record_floats() const noexcept { return pose_dim() + 2u; }
    /// Floats of one clip's direction histograms: per part of every level (1 +
    /// 2 + … + direction_levels parts), per pose joint, per coordinate plane
    /// (xy, yz, xz), direction_bins sectors; 0 without levels.
    constexpr std::size_t direction_size() const noexcept {
        return std::size_t{direction_levels} * (direction_levels + 1u) / 2u * pose_joint_count * 3u * direction_bins;
    }
    /// Floats of one window's direction histograms (window_direction_penalties()): per
    /// pose joint, per coordinate plane, direction_bins sectors; 0 without a window.
    constexpr std::size_t window_direction_size() const noexcept {
        return window_direction_chars > 0 ? std::size_t{pose_joint_count} * 3u * direction_bins : 0u;
    }
    /// Whether the model can score the directions of a stream's last
    /// window_direction_chars characters (the segmenter's evidence beside the exemplars).
    constexpr bool has_window_directions() const noexcept {
        return window_direction_chars > 1 && pose_joint_count > 0 && window_direction_weights != nullptr &&
               window_direction_bias != nullptr;
    }
    /// Whether the exemplars include centres of "no action" (labelled
    /// unknown_label, after every label's): the segmenter then weighs "no
    /// action" by its exemplars too. Learned from the unlabelled stretches of
    /// training recordings.
    constexpr bool has_no_action_exemplars() const noexcept {
        return exemplar_count > 0 && exemplar_labels != nullptr && exemplar_labels[exemplar_count - 1] == unknown_label;
    }
    /// Length of the vectors the tree is built on and descends with: the GMM
    /// posterior (J), or without a GMM the projected pose (d).
    constexpr std::size_t tree_dim() const noexcept { return has_gmm() ? component_count : feature_dim; }
    /// Floats per component in gmm_factors.
    constexpr std::size_t factor_size() const noexcept {
        return covariance == Covariance::full ? static_cast<std::size_t>(feature_dim) * (feature_dim + 1u) / 2u
                                              : feature_dim;
    }
    /// Components are evaluated four at a time (gmm.hpp), so gmm_factors keeps
    /// each block of four components interleaved: element k of component j is
    /// at first · factor_size() + k · lanes + (j − first), where first = j − j mod 4
    /// and lanes = min(4, J − first) (the last block may hold fewer). One
    /// component's elements keep their order (U column by column, or the
    /// diagonal); a block's four are side by side, so one vector load reads
    /// an element of each.
    constexpr std::size_t gmm_factor_index(std::size_t component, std::size_t element) const noexcept {
        const std::size_t first = component - component % gmm_block;
        return first * factor_size() + element * gmm_block_lanes(first) + (component - first);
    }
    /// Components in the block that starts at component `first` (a multiple of gmm_block).
    constexpr std::size_t gmm_block_lanes(std::size_t first) const noexcept {
        return component_count - first < gmm_block ? component_count - first : gmm_block;
    }
    /// Components per block of gmm_factors.
    static constexpr std::size_t gmm_block = 4;
    constexpr std::uint32_t representative_length(std::size_t r) const noexcept {
        return representative_offsets[r + 1] - representative_offsets[r];
    }
    constexpr std::uint32_t total_representative_chars() const noexcept {
        return representative_count == 0 || representative_offsets == nullptr
                   ? 0u
                   : representative_offsets[representative_count];
    }
    /// Whether W[a][b] == W[b][a] for every pair (every trained model's W is;
    /// the segmenter then reads W by row, and training measures a pair of
    /// equal-length strings in one direction).
    constexpr bool character_distances_symmetric() const noexcept {
        const std::size_t K = character_count;
        for (std::size_t a = 0; a < K; ++a)
            for (std::size_t b = a + 1; b < K; ++b)
                if (!(character_distances[a * K + b] == character_distances[b * K + a])) return false;
        return true;
    }
    /// Windows that can be open at once: ceil(window / step).
    constexpr std::uint32_t max_open_windows() const noexcept {
        return step_chars == 0 ? 0u : (window_chars + step_chars - 1u) / step_chars;
    }
};

/// Weights W[a][b] between characters: K × K floats, row-major, not owned.
struct CharacterWeights {
    const float* values = nullptr;
    std::size_t character_count = 0;
    float operator()(Character a, Character b) const noexcept {
        return values[static_cast<std::size_t>(a) * character_count + b];
    }
};

/// The model's W as CharacterWeights.
constexpr CharacterWeights character_weights(const ModelView& m) noexcept {
    return CharacterWeights{m.character_distances, m.character_count};
}

/// Most neighbours of the kNN vote (its scratch is on the stack and its work quadratic in k).
constexpr std::size_t max_neighbours = 64;

/// Most feature coordinates the clip descriptor reads (descriptor.hpp): its
/// covariances take K (K + 1) / 2 floats a part, so 64 is already 2,080.
constexpr std::size_t max_descriptor_dims = 64;

/// Smallest string period a model may have (a 1 kHz string rate; the paper's is 12 Hz).
constexpr std::uint32_t min_string_period_us = 1000;
/// Largest string period (a 1 Hz string rate): the default restart gap (1 s)
/// then always spans a period, so a model's own settings always work.
constexpr std::uint32_t max_string_period_us = 1000000;
/// Largest magnitude of any value in the projection, GMM means and factors,
/// tree centroids and W: far above anything training produces, low enough
/// that sums over a model's dimensions stay far inside float range.
constexpr float max_table_value = 1.0e6f;
/// Longest settle delay a segmenter accepts (10 minutes); also the bound of
/// the model's early settling, shortest action and label lead.
constexpr std::int64_t max_settle_delay_us = 600000000;
/// Largest weight of a term added to a distance or a cost (the velocity, the
/// votes, exemplars, descriptor and directions, offline and online). One bound
/// for the model's validation and the segmenter's settings check, so a model
/// that validates always starts with its own settings.
constexpr float max_weight = 1000.0f;
/// Bounds of the GMM's log-normalisers and log-weights: a log-weight is the
/// log of a probability (≤ 0), and neither may be so large that one
/// component wins whatever the pose.
constexpr float max_log_normalizer = 1.0e4f;
constexpr float min_log_weight = -1.0e4f;

namespace detail {

inline bool all_finite(const float* values, std::size_t count) noexcept {
    if (values == nullptr) return false;
    for (std::size_t i = 0; i < count; ++i)
        if (!is_finite(values[i])) return false;
    return true;
}

/// Whether `names` holds `count` non-empty NUL-terminated names with no NUL
/// inside, offsets rising from 0: each name ends where the next begins.
inline bool names_ok(const NameTable& names, std::size_t count) noexcept {
    if (!names.present() || names.offsets[0] != 0) return false;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t begin = names.offsets[i], end = names.offsets[i + 1];
        if (end < begin + 2u) return false;  // at least one character and the NUL
        for (std::uint32_t k = begin; k + 1 < end; ++k)
            if (names.text[k] == '\0') return false;
        if (names.text[end - 1] != '\0') return false;
    }
    return true;
}

/// All finite and within [low, high].
inline bool all_within(const float* values, std::size_t count, float low, float high) noexcept {
    if (values == nullptr) return false;
    for (std::size_t i = 0; i < count; ++i)
        if (!(values[i] >= low && values[i] <= high)) return false;  // NaN fails too
    return true;
}

/// A weight in [0, max_weight]; NaN is not one.
constexpr bool is_weight(float w) noexcept { return w >= 0.0f && w <= max_weight; }

/// Records which check failed (a static string naming the field) and returns invalid_model.
inline Status refuse(const char** problem, const char* what) noexcept {
    if (problem != nullptr) *problem = what;
    return Status::invalid_model;
}

}  // namespace detail

/// Checks the tables that turn frames into characters (skeleton, projection,
/// GMM, tree, string rate) so the per-frame code can trust them. O(table
/// size); call once, before streaming. Returns ok or invalid_model; then
/// `problem`, when given, names the field and what is wrong (static storage).
inline Status validate_feature_tables(const ModelView& m, const char** problem = nullptr) noexcept {
    using detail::all_within;
    using detail::refuse;
    const float big = max_table_value;
    // Skeleton.
    if (m.joint_count == 0) return refuse(problem, "joint_count: no joints");
    // Optional in a hand-built view; trained models name every joint.
    if ((m.joint_names.text != nullptr || m.joint_names.offsets != nullptr) &&
        !detail::names_ok(m.joint_names, m.joint_count))
        return refuse(problem, "joint_names: not joint_count non-empty NUL-terminated names");
    if (m.up_axis > 2) return refuse(problem, "up_axis: not 0, 1 or 2");
    if (m.scale_mode > ScaleMode::torso) return refuse(problem, "scale_mode: unknown mode");
    if (m.covariance > Covariance::diagonal) return refuse(problem, "covariance: unknown kind");
    if (m.root_joint >= m.joint_count) return refuse(problem, "root_joint: not a joint of the skeleton");
    if (m.left_hip_joint >= m.joint_count) return refuse(problem, "left_hip_joint: not a joint of the skeleton");
    if (m.right_hip_joint >= m.joint_count) return refuse(problem, "right_hip_joint: not a joint of the skeleton");
    if (m.left_hip_joint == m.right_hip_joint)
        return refuse(problem, "right_hip_joint: the same joint as the left hip");
    if (m.scale_mode == ScaleMode::hip_width && !(m.reference_scale > 0.0f && m.reference_scale <= big))
        return refuse(problem, "reference_scale: not a positive finite length");
    if (uses_kinematic_tree(m.scale_mode)) {
        if (m.joint_parents == nullptr || m.bone_order == nullptr || m.bone_lengths == nullptr)
            return refuse(problem, "joint_parents: bone-length or torso scaling needs the kinematic tree");
        if (m.joint_count > max_bone_joints) return refuse(problem, "joint_count: over 256 joints to scale by bones");
        // bone_order lists every joint once, each after its parent.
        for (std::size_t k = 0; k < m.joint_count; ++k) {
            const std::size_t j = m.bone_order[k];
            if (j >= m.joint_count) return refuse(problem, "bone_order: not a joint of the skeleton");
            const int parent = m.joint_parents[j];
            if (parent >= static_cast<int>(m.joint_count) || parent < -1)
                return refuse(problem, "joint_parents: not a joint of the skeleton");
            if (parent >= 0) {
                bool earlier = false;
                for (std::size_t e = 0; e < k && !earlier; ++e) earlier = m.bone_order[e] == parent;
                if (!earlier) return refuse(problem, "bone_order: a joint before its parent, or twice");
            }
            for (std::size_t e = 0; e < k; ++e)
                if (m.bone_order[e] == j) return refuse(problem, "bone_order: a joint listed twice");
        }
        if (!detail::all_within(m.bone_lengths, m.joint_count, 0.0f, 1000.0f))
            return refuse(problem, "bone_lengths: missing, negative, non-finite or beyond 1 km");
        if (m.scale_mode == ScaleMode::torso) {
            float torso = 0.0f;
            for (std::size_t j = 0; j < m.joint_count; ++j)
                if (m.joint_parents[j] >= 0) torso += m.bone_lengths[j];
            if (!(torso > 1.0e-3f)) return refuse(problem, "bone_lengths: no torso bone to scale by");
        }
    }
    if (m.pose_joint_count == 0 || m.pose_joints == nullptr) return refuse(problem, "pose_joints: empty");
    for (std::size_t i = 0; i < m.pose_joint_count; ++i)
        if (m.pose_joints[i] >= m.joint_count) return refuse(problem, "pose_joints: not a joint of the skeleton");
    // Motion.
    if (!detail::is_weight(m.velocity_weight))
        return refuse(problem, "velocity_weight: negative, non-finite or beyond 1000");
    if (!detail::is_weight(m.acceleration_weight))
        return refuse(problem, "acceleration_weight: negative, non-finite or beyond 1000");
    if (m.has_motion() && !(m.velocity_span_us >= 10000 && m.velocity_span_us <= 2000000))
        return refuse(problem, "velocity_span_us: not between 10 ms and 2 s");
    // Projection.
    const std::size_t pose_dim = m.input_dim();
    if (m.feature_dim == 0) return refuse(problem, "feature_dim: zero");
    if (m.has_projection()) {
        if (m.feature_dim > pose_dim) return refuse(problem, "feature_dim: larger than the pose");
        if (!all_within(m.projection_mean, pose_dim, -big, big))
            return refuse(problem, "projection_mean: missing, non-finite or beyond 1e6");
        if (!all_within(m.projection_matrix, pose_dim * m.feature_dim, -big, big))
            return refuse(problem, "projection_matrix: non-finite or beyond 1e6");
    } else if (m.feature_dim != pose_dim) {
        return refuse(problem, "feature_dim: not the input's length, and there is no projection");
    }
    // GMM.
    const std::size_t J = m.component_count;
    if (J > 0) {
        if (!all_within(m.gmm_means, J * m.feature_dim, -big, big))
            return refuse(problem, "gmm_means: missing, non-finite or beyond 1e6");
        if (!all_within(m.gmm_factors, J * m.factor_size(), -big, big))
            return refuse(problem, "gmm_factors: missing, non-finite or beyond 1e6");
        if (!all_within(m.gmm_log_normalizers, J, -max_log_normalizer, max_log_normalizer))
            return refuse(problem, "gmm_log_normalizers: missing, non-finite or beyond 1e4");
        if (!all_within(m.gmm_log_weights, J, min_log_weight, 0.0f))
            return refuse(problem, "gmm_log_weights: missing, or not the log of a probability (in [-1e4, 0])");
    }
    // Tree: children point forward and leaves carry a character.
    if (m.node_count == 0 || m.node_children == nullptr || m.node_characters == nullptr)
        return refuse(problem, "node_characters: no tree");
    if (!all_within(m.node_centroids, static_cast<std::size_t>(m.node_count) * m.tree_dim(), -big, big))
        return refuse(problem, "node_centroids: missing, non-finite or beyond 1e6");
    const std::size_t K = m.character_count;
    if (K == 0) return refuse(problem, "character_count: zero");
    for (std::size_t n = 0; n < m.node_count; ++n) {
        const int left = m.node_children[2 * n], right = m.node_children[2 * n + 1];
        const bool leaf = left < 0 && right < 0;
        if (leaf) {
            if (m.node_characters[n] >= K) return refuse(problem, "node_characters: a leaf's character is not below K");
            continue;
        }
        if (left <= static_cast<int>(n) || right <= static_cast<int>(n) || left == right)
            return refuse(problem, "node_children: a child that does not point forward");
        if (left >= m.node_count || right >= m.node_count) return refuse(problem, "node_children: past the last node");
    }
    if (m.string_period_us < min_string_period_us)
        return refuse(problem, "string_period_us: below 1000 (a string rate above 1 kHz)");
    if (m.string_period_us > max_string_period_us)
        return refuse(problem, "string_period_us: above 1000000 (a string rate below 1 Hz)");
    return Status::ok;
}

/// Checks the tables that turn characters into labels (W, representatives,
/// labels, window and kNN settings) so the matcher can trust them.
inline Status validate_matching_tables(const ModelView& m, const char** problem = nullptr) noexcept {
    using detail::refuse;
    const std::size_t K = m.character_count;
    if (K == 0) return refuse(problem, "character_count: zero");
    // A distance: costs stay ≥ 0 and below float range.
    if (!detail::all_within(m.character_distances, K * K, 0.0f, max_table_value))
        return refuse(problem, "character_distances: missing, negative, non-finite or beyond 1e6");
    // Strings and representatives.
    if (m.label_count == 0 || !m.label_names.present()) return refuse(problem, "label_names: none");
    if (!detail::names_ok(m.label_names, m.label_count))
        return refuse(problem, "label_names: not label_count non-empty NUL-terminated names");
    const std::size_t R = m.representative_count;
    if (R == 0 || m.representative_offsets == nullptr || m.representative_chars == nullptr ||
        m.representative_labels == nullptr)
        return refuse(problem, "representative_labels: no representatives");
    if (m.representative_offsets[0] != 0) return refuse(problem, "representative_offsets: not starting at 0");
    for (std::size_t r = 0; r < R; ++r) {
        if (m.representative_offsets[r + 1] <= m.representative_offsets[r])
            return refuse(problem, "representative_offsets: an empty or backward string");
        if (m.representative_labels[r] >= m.label_count)
            return refuse(problem, "representative_labels: not a label of the model");
    }
    for (std::size_t c = 0; c < m.total_representative_chars(); ++c)
        if (m.representative_chars[c] >= K) return refuse(problem, "representative_chars: not below K");
    // Votes: log-probabilities, finite, so a sum over any string stays finite.
    if (!detail::is_weight(m.vote_weight))
        return refuse(problem, "vote_weight: negative, non-finite or beyond 1000");
    if (m.vote_weight > 0.0f &&
        !detail::all_within(m.character_votes, std::size_t{m.label_count} * K, min_log_weight, 0.0f))
        return refuse(problem, "character_votes: missing, or not log-probabilities in [-1e4, 0]");
    if (m.has_no_action_votes > 1) return refuse(problem, "has_no_action_votes: not 0 or 1");
    if (m.vote_weight > 0.0f && m.has_no_action_votes && !detail::all_within(m.no_action_votes, K, min_log_weight, 0.0f))
        return refuse(problem, "no_action_votes: missing, or not log-probabilities in [-1e4, 0]");
    // Exemplars: labelled points of the feature space, a positive scale.
    if (!detail::is_weight(m.exemplar_weight))
        return refuse(problem, "exemplar_weight: negative, non-finite or beyond 1000");
    if (m.exemplar_dim > m.feature_dim) return refuse(problem, "exemplar_dim: more than feature_dim");
    if (m.exemplar_count > 0) {
        if (m.exemplar_labels == nullptr) return refuse(problem, "exemplar_labels: missing");
        // Each a label of the model, or unknown_label ("no action") after every label's.
        bool no_action = false;
        for (std::size_t e = 0; e < m.exemplar_count; ++e) {
            const LabelId label = m.exemplar_labels[e];
            if (label == unknown_label) {
                no_action = true;
                continue;
            }
            if (label >= m.label_count) return refuse(problem, "exemplar_labels: not a label of the model");
            if (no_action) return refuse(problem, "exemplar_labels: a label's centre after those of no action");
        }
        if (!detail::all_within(m.exemplars, std::size_t{m.exemplar_count} * m.exemplar_dims(), -max_table_value,
                                max_table_value))
            return refuse(problem, "exemplars: missing, non-finite or beyond 1e6");
    }
    if (m.exemplar_weight > 0.0f && !(m.exemplar_scale >= 1.0e-12f && m.exemplar_scale <= max_table_value))
        return refuse(problem, "exemplar_scale: not a positive finite mean squared distance");
    // The clip descriptor: a linear classifier over at most 64 coordinates (its
    // covariances grow with their square), finite weights.
    if (!detail::is_weight(m.descriptor_weight))
        return refuse(problem, "descriptor_weight: negative, non-finite or beyond 1000");
    if (m.descriptor_levels > 8) return refuse(problem, "descriptor_levels: more than 8");
    if (m.descriptor_dim > m.feature_dim) return refuse(problem, "descriptor_dim: more than feature_dim");
    if (m.descriptor_levels > 0) {
        if (m.descriptor_dims() == 0 || m.descriptor_dims() > max_descriptor_dims)
            return refuse(problem, "descriptor_dim: the descriptor reads 1 to 64 coordinates");
        if (!detail::all_within(m.descriptor_weights, std::size_t{m.label_count} * m.descriptor_size(),
                                -max_table_value, max_table_value))
            return refuse(problem, "descriptor_weights: missing, non-finite or beyond 1e6");
        if (!detail::all_within(m.descriptor_bias, m.label_count, -max_table_value, max_table_value))
            return refuse(problem, "descriptor_bias: missing, non-finite or beyond 1e6");
    }
    // The motion directions: a linear classifier over the pose joints' histograms.
    if (!detail::is_weight(m.direction_weight))
        return refuse(problem, "direction_weight: negative, non-finite or beyond 1000");
    if (m.direction_levels > 8) return refuse(problem, "direction_levels: more than 8");
    if (m.direction_levels > 0) {
        if (m.pose_joint_count == 0) return refuse(problem, "direction_levels: no pose joints to follow");
        if (!detail::all_within(m.direction_weights, std::size_t{m.label_count} * m.direction_size(), -max_table_value,
                                max_table_value))
            return refuse(problem, "direction_weights: missing, non-finite or beyond 1e6");
        if (!detail::all_within(m.direction_bias, m.label_count, -max_table_value, max_table_value))
            return refuse(problem, "direction_bias: missing, non-finite or beyond 1e6");
    }
    // The window's directions: the same histograms over a stream's last characters.
    if (m.window_direction_chars > 0) {
        if (m.pose_joint_count == 0) return refuse(problem, "window_direction_chars: no pose joints to follow");
        if (!detail::all_within(m.window_direction_weights, std::size_t{m.label_count} * m.window_direction_size(),
                                -max_table_value, max_table_value))
            return refuse(problem, "window_direction_weights: missing, non-finite or beyond 1e6");
        if (!detail::all_within(m.window_direction_bias, m.label_count, -max_table_value, max_table_value))
            return refuse(problem, "window_direction_bias: missing, non-finite or beyond 1e6");
    }
    // Matching.
    if (m.variant > MatchVariant::subsequence) return refuse(problem, "variant: unknown");
    if (m.normalization > LengthNormalization::query) return refuse(problem, "normalization: unknown");
    if (m.window_chars == 0) return refuse(problem, "window_chars: zero");
    if (m.step_chars == 0) return refuse(problem, "step_chars: zero");
    if (m.neighbours == 0 || m.neighbours > R || m.neighbours > max_neighbours)
        return refuse(problem, "neighbours: zero, over 64 or more than the representatives");
    if (detail::is_nan(m.unknown_distance) || m.unknown_distance < 0.0f)
        return refuse(problem, "unknown_distance: negative or NaN");
    if (m.has_label_bounds > 1) return refuse(problem, "has_label_bounds: not 0 or 1");
    if (m.has_label_bounds != 0) {
        if (m.label_bounds == nullptr) return refuse(problem, "label_bounds: missing");
        for (std::size_t l = 0; l < m.label_count; ++l)
            if (!(m.label_bounds[l] >= 0.0f)) return refuse(problem, "label_bounds: negative or NaN");
    }
    // Online settings.
    if (m.settle_delay_us > max_settle_delay_us) return refuse(problem, "settle_delay_us: over 10 minutes");
    if (m.settle_stable_us > max_settle_delay_us) return refuse(problem, "settle_stable_us: over 10 minutes");
    if (!(m.segment_penalty >= 0.0f && m.segment_penalty <= max_table_value) ||
        !(m.stay_penalty >= 0.0f && m.stay_penalty <= max_table_value) ||
        !(m.skip_penalty >= 0.0f && m.skip_penalty <= max_table_value))
        return refuse(problem, "segment_penalty: a penalty negative, non-finite or beyond 1e6");
    if (!(m.unknown_cost >= 0.0f)) return refuse(problem, "unknown_cost: negative or NaN");
    if (!detail::is_weight(m.segment_vote_weight))
        return refuse(problem, "segment_vote_weight: negative, non-finite or beyond 1000");
    if (!detail::is_weight(m.segment_exemplar_weight))
        return refuse(problem, "segment_exemplar_weight: negative, non-finite or beyond 1000");
    if (!detail::is_weight(m.segment_direction_weight))
        return refuse(problem, "segment_direction_weight: negative, non-finite or beyond 1000");
    if (m.min_action_us > max_settle_delay_us) return refuse(problem, "min_action_us: over 10 minutes");
    if (m.label_lead_us > max_settle_delay_us) return refuse(problem, "label_lead_us: over 10 minutes");
    return Status::ok;
}

/// Checks every index, size and value of a complete model; see
/// validate_feature_tables() for `problem`.
inline Status validate_model(const ModelView& m, const char** problem = nullptr) noexcept {
    const Status status = validate_feature_tables(m, problem);
    return status != Status::ok ? status : validate_matching_tables(m, problem);
}

}  // namespace actionstring
