// actionstring — every field of a trained model, declared once.
//
// ACTIONSTRING_MODEL_FIELDS lists the fields in the order the model artifact
// stores them. The runtime's ModelView (model.hpp), the host's owning model
// data, the artifact reader and writer and the header generator are all
// expanded from this one list, so adding a table is one line here plus the
// code that uses it. The design document (docs/design.md §3) describes each table.
//
// The caller passes one macro per kind of field:
//
//   SCALAR(type, name, initial, low, high)
//       One value. For integer and enum types [low, high] is the range an
//       artifact may hold; floats ignore it (any finite value, or ±inf).
//   COUNT(type, name, table)
//       The view's element count of `table`. Owning model data has no such
//       member: the count is the table's size, so the two cannot disagree.
//   TABLE(type, name, size, low, high)
//       An array. The view holds a pointer (null when empty), owning data a
//       vector. `size` is its element count as an expression of the view `m`
//       (0 for an absent optional table); it may use the fields listed before
//       it. [low, high] bounds integer elements as for SCALAR.
//   NAMES(name, count)
//       NUL-terminated names (joints, labels): `const char* const*` in the
//       view, one line each in the artifact.
//
// Enum types, Character and LabelId are those of namespace actionstring; an
// expansion outside that namespace must qualify them itself (see model.hpp).
#pragma once

// clang-format off
#define ACTIONSTRING_MODEL_FIELDS(SCALAR, COUNT, TABLE, NAMES)                                            \
    /* --- skeleton and pose normalisation (design §1.1) --- */                                           \
    SCALAR(std::uint16_t, joint_count, 0, 1, 65535)        /* joints per input frame (xyz each) */        \
    NAMES(joint_names, m.joint_count)                      /* the input skeleton, in frame order */       \
    SCALAR(std::uint16_t, root_joint, 0, 0, 65535)         /* the pose is made relative to it */          \
    SCALAR(std::uint16_t, left_hip_joint, 0, 0, 65535)     /* with the right hip: the facing direction */ \
    SCALAR(std::uint16_t, right_hip_joint, 0, 0, 65535)                                                   \
    SCALAR(std::uint8_t, up_axis, 1, 0, 2)                 /* 0 = x, 1 = y, 2 = z */                      \
    SCALAR(ScaleMode, scale_mode, ScaleMode::none, 0, 3)                                                  \
    SCALAR(float, reference_scale, 1.0f, 0, 0)             /* target hip width when scaling by it */      \
    /* the kinematic tree, for bone-length or torso scaling only (empty otherwise) */                     \
    TABLE(std::int16_t, joint_parents, (uses_kinematic_tree(m.scale_mode) ? m.joint_count : 0u), -1, 32767) \
    TABLE(std::uint16_t, bone_order, (uses_kinematic_tree(m.scale_mode) ? m.joint_count : 0u), 0, 65535)    \
    TABLE(float, bone_lengths, (uses_kinematic_tree(m.scale_mode) ? m.joint_count : 0u), 0, 0) /* to the parent */ \
    COUNT(std::uint16_t, pose_joint_count, pose_joints)                                                   \
    TABLE(std::uint16_t, pose_joints, m.pose_joint_count, 0, 65535) /* joints of the pose vector */       \
    /* --- motion (design §1.1): the pose's velocity beside it, weighted; 0 = none --- */                 \
    SCALAR(float, velocity_weight, 0.0f, 0, 0)                                                            \
    SCALAR(std::uint32_t, velocity_span_us, 0, 0, 10000000) /* motion is taken over about this */         \
    /* then the change of the velocity across that span, weighted; 0 = none */                            \
    SCALAR(float, acceleration_weight, 0.0f, 0, 0)                                                        \
    /* --- optional projection z = P (x - m) (design §1.2) --- */                                         \
    SCALAR(std::uint16_t, feature_dim, 0, 0, 65535)        /* d; input_dim() without PCA */               \
    TABLE(float, projection_mean, (m.has_projection() ? m.input_dim() : 0u), 0, 0)                        \
    /* P column by column: row c holds the weights of pose coordinate c in every feature */               \
    TABLE(float, projection_matrix, (m.has_projection() ? m.input_dim() * m.feature_dim : 0u), 0, 0)      \
    /* --- GMM of key-poses (design §1.3); J = 0: no GMM, the tree descends on z --- */                   \
    SCALAR(std::uint16_t, component_count, 0, 0, 65535)    /* J */                                        \
    SCALAR(Covariance, covariance, Covariance::full, 0, 1)                                                \
    TABLE(float, gmm_means, std::size_t{m.component_count} * m.feature_dim, 0, 0)                         \
    /* precision = U^T U, U upper triangular: full packs U column by column, diagonal keeps sqrt(prec); */ \
    /* four components interleaved element by element (ModelView::gmm_factor_index) */                    \
    TABLE(float, gmm_factors, m.component_count * m.factor_size(), 0, 0)                                  \
    TABLE(float, gmm_log_normalizers, m.component_count, 0, 0) /* -d/2 log 2pi + sum log U_ii */          \
    TABLE(float, gmm_log_weights, m.component_count, 0, 0)                                                \
    /* --- cluster tree whose leaves are the characters (design §1.4) --- */                              \
    COUNT(std::uint16_t, node_count, node_characters)      /* node 0 is the root */                       \
    TABLE(float, node_centroids, m.node_count * m.tree_dim(), 0, 0)                                       \
    /* children, both -1 at a leaf; a child's index is greater than its parent's */                       \
    TABLE(std::int16_t, node_children, 2u * m.node_count, -1, 32767)                                      \
    TABLE(Character, node_characters, m.node_count, 0, 65535) /* meaningful at leaves */                  \
    SCALAR(std::uint16_t, character_count, 0, 0, 65535)    /* K */                                        \
    TABLE(float, character_distances, std::size_t{m.character_count} * m.character_count, 0, 0) /* W */ \
    /* --- strings and representatives (design §1.5, §1.7) --- */                                         \
    SCALAR(std::uint32_t, string_period_us, 0, 1, 1000000) /* one character every this many us */        \
    COUNT(std::uint16_t, representative_count, representative_labels) /* R */                            \
    TABLE(std::uint32_t, representative_offsets, m.representative_count + 1u, 0, 4294967295)              \
    TABLE(Character, representative_chars, m.total_representative_chars(), 0, 65535)                     \
    TABLE(LabelId, representative_labels, m.representative_count, 0, 65535)                              \
    COUNT(std::uint16_t, label_count, label_names)                                                        \
    NAMES(label_names, m.label_count)                                                                     \
    /* --- matching and labelling (design §1.6, §1.8) --- */                                              \
    SCALAR(MatchVariant, variant, MatchVariant::whole, 0, 2)                                              \
    SCALAR(LengthNormalization, normalization, LengthNormalization::none, 0, 2)                           \
    SCALAR(std::uint16_t, window_chars, 0, 1, 65535)       /* sliding window length in characters */      \
    SCALAR(std::uint16_t, step_chars, 0, 1, 65535)         /* a window opens every step_chars */          \
    SCALAR(std::uint16_t, neighbours, 1, 1, 64)            /* k of the kNN vote */                        \
    SCALAR(float, unknown_distance, detail::infinity(), 0, 0) /* best distance above it: unknown */     \
    /* each label's own bound on that distance, learned at training from held-out positives and */       \
    /* negatives (synthetic, and the unlabelled stretches of recordings); none when 0 */                 \
    SCALAR(std::uint8_t, has_label_bounds, 0, 0, 1)                                                       \
    TABLE(float, label_bounds, (m.has_label_bounds ? m.label_count : 0u), 0, 0)                           \
    /* the characters' label votes beside DTW (design §1.8): weight λ (0 = none) and log P(c | label), */ \
    /* label by label (K floats each) */                                                                  \
    SCALAR(float, vote_weight, 0.0f, 0, 0)                                                                \
    TABLE(float, character_votes, (m.vote_weight > 0.0f ? std::size_t{m.label_count} * m.character_count : 0u), 0, 0) \
    /* and log P(c | no action), learned from the unlabelled stretches of training recordings (or none) */ \
    SCALAR(std::uint8_t, has_no_action_votes, 0, 0, 1)                                                    \
    TABLE(float, no_action_votes, (m.vote_weight > 0.0f && m.has_no_action_votes ? m.character_count : 0u), 0, 0) \
    /* exemplars (design §1.8): each label's training features (z) summarised by k-means centres; */         \
    /* a clip's mean squared distance to each label's nearest centre, over exemplar_scale (the     */         \
    /* training features' own mean), times exemplar_weight, joins the votes in clip classification */         \
    SCALAR(float, exemplar_weight, 0.0f, 0, 0)             /* 0 = none */                                 \
    SCALAR(float, exemplar_scale, 1.0f, 0, 0)                                                             \
    /* the feature's leading coordinates a centre keeps and a distance reads; 0 = all (feature_dim) */    \
    SCALAR(std::uint16_t, exemplar_dim, 0, 0, 65535)                                                      \
    COUNT(std::uint16_t, exemplar_count, exemplar_labels)                                                 \
    TABLE(LabelId, exemplar_labels, m.exemplar_count, 0, 65535) /* each centre's label */                 \
    TABLE(float, exemplars, std::size_t{m.exemplar_count} * m.exemplar_dims(), 0, 0) /* exemplar_dims() each */ \
    /* the clip descriptor (design §1.8): a temporal pyramid of the clip's feature means and        */ \
    /* covariances (descriptor.hpp), scored per label by a linear classifier fitted by ridge        */ \
    /* regression; descriptor_weight times each label's shortfall from the best score joins the votes */ \
    SCALAR(float, descriptor_weight, 0.0f, 0, 0)           /* 0 = none */                                 \
    SCALAR(std::uint8_t, descriptor_levels, 0, 0, 8)       /* level v cuts the clip in v parts; 0 = none */ \
    SCALAR(std::uint16_t, descriptor_dim, 0, 0, 65535)     /* the feature's leading coordinates; 0 = all */ \
    /* label by label, descriptor_size() weights each (the training standardisation folded in) */      \
    TABLE(float, descriptor_weights, std::size_t{m.label_count} * m.descriptor_size(), 0, 0)               \
    TABLE(float, descriptor_bias, (m.descriptor_levels > 0 ? m.label_count : 0u), 0, 0)                   \
    /* the clip's motion directions (design §1.8, descriptor.hpp): per part of a temporal pyramid,   */ \
    /* each pose joint's histogram of step directions in the three coordinate planes (the clip     */ \
    /* turned by its first facing), scored per label by a second ridge classifier beside the first */ \
    SCALAR(float, direction_weight, 0.0f, 0, 0)            /* 0 = none */                                 \
    SCALAR(std::uint8_t, direction_levels, 0, 0, 8)        /* level v cuts the clip in v parts; 0 = none */ \
    TABLE(float, direction_weights, std::size_t{m.label_count} * m.direction_size(), 0, 0)                 \
    TABLE(float, direction_bias, (m.direction_levels > 0 ? m.label_count : 0u), 0, 0)                     \
    /* the motion directions of the last few characters of a stream (descriptor.hpp,              */ \
    /* window_direction_penalties()): the histograms over a window of that many characters,     */ \
    /* scored per label by a third ridge classifier fitted on every training clip's windows,     */ \
    /* for the segmenter                                                                          */ \
    SCALAR(std::uint16_t, window_direction_chars, 0, 0, 1024) /* the window; 0 = none */               \
    TABLE(float, window_direction_weights, std::size_t{m.label_count} * m.window_direction_size(), 0, 0)   \
    TABLE(float, window_direction_bias, (m.window_direction_chars > 0 ? m.label_count : 0u), 0, 0)       \
    /* --- online settings of the segmenter (design §1.8), chosen at training --- */                      \
    SCALAR(std::uint32_t, settle_delay_us, 2000000, 0, 600000000) /* a character's label is final then */ \
    /* or sooner, once every best explanation has given it that label this long; 0: the delay alone */   \
    SCALAR(std::uint32_t, settle_stable_us, 0, 0, 600000000)                                              \
    SCALAR(float, segment_penalty, 3.0f, 0, 0)             /* cost of starting another segment */         \
    SCALAR(float, stay_penalty, 0.3f, 0, 0)                /* two stream characters on one */             \
    SCALAR(float, skip_penalty, 0.3f, 0, 0)                /* skipping a representative character */      \
    SCALAR(float, unknown_cost, detail::infinity(), 0, 0)  /* per character of "no action"; inf: none */ \
    SCALAR(float, segment_vote_weight, 0.0f, 0, 0)         /* the characters' votes in the explanation */ \
    SCALAR(float, segment_exemplar_weight, 0.0f, 0, 0)     /* the exemplars in the explanation */         \
    SCALAR(float, segment_direction_weight, 0.0f, 0, 0)    /* the window's directions in the explanation */ \
    /* an action event needs a settled run this long (events.hpp): a shorter one is flicker */            \
    SCALAR(std::uint32_t, min_action_us, 250000, 0, 600000000)                                           \
    /* how much earlier than its tick a character's label applies (annotator.hpp, label_time_us()): */  \
    /* the feature's motion looks back over its span, so an action shows in it a little late        */  \
    SCALAR(std::uint32_t, label_lead_us, 0, 0, 600000000)
// clang-format on
