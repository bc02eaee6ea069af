// actionstring — a whole clip's label (design.md §1.8): a gesture between two
// events of the game or the device, or a recorded take, whose bounds the
// caller knows.
//
// The streaming annotator explains a running stream as actions laid end to
// end; a clip whose beginning and end are known is classified as a whole
// instead, as the trainer's cross-validation and `eval` classify clips: the
// batch string distance to every representative, plus what the characters'
// votes, the exemplars and the clip descriptor add per label, then the kNN of
// classify_distances(). The caller collects the clip's characters (and, when
// the model has exemplars or a clip descriptor, the features they were made
// from: EncodedFrame's previous_feature / current_feature) from a
// StringEncoder, in order; the functions here compose the stages in the order
// the host's classify_clip() does, which calls them, so a device and `eval`
// give a clip the same label bit for bit.
//
// Nothing is allocated: the scratch is the caller's, clip_scratch_floats()
// floats and clip_cells() DTW cells, read and written only during a call.
// ClipRecorder does the collecting too, in one block of storage the caller
// owns (storage.hpp), sized by the model and the longest clip it must hold.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/classify.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/exemplars.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"
#include "actionstring/string_distance.hpp"

namespace actionstring {

/// The longest representative string of a model, in characters.
constexpr std::uint32_t longest_representative(const ModelView& model) noexcept {
    std::uint32_t longest = 0;
    for (std::size_t r = 0; r < model.representative_count; ++r)
        if (model.representative_length(r) > longest) longest = model.representative_length(r);
    return longest;
}

/// DTW cells classify_clip() and representative_distances() need for a clip of
/// `length` characters (one representative at a time).
constexpr std::size_t clip_cells(const ModelView& model, std::size_t length) noexcept {
    return string_distance_cells(length, longest_representative(model));
}

/// Floats of scratch classify_clip() needs: the distance to every
/// representative, five label-sized rows (the exemplars' sums, their
/// penalties, the clip summaries' penalties, all of them added, and the
/// directions' own) and the larger of the descriptor's and the directions'
/// scratch (clip_summary_penalties()).
constexpr std::size_t clip_scratch_floats(const ModelView& model) noexcept {
    return model.representative_count + 5u * model.label_count +
           (model.descriptor_size() > model.direction_size() ? model.descriptor_size() : model.direction_size());
}

/// The batch string distance (the model's variant and normalisation) from a
/// clip's string to every representative; +inf for a representative it
/// cannot be compared with (an empty string, a string too long for a path).
/// @param string    `length` characters; read only during the call
/// @param cells     clip_cells(model, length) cells (caller-owned), overwritten
/// @param distances receives representative_count floats (caller-owned)
inline void representative_distances(const ModelView& model, const Character* string, std::size_t length,
                                     detail::Cell* cells, float* distances) noexcept {
    if (distances == nullptr) return;
    for (std::size_t r = 0; r < model.representative_count; ++r) {
        distances[r] = detail::infinity();
        if (string == nullptr || length == 0 || cells == nullptr) continue;
        const Character* rep = model.representative_chars + model.representative_offsets[r];
        // A refusal leaves the distance at +inf.
        (void)string_distance(string, length, rep, model.representative_length(r), character_weights(model),
                              MatchOptions{model.variant, model.normalization}, cells, &distances[r]);
    }
}

/// Per label, the sum over a clip's `length` features of exemplar_distances(),
/// in order (what exemplar_penalties() reads). All 0 without exemplars.
/// @param features  length × feature_dim floats; read only during the call
/// @param row       label_count floats of scratch (caller-owned), overwritten
/// @param sums      receives label_count floats (caller-owned)
inline void exemplar_sums(const ModelView& model, const float* features, std::size_t length, float* row,
                          float* sums) noexcept {
    if (sums == nullptr) return;
    const std::size_t L = model.label_count;
    for (std::size_t l = 0; l < L; ++l) sums[l] = 0.0f;
    if (!model.has_exemplars() || features == nullptr || row == nullptr) return;
    for (std::size_t c = 0; c < length; ++c) {
        exemplar_distances(model, features + c * model.feature_dim, row);
        for (std::size_t l = 0; l < L; ++l) sums[l] += row[l];
    }
}

/// What a clip adds to the distance of each label's representatives: the
/// characters' votes, then the exemplars' penalties from their `sums`
/// (exemplar_sums(), or null: none), then the clip descriptor's `descriptor`
/// penalties (descriptor_penalties(), or null: none), added in that order.
/// Returns whether any applies (the model has votes, or exemplars with sums,
/// or a descriptor with penalties); classify_distances() then takes them.
/// @param string     `length` characters; read only during the call
/// @param row        label_count floats of scratch (caller-owned), overwritten
/// @param penalties  receives label_count floats (caller-owned)
inline bool clip_penalties(const ModelView& model, const Character* string, std::size_t length, const float* sums,
                           const float* descriptor, float* row, float* penalties) noexcept {
    if (penalties == nullptr) return false;
    const std::size_t L = model.label_count;
    vote_penalties(model, string, length, penalties);
    const bool exemplars = model.has_exemplars() && sums != nullptr && row != nullptr;
    if (exemplars) {
        exemplar_penalties(model, sums, length, row);
        for (std::size_t l = 0; l < L; ++l) penalties[l] += row[l];
    }
    const bool described = (model.has_descriptor() || model.has_directions()) && descriptor != nullptr;
    if (described)
        for (std::size_t l = 0; l < L; ++l) penalties[l] += descriptor[l];
    return model.has_votes() || exemplars || described;
}

namespace detail {

// classify_clip()'s scores: the string's distance to every representative,
// left in scratch's first representative_count floats, and the penalties
// clip_penalties() adds to each label's (returned; null when none applies).
inline const float* clip_scores(const ModelView& model, const Character* string, const float* features,
                                const float* records, std::size_t length, float* scratch,
                                detail::Cell* cells) noexcept {
    const std::size_t L = model.label_count;
    float* const distances = scratch;
    float* const sums = distances + model.representative_count;
    float* const row = sums + L;
    float* const described = row + L;
    float* const penalties = described + L;
    float* const directed = penalties + L;
    float* const descriptor_scratch = directed + L;
    representative_distances(model, string, length, cells, distances);
    const bool with_exemplars = model.has_exemplars() && features != nullptr;
    const bool summarised =
        clip_summary_penalties(model, features, records, length, descriptor_scratch, directed, described);
    if (with_exemplars) exemplar_sums(model, features, length, row, sums);
    const bool any = clip_penalties(model, string, length, with_exemplars ? sums : nullptr,
                                    summarised ? described : nullptr, row, penalties);
    return any ? penalties : nullptr;
}

}  // namespace detail

/// The label of a whole clip: its string's distance to every representative,
/// what the votes, the exemplars and the clip descriptor add (clip_penalties()),
/// then classify_distances()'s kNN, its unknown distance and bounds.
/// @param string    `length` characters of the clip, in order; read only during the call
/// @param features  length × feature_dim floats, the features those characters
///                  were made from, in order; null to leave out the exemplars
///                  and the clip descriptor (a model without them needs none)
/// @param records   length × direction_record_floats() floats, those
///                  characters' poses and facings, in order (EncodedFrame's
///                  previous_pose / previous_facing …); read only by a model
///                  with motion directions, which leave the label alone when null
/// @param scratch   clip_scratch_floats(model) floats (caller-owned), overwritten
/// @param cells     clip_cells(model, length) cells (caller-owned), overwritten
/// @return the label (unknown_label for an empty clip, or when nothing is near enough)
inline Classification classify_clip(const ModelView& model, const Character* string, const float* features,
                                    const float* records, std::size_t length, float* scratch,
                                    detail::Cell* cells) noexcept {
    if (scratch == nullptr) return Classification{};
    const float* const penalties = detail::clip_scores(model, string, features, records, length, scratch, cells);
    return classify_distances(model, scratch, penalties);
}

/// Each label's score for a whole clip, from the same distances and penalties
/// classify_clip() decides by (label_distances(): the nearest representative
/// of each label, its penalty added; smaller is nearer). For ranking labels
/// (top-k accuracy, ROC curves, fusing with another classifier); the label
/// itself, with the unknown distance and bounds, is classify_clip()'s. The
/// arguments are classify_clip()'s.
/// @param out receives label_count floats (caller-owned); all +inf for an empty clip
inline void clip_label_distances(const ModelView& model, const Character* string, const float* features,
                                 const float* records, std::size_t length, float* scratch, detail::Cell* cells,
                                 float* out) noexcept {
    if (out == nullptr) return;
    if (scratch == nullptr) {
        for (std::size_t l = 0; l < model.label_count; ++l) out[l] = detail::infinity();
        return;
    }
    const float* const penalties = detail::clip_scores(model, string, features, records, length, scratch, cells);
    label_distances(model, scratch, penalties, out);
}

/// Records a clip from frames and labels it when asked: a gesture between two
/// events. The frames go through its own StringEncoder; the characters and
/// their features are kept, up to `max_characters` (the first ones: a longer
/// clip keeps its beginning and push_frame() says so), and classify() runs
/// classify_clip() over them. Works in caller-owned storage of
/// required_bytes(model, max_characters) bytes (storage.hpp); keeps pointers
/// to the ModelView given to init() and to the storage: both must outlive it.
class ClipRecorder {
public:
    /// Bytes of storage init() needs (constexpr when the model is), or
    /// unsatisfiable_bytes when no storage could hold that many characters.
    static constexpr std::size_t required_bytes(const ModelView& model, std::size_t max_characters,
                                                const EncoderConfig& config = {}) noexcept {
        return plan(model, max_characters, config).bytes;
    }

    /// @return ok, invalid_model (validate_model() names the field),
    ///         invalid_argument (no room for a character, or times the encoder
    ///         refuses), storage_too_small, or what the encoder's init() returns
    Status init(const ModelView& model, std::size_t max_characters, const EncoderConfig& config, void* storage,
                std::size_t bytes) noexcept {
        model_ = nullptr;
        // Every table classify() reads, checked once here (as Annotator::init() does).
        const Status valid = validate_model(model);
        if (valid != Status::ok) return valid;
        if (max_characters == 0) return Status::invalid_argument;
        const EncoderConfig plain = immediate(config);
        const Plan p = plan(model, max_characters, config);
        if (!detail::storage_fits(storage, bytes, p.bytes)) return Status::storage_too_small;
        detail::clear_storage(storage, p.bytes);
        const Status status =
            encoder_.init(model, plain, detail::storage_at<unsigned char>(storage, p.encoder), p.encoder_bytes);
        if (status != Status::ok) return status;
        characters_ = detail::storage_at<Character>(storage, p.characters);
        features_ = detail::storage_at<float>(storage, p.features);
        records_ = detail::storage_at<float>(storage, p.records);
        scratch_ = detail::storage_at<float>(storage, p.scratch);
        cells_ = detail::storage_at<detail::Cell>(storage, p.cells);
        capacity_ = max_characters;
        model_ = &model;
        reset();
        return Status::ok;
    }

    /// A new clip: the characters are forgotten and the encoder starts a new stream.
    void reset() noexcept {
        length_ = 0;
        overflowed_ = false;
        if (model_ != nullptr) encoder_.reset();
    }

    /// One frame: `positions` holds joint_count × 3 floats (metres, the model's
    /// joint order), read only during the call. Returns the encoder's status
    /// (a frame that is not a pose is skipped and changes nothing), or
    /// storage_too_small when the clip is full and this frame's characters
    /// were dropped; not_initialized before a successful init().
    Status push_frame(std::int64_t time_us, const float* positions) noexcept {
        if (model_ == nullptr) return Status::not_initialized;
        const EncodedFrame e = encoder_.push_frame(time_us, positions);
        if (!e.accepted()) return e.status;
        const std::size_t d = model_->feature_dim;
        bool dropped = false;
        for (std::uint32_t k = 0; k < e.count(); ++k) {
            if (length_ == capacity_) {
                dropped = true;
                break;
            }
            const bool previous = k < e.from_previous;
            characters_[length_] = previous ? e.previous : e.current;
            const float* feature = previous ? e.previous_feature : e.current_feature;
            for (std::size_t i = 0; i < d; ++i) features_[length_ * d + i] = feature[i];
            if (model_->has_directions()) {
                const std::size_t D = model_->pose_dim(), n = model_->direction_record_floats();
                const float* pose = previous ? e.previous_pose : e.current_pose;
                const float* facing = previous ? e.previous_facing : e.current_facing;
                float* record = records_ + length_ * n;
                for (std::size_t i = 0; i < D; ++i) record[i] = pose[i];
                record[D] = facing[0];
                record[D + 1u] = facing[1];
            }
            ++length_;
        }
        overflowed_ = overflowed_ || dropped;
        return dropped ? Status::storage_too_small : e.status;
    }

    /// The clip's label so far (classify_clip(): unknown before its first
    /// character). Reads the characters, writes only the scratch; the clip
    /// goes on recording.
    Classification classify() noexcept {
        if (model_ == nullptr) return Classification{};
        return classify_clip(*model_, characters_, features_, model_->has_directions() ? records_ : nullptr, length_,
                             scratch_, cells_);
    }

    /// Each label's score for the clip so far (clip_label_distances(): smaller
    /// is nearer; all +inf before its first character), into `out`,
    /// label_count floats (caller-owned). Writes only the scratch and `out`.
    void label_distances(float* out) noexcept {
        if (model_ == nullptr || out == nullptr) return;
        clip_label_distances(*model_, characters_, features_, model_->has_directions() ? records_ : nullptr, length_,
                             scratch_, cells_, out);
    }

    std::size_t length() const noexcept { return length_; }
    std::size_t capacity() const noexcept { return capacity_; }
    /// Whether characters were dropped since the last reset() (the clip was longer than capacity()).
    bool overflowed() const noexcept { return overflowed_; }
    /// The clip's characters, length() of them.
    const Character* characters() const noexcept { return characters_; }
    /// Their features, feature_dim floats each.
    const float* features() const noexcept { return features_; }
    /// Their poses and facings, direction_record_floats() each, kept only for
    /// a model with motion directions (else null).
    const float* records() const noexcept { return model_ != nullptr && model_->has_directions() ? records_ : nullptr; }

private:
    struct Plan {
        std::size_t encoder = 0, encoder_bytes = 0, characters = 0, features = 0, records = 0, scratch = 0, cells = 0,
                    bytes = 0;
    };
    // Every character and its feature as its frame comes: never deferred, so
    // required_bytes() and init() size the encoder alike whatever is asked.
    static constexpr EncoderConfig immediate(EncoderConfig config) noexcept {
        config.deferred = false;
        return config;
    }
    static constexpr Plan plan(const ModelView& model, std::size_t max_characters,
                               const EncoderConfig& config) noexcept {
        Plan p;
        detail::StorageLayout layout;
        p.encoder_bytes = StringEncoder::required_bytes(model, immediate(config));
        p.encoder = layout.add_bytes(p.encoder_bytes, 1);
        p.characters = layout.add<Character>(max_characters);
        const std::size_t d = model.feature_dim;
        // Counts whose product would wrap are no storage at all.
        const std::size_t n = model.has_directions() ? model.direction_record_floats() : 0u;  // kept records
        const bool too_many = (d != 0 && max_characters > unsatisfiable_bytes / d) ||
                              (n != 0 && max_characters > unsatisfiable_bytes / n) ||
                              max_characters >= unsatisfiable_bytes / (longest_representative(model) + 1u);
        p.features = layout.add<float>(too_many ? unsatisfiable_bytes : max_characters * d);
        p.records = layout.add<float>(too_many ? unsatisfiable_bytes : max_characters * n);
        p.scratch = layout.add<float>(clip_scratch_floats(model));
        p.cells = layout.add<detail::Cell>(too_many ? unsatisfiable_bytes : clip_cells(model, max_characters));
        p.bytes = p.encoder_bytes == unsatisfiable_bytes ? unsatisfiable_bytes : layout.bytes();
        return p;
    }

    const ModelView* model_ = nullptr;
    StringEncoder encoder_;
    Character* characters_ = nullptr;
    float* features_ = nullptr;
    float* records_ = nullptr;  // with motion directions: each character's pose and facing
    float* scratch_ = nullptr;
    detail::Cell* cells_ = nullptr;
    std::size_t capacity_ = 0, length_ = 0;
    bool overflowed_ = false;
};

}  // namespace actionstring
