// actionstring C API over the runtime: models from blobs (or one built in),
// states in caller memory sized by the model.
#define ACTIONSTRING_C_BUILDING
#include "actionstring_c.h"

#include <cstdint>
#include <cstring>
#include <new>

#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
#include "actionstring/clip.hpp"
#include "actionstring/storage.hpp"
#include "actionstring/version.hpp"
#if defined(ACTIONSTRING_C_MODEL_HEADER)
#include ACTIONSTRING_C_MODEL_HEADER
#endif

namespace {

using actionstring::Annotator;
using actionstring::AnnotatorConfig;
using actionstring::ModelView;
using actionstring::Status;

// A handle or state set up by this API is told from stray memory by a magic
// word and its own address (memory filled with the magic, or a copy, does not
// hold it); a state also ends in a guard block (an overrun from the memory
// before it, or a state given less memory than it claims).
constexpr std::uint32_t kModelMagic = 0x4153544Du;  // "ASTM"
constexpr std::uint32_t kStateMagic = 0x41535452u;  // "ASTR"
constexpr std::uint32_t kClipMagic = 0x41535443u;   // "ASTC"
constexpr unsigned char kGuardByte = 0xA5;
constexpr std::size_t kGuardBytes = 16;

struct Model {
    std::uint32_t magic = 0;
    const void* self = nullptr;
    ModelView view;
    char checksum[40] = {};
};
static_assert(sizeof(Model) <= sizeof(actionstring_model), "the public handle holds the model");
static_assert(alignof(Model) <= alignof(actionstring_model), "the public handle is aligned for the model");

struct State {
    std::uint32_t magic = 0;
    const void* self = nullptr;
    const Model* model = nullptr;
    std::size_t total = 0;  // bytes from the state's start to the end of its guard
    Annotator annotator;
};
constexpr std::size_t kHeaderBytes =
    (sizeof(State) + actionstring::state_alignment - 1) / actionstring::state_alignment * actionstring::state_alignment;

struct ClipState {
    std::uint32_t magic = 0;
    const void* self = nullptr;
    const Model* model = nullptr;
    std::size_t total = 0;  // bytes from the recorder's start to the end of its guard
    actionstring::ClipRecorder recorder;
};
constexpr std::size_t kClipHeaderBytes = (sizeof(ClipState) + actionstring::state_alignment - 1) /
                                         actionstring::state_alignment * actionstring::state_alignment;

static_assert(ACTIONSTRING_OK == static_cast<int>(Status::ok), "status values match");
static_assert(ACTIONSTRING_TIME_WENT_BACKWARDS == static_cast<int>(Status::time_went_backwards), "status values match");
static_assert(ACTIONSTRING_NOT_INITIALIZED == static_cast<int>(Status::not_initialized), "status values match");
static_assert(ACTIONSTRING_STORAGE_TOO_SMALL == static_cast<int>(Status::storage_too_small), "status values match");

actionstring_status code(Status status) { return static_cast<actionstring_status>(status); }

const Model* checked_model(const actionstring_model* handle) {
    if (handle == nullptr) return nullptr;
    const auto* model = reinterpret_cast<const Model*>(handle);
    return model->magic == kModelMagic && model->self == model ? model : nullptr;
}

// The state behind a handle, or null when the handle is not one
// actionstring_init() returned (misaligned, never initialised, overwritten, moved).
// (T is State or ClipState, each with its magic and header size.)
template <class T>
const T* checked_block(const void* handle, std::uint32_t magic, std::size_t header_bytes) {
    if (handle == nullptr || reinterpret_cast<std::uintptr_t>(handle) % actionstring::state_alignment != 0)
        return nullptr;
    const auto* state = static_cast<const T*>(handle);
    if (state->magic != magic || state->self != state ||
        checked_model(reinterpret_cast<const actionstring_model*>(state->model)) == nullptr)
        return nullptr;
    if (state->total < header_bytes + kGuardBytes) return nullptr;
    const auto* guard = reinterpret_cast<const unsigned char*>(state) + state->total - kGuardBytes;
    for (std::size_t i = 0; i < kGuardBytes; ++i)
        if (guard[i] != kGuardByte) return nullptr;
    return state;
}
const State* checked(const void* handle) { return checked_block<State>(handle, kStateMagic, kHeaderBytes); }
State* live(actionstring_state* handle) { return const_cast<State*>(checked(handle)); }
const State* live(const actionstring_state* handle) { return checked(handle); }
const ClipState* checked_clip(const void* handle) {
    return checked_block<ClipState>(handle, kClipMagic, kClipHeaderBytes);
}
ClipState* live_clip(actionstring_clip* handle) { return const_cast<ClipState*>(checked_clip(handle)); }

// Marks a block set up in `size` bytes as live: the guard at the very end of
// the caller's memory (everything before it is the block's), then its model,
// its own address and its magic word, which checked_block() reads back.
template <class T>
void seal(T& block, const Model* model, std::size_t size, std::uint32_t magic) {
    block.total = size;
    std::memset(reinterpret_cast<unsigned char*>(&block) + size - kGuardBytes, kGuardByte, kGuardBytes);
    block.model = model;
    block.self = &block;
    block.magic = magic;
}

// Bytes a recorder of `max_characters` needs in all, or 0 when none could hold it.
std::size_t clip_bytes(const ModelView& model, std::uint32_t max_characters) {
    if (max_characters == 0) return 0;
    const std::size_t recorder = actionstring::ClipRecorder::required_bytes(model, max_characters);
    if (recorder == actionstring::unsatisfiable_bytes ||
        recorder > actionstring::unsatisfiable_bytes - kClipHeaderBytes - kGuardBytes)
        return 0;
    return kClipHeaderBytes + recorder + kGuardBytes;
}

// The segmenter's settings from the C struct, and back.
actionstring::SegmenterConfig from_settings(const actionstring_online_settings& s) {
    actionstring::SegmenterConfig c;
    c.settle_delay_us = s.settle_delay_us;
    c.segment_penalty = s.segment_penalty;
    c.stay_penalty = s.stay_penalty;
    c.skip_penalty = s.skip_penalty;
    c.unknown_cost = s.unknown_cost;
    c.vote_weight = s.vote_weight;
    c.exemplar_weight = s.exemplar_weight;
    c.settle_stable_us = s.settle_stable_us;
    c.direction_weight = s.direction_weight;
    return c;
}
actionstring_online_settings to_settings(const actionstring::SegmenterConfig& c) {
    return actionstring_online_settings{c.settle_delay_us, c.segment_penalty,  c.stay_penalty,
                                        c.skip_penalty,    c.unknown_cost,     c.vote_weight,
                                        c.exemplar_weight, c.settle_stable_us, c.direction_weight};
}

AnnotatorConfig to_config(const ModelView& model, const actionstring_config* c) {
    AnnotatorConfig config = actionstring::annotator_config(model);
    if (c == nullptr) return config;
    config.max_gap_us = c->max_gap_us;
    config.max_backward_us = c->max_backward_us;
    config.window_rule = c->window_rule != 0;
    config.min_action_us = c->min_action_us;
    config.spread_work = c->spread_work != 0;
    config.label_lead_us = c->label_lead_us;
    for (int a = 0; a < 3; ++a) config.up[a] = c->up[a];
    config.max_pose_speed = c->max_pose_speed;
    config.segmenter = from_settings(c->online);
    return config;
}

// Whether an up direction is none (all zero) or one the encoder turns by.
bool up_ok(const ModelView& model, const float* up) {
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f) return true;
    float rotation[9];
    return actionstring::up_rotation(up, model.up_axis, rotation) == Status::ok;
}

// Whether a config is one init() accepts for the model (given enough memory).
bool config_ok(const ModelView& model, const AnnotatorConfig& config) {
    return actionstring::ActionSegmenter::check(model, config.segmenter) == Status::ok &&
           actionstring::StringSampler::settings_ok(model.string_period_us, config.max_gap_us,
                                                    config.max_backward_us) &&
           Annotator::required_bytes(model, config) != actionstring::unsatisfiable_bytes && config.min_action_us >= 0 &&
           config.min_action_us <= actionstring::max_settle_delay_us && config.label_lead_us >= 0 &&
           config.label_lead_us <= actionstring::max_settle_delay_us && up_ok(model, config.up) &&
           config.max_pose_speed >= 0.0f;
}

void set_model(actionstring_model* handle, const ModelView& view, const char* checksum) {
    Model* model = new (handle) Model();
    model->view = view;
    std::strncpy(model->checksum, checksum, sizeof model->checksum - 1);
    model->self = model;
    model->magic = kModelMagic;
}

// Restarts a state's stream with another config of its model, checked first,
// so a refused config leaves the state as it was.
actionstring_status reconfigure(State& state, const AnnotatorConfig& config) {
    const ModelView& model = state.model->view;
    if (!config_ok(model, config)) return ACTIONSTRING_INVALID_ARGUMENT;
    const std::size_t room = state.total - kHeaderBytes - kGuardBytes;
    if (Annotator::required_bytes(model, config) > room) return ACTIONSTRING_STORAGE_TOO_SMALL;
    return code(state.annotator.init(model, config, reinterpret_cast<unsigned char*>(&state) + kHeaderBytes, room));
}

// The state's config with `change` applied, then reconfigure(): one setting's setter.
template <typename Change>
actionstring_status change_config(actionstring_state* handle, Change change) {
    State* state = live(handle);
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    AnnotatorConfig config = state->annotator.config();
    change(config);
    return reconfigure(*state, config);
}

}  // namespace

extern "C" {

actionstring_status actionstring_model_from_blob(const void* blob, size_t size, actionstring_model* handle) {
    if (handle == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
    reinterpret_cast<Model*>(handle)->magic = 0;
    ModelView view;
    const Status status = actionstring::model_from_blob(blob, size, view);
    if (status != Status::ok) return code(status);
    // The blob's own checksum, as recorded in it (verified by model_from_blob).
    const auto* bytes = static_cast<const unsigned char*>(blob);
    char checksum[40] = "blob-fnv1a64:";
    const std::uint64_t sum = actionstring::detail::blob_u64(bytes + actionstring::detail::blob_checksum_at);
    for (int i = 0; i < 16; ++i) checksum[13 + i] = "0123456789abcdef"[(sum >> (4 * (15 - i))) & 0xFu];
    set_model(handle, view, checksum);
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_model_builtin(actionstring_model* handle) {
    if (handle == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
#if defined(ACTIONSTRING_C_MODEL_HEADER)
    set_model(handle, ACTIONSTRING_C_MODEL_NAMESPACE::kModel, ACTIONSTRING_C_MODEL_NAMESPACE::kModelChecksum);
    return ACTIONSTRING_OK;
#else
    reinterpret_cast<Model*>(handle)->magic = 0;
    return ACTIONSTRING_INVALID_ARGUMENT;
#endif
}

uint32_t actionstring_model_joint_count(const actionstring_model* handle) {
    const Model* model = checked_model(handle);
    return model == nullptr ? 0u : model->view.joint_count;
}

const char* actionstring_model_joint_name(const actionstring_model* handle, uint32_t joint) {
    const Model* model = checked_model(handle);
    if (model == nullptr || joint >= model->view.joint_count || !model->view.joint_names.present()) return "";
    return model->view.joint_names[joint];
}

uint32_t actionstring_model_label_count(const actionstring_model* handle) {
    const Model* model = checked_model(handle);
    return model == nullptr ? 0u : model->view.label_count;
}

const char* actionstring_model_label_name(const actionstring_model* handle, int32_t label) {
    const Model* model = checked_model(handle);
    if (model == nullptr || label < 0 || static_cast<uint32_t>(label) >= model->view.label_count) return "unknown";
    return model->view.label_names[static_cast<std::size_t>(label)];
}

const char* actionstring_version(void) { return actionstring::version_string(); }

const char* actionstring_model_checksum(const actionstring_model* handle) {
    const Model* model = checked_model(handle);
    return model == nullptr ? "" : model->checksum;
}

actionstring_status actionstring_default_config(const actionstring_model* handle, actionstring_config* config) {
    const Model* model = checked_model(handle);
    if (model == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (config == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
    const AnnotatorConfig c = actionstring::annotator_config(model->view);
    config->online = actionstring_model_online_settings(handle);
    config->max_gap_us = c.max_gap_us;
    config->max_backward_us = c.max_backward_us;
    config->window_rule = c.window_rule ? 1 : 0;
    config->min_action_us = c.min_action_us;
    config->spread_work = c.spread_work ? 1 : 0;
    config->label_lead_us = c.label_lead_us;
    for (int a = 0; a < 3; ++a) config->up[a] = c.up[a];
    config->max_pose_speed = c.max_pose_speed;
    return ACTIONSTRING_OK;
}

size_t actionstring_state_size(const actionstring_model* handle, const actionstring_config* c) {
    const Model* model = checked_model(handle);
    if (model == nullptr) return 0;
    const AnnotatorConfig config = to_config(model->view, c);
    if (!config_ok(model->view, config)) return 0;
    return kHeaderBytes + Annotator::required_bytes(model->view, config) + kGuardBytes;
}

size_t actionstring_state_alignment(void) { return actionstring::state_alignment; }

actionstring_status actionstring_init(const actionstring_model* handle, const actionstring_config* c, void* memory,
                                      size_t size, actionstring_state** out) {
    if (out != nullptr) *out = nullptr;
    const Model* model = checked_model(handle);
    if (model == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (out == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
    const AnnotatorConfig config = to_config(model->view, c);
    if (!config_ok(model->view, config)) return ACTIONSTRING_INVALID_ARGUMENT;
    const std::size_t needed = kHeaderBytes + Annotator::required_bytes(model->view, config) + kGuardBytes;
    if (memory == nullptr || size < needed ||
        reinterpret_cast<std::uintptr_t>(memory) % actionstring::state_alignment != 0)
        return ACTIONSTRING_STORAGE_TOO_SMALL;
    auto* state = new (memory) State();
    auto* bytes = static_cast<unsigned char*>(memory);
    const Status status =
        state->annotator.init(model->view, config, bytes + kHeaderBytes, size - kHeaderBytes - kGuardBytes);
    if (status != Status::ok) return code(status);
    seal(*state, model, size, kStateMagic);
    *out = reinterpret_cast<actionstring_state*>(state);
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_push_frame(actionstring_state* handle, int64_t time_us, const float* positions,
                                            size_t position_count, actionstring_frame_result* result) {
    actionstring_frame_result out{ACTIONSTRING_OK, 0, 0, 0, 0, 0};
    State* state = live(handle);
    if (state == nullptr) out.status = ACTIONSTRING_NOT_INITIALIZED;
    else if (positions == nullptr || position_count != static_cast<size_t>(state->model->view.joint_count) * 3u)
        out.status = ACTIONSTRING_INVALID_ARGUMENT;
    else {
        const actionstring::FrameResult frame = state->annotator.push_frame(time_us, positions);
        out.status = code(frame.status);
        out.characters = frame.characters;
        out.windows_completed = frame.windows_completed;
        out.characters_settled = frame.characters_settled;
        out.events = frame.events;
        out.characters_flushed = frame.characters_flushed;
    }
    if (result != nullptr) *result = out;
    return out.status;
}

actionstring_status actionstring_event_at(const actionstring_state* handle, uint32_t index, actionstring_event* event) {
    const State* state = live(handle);
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (event == nullptr || index >= state->annotator.event_count()) return ACTIONSTRING_INVALID_ARGUMENT;
    const actionstring::ActionEvent& e = state->annotator.event(index);
    event->started = e.kind == actionstring::ActionEvent::Kind::started ? 1 : 0;
    event->label = static_cast<int32_t>(e.label);
    event->start_time_us = e.start_time_us;
    event->end_time_us = e.end_time_us;
    event->first_character = static_cast<int64_t>(e.first_character);
    event->last_character = static_cast<int64_t>(e.last_character);
    event->confidence = e.confidence;
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_flush(actionstring_state* handle, uint32_t* events) {
    State* state = live(handle);
    if (events != nullptr) *events = 0;
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    const std::uint32_t count = state->annotator.flush();
    if (events != nullptr) *events = count;
    return ACTIONSTRING_OK;
}

uint32_t actionstring_flushed_count(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? 0u : state->annotator.flushed_characters();
}

int32_t actionstring_flushed_label(const actionstring_state* handle, uint32_t index) {
    const State* state = live(handle);
    if (state == nullptr) return -1;
    const actionstring::LabelId label = state->annotator.flushed_label(index);
    return label == actionstring::unknown_label ? -1 : static_cast<int32_t>(label);
}

int64_t actionstring_flushed_label_time_us(const actionstring_state* handle, uint32_t index) {
    const State* state = live(handle);
    if (state == nullptr || index >= state->annotator.flushed_characters()) return 0;
    return state->annotator.flushed_label_time_us(index);
}

actionstring_status actionstring_finish_work(actionstring_state* handle, actionstring_frame_result* result) {
    State* state = live(handle);
    actionstring_frame_result out{};
    if (state == nullptr) out.status = ACTIONSTRING_NOT_INITIALIZED;
    else {
        const actionstring::FrameResult frame = state->annotator.finish_work();
        out.status = code(frame.status);
        out.characters_settled = frame.characters_settled;
        out.events = frame.events;
    }
    if (result != nullptr) *result = out;
    return out.status;
}

actionstring_status actionstring_reset(actionstring_state* handle) {
    State* state = live(handle);
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    state->annotator.reset();
    return ACTIONSTRING_OK;
}

actionstring_online_settings actionstring_model_online_settings(const actionstring_model* handle) {
    const Model* model = checked_model(handle);
    if (model == nullptr) return actionstring_online_settings{0, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0, 0.0f};
    return to_settings(actionstring::segmenter_config(model->view));
}

actionstring_status actionstring_set_online_settings(actionstring_state* handle,
                                                     const actionstring_online_settings* settings) {
    State* state = live(handle);
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (settings == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
    AnnotatorConfig config = state->annotator.config();
    config.segmenter = from_settings(*settings);
    return reconfigure(*state, config);
}

actionstring_status actionstring_set_min_action(actionstring_state* handle, int64_t min_action_us) {
    return change_config(handle, [&](AnnotatorConfig& config) { config.min_action_us = min_action_us; });
}

actionstring_status actionstring_set_label_lead(actionstring_state* handle, int64_t label_lead_us) {
    return change_config(handle, [&](AnnotatorConfig& config) { config.label_lead_us = label_lead_us; });
}

actionstring_status actionstring_set_up_direction(actionstring_state* handle, float x, float y, float z) {
    return change_config(handle, [&](AnnotatorConfig& config) {
        config.up[0] = x;
        config.up[1] = y;
        config.up[2] = z;
    });
}

int32_t actionstring_label(const actionstring_state* handle) {
    const State* state = live(handle);
    if (state == nullptr || state->annotator.label() == actionstring::unknown_label) return -1;
    return static_cast<int32_t>(state->annotator.label());
}

int32_t actionstring_live_label(const actionstring_state* handle) {
    const State* state = live(handle);
    if (state == nullptr || state->annotator.live_label() == actionstring::unknown_label) return -1;
    return static_cast<int32_t>(state->annotator.live_label());
}

float actionstring_live_margin(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? 0.0f : state->annotator.live_margin();
}

int64_t actionstring_settled_character(const actionstring_state* handle) {
    const State* state = live(handle);
    if (state == nullptr || !state->annotator.has_settled()) return -1;
    return static_cast<int64_t>(state->annotator.settled_character());
}

int32_t actionstring_settled_label(const actionstring_state* handle, int64_t character) {
    const State* state = live(handle);
    if (state == nullptr || character < 0) return -1;
    const actionstring::LabelId label = state->annotator.settled_label(static_cast<std::uint64_t>(character));
    return label == actionstring::unknown_label ? -1 : static_cast<int32_t>(label);
}

int64_t actionstring_label_time_us(const actionstring_state* handle, int64_t character) {
    const State* state = live(handle);
    if (state == nullptr || character < 0) return 0;
    return state->annotator.label_time_us(static_cast<std::uint64_t>(character));
}

float actionstring_confidence(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? 0.0f : state->annotator.confidence();
}

const char* actionstring_label_name(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? "unknown" : state->annotator.label_name();
}

const actionstring_model* actionstring_state_model(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? nullptr : reinterpret_cast<const actionstring_model*>(state->model);
}

size_t actionstring_clip_size(const actionstring_model* handle, uint32_t max_characters) {
    const Model* model = checked_model(handle);
    return model == nullptr ? 0 : clip_bytes(model->view, max_characters);
}

actionstring_status actionstring_clip_init(const actionstring_model* handle, uint32_t max_characters, void* memory,
                                           size_t size, actionstring_clip** out) {
    if (out != nullptr) *out = nullptr;
    const Model* model = checked_model(handle);
    if (model == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (out == nullptr || max_characters == 0) return ACTIONSTRING_INVALID_ARGUMENT;
    const std::size_t needed = clip_bytes(model->view, max_characters);
    if (needed == 0 || memory == nullptr || size < needed ||
        reinterpret_cast<std::uintptr_t>(memory) % actionstring::state_alignment != 0)
        return ACTIONSTRING_STORAGE_TOO_SMALL;
    auto* clip = new (memory) ClipState();
    auto* bytes = static_cast<unsigned char*>(memory);
    const Status status = clip->recorder.init(model->view, max_characters, actionstring::EncoderConfig{},
                                              bytes + kClipHeaderBytes, size - kClipHeaderBytes - kGuardBytes);
    if (status != Status::ok) return code(status);
    seal(*clip, model, size, kClipMagic);
    *out = reinterpret_cast<actionstring_clip*>(clip);
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_clip_push_frame(actionstring_clip* handle, int64_t time_us, const float* positions,
                                                 size_t position_count) {
    ClipState* clip = live_clip(handle);
    if (clip == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (positions == nullptr || position_count != static_cast<size_t>(clip->model->view.joint_count) * 3u)
        return ACTIONSTRING_INVALID_ARGUMENT;
    return code(clip->recorder.push_frame(time_us, positions));
}

uint32_t actionstring_clip_length(const actionstring_clip* handle) {
    const ClipState* clip = checked_clip(handle);
    return clip == nullptr ? 0u : static_cast<uint32_t>(clip->recorder.length());
}

actionstring_status actionstring_clip_classify(actionstring_clip* handle, int32_t* label, float* confidence) {
    if (label != nullptr) *label = -1;
    if (confidence != nullptr) *confidence = 0.0f;
    ClipState* clip = live_clip(handle);
    if (clip == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    const actionstring::Classification c = clip->recorder.classify();
    if (c.label == actionstring::unknown_label) return ACTIONSTRING_OK;
    if (label != nullptr) *label = static_cast<int32_t>(c.label);
    if (confidence != nullptr) *confidence = c.confidence;
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_clip_label_distances(actionstring_clip* handle, float* distances, size_t count) {
    ClipState* clip = live_clip(handle);
    if (clip == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (distances == nullptr || count < clip->model->view.label_count) return ACTIONSTRING_INVALID_ARGUMENT;
    clip->recorder.label_distances(distances);
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_clip_reset(actionstring_clip* handle) {
    ClipState* clip = live_clip(handle);
    if (clip == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    clip->recorder.reset();
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_clip_set_up_direction(actionstring_clip* handle, float x, float y, float z) {
    ClipState* clip = live_clip(handle);
    if (clip == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    actionstring::EncoderConfig config;
    config.up[0] = x;
    config.up[1] = y;
    config.up[2] = z;
    // Checked first, so a refused direction leaves the recorder as it was; then set up
    // again in its own memory, which the same model and capacity fit as before.
    if (!up_ok(clip->model->view, config.up)) return ACTIONSTRING_INVALID_ARGUMENT;
    auto* bytes = reinterpret_cast<unsigned char*>(clip);
    return code(clip->recorder.init(clip->model->view, clip->recorder.capacity(), config, bytes + kClipHeaderBytes,
                                    clip->total - kClipHeaderBytes - kGuardBytes));
}

const char* actionstring_status_name(actionstring_status status) {
    if (status < 0 || status > ACTIONSTRING_STORAGE_TOO_SMALL) return "unknown_status";
    return actionstring::status_name(static_cast<Status>(status));
}

}  // extern "C"
