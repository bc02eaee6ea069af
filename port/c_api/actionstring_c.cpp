// actionstring C API over the runtime and one generated model header.
#define ACTIONSTRING_C_BUILDING
#include "actionstring_c.h"

#include <cstdint>
#include <new>

#include "actionstring/annotator.hpp"
#include ACTIONSTRING_C_MODEL_HEADER

namespace {

namespace model = ACTIONSTRING_C_MODEL_NAMESPACE;
using actionstring::Annotator;

// Distinguish a state set up by actionstring_init() from stray memory: a
// magic word, the state's own address (memory filled with the magic, or a
// state copied or overwritten after init, does not hold it) and a closing
// magic word after the annotator (an overrun from the memory before it).
constexpr std::uint32_t kMagic = 0x41535452u;     // "ASTR"
constexpr std::uint32_t kEndMagic = 0x52545341u;  // "RTSA"

struct State {
    std::uint32_t magic = kMagic;
    const void* self = nullptr;
    Annotator annotator;
    actionstring::StateBuffer<model::kAnnotatorWithWindowsBytes> storage;
    std::uint32_t end_magic = kEndMagic;
};

static_assert(ACTIONSTRING_OK == static_cast<int>(actionstring::Status::ok), "status values match");
static_assert(ACTIONSTRING_TIME_WENT_BACKWARDS == static_cast<int>(actionstring::Status::time_went_backwards),
              "status values match");
static_assert(ACTIONSTRING_NOT_INITIALIZED == static_cast<int>(actionstring::Status::not_initialized),
              "status values match");

actionstring_status code(actionstring::Status status) { return static_cast<actionstring_status>(status); }

// The state behind a handle, or null when the handle is not one
// actionstring_init() returned (misaligned, never initialised, overwritten).
const State* checked(const void* handle) {
    if (handle == nullptr || reinterpret_cast<std::uintptr_t>(handle) % alignof(State) != 0) return nullptr;
    const auto* state = static_cast<const State*>(handle);
    if (state->magic != kMagic || state->self != state || state->end_magic != kEndMagic) return nullptr;
    return state;
}
State* live(actionstring_state* handle) { return const_cast<State*>(checked(handle)); }
const State* live(const actionstring_state* handle) { return checked(handle); }

}  // namespace

extern "C" {

size_t actionstring_state_size(void) { return sizeof(State); }
size_t actionstring_state_alignment(void) { return alignof(State); }

actionstring_status actionstring_init(void* memory, size_t size, actionstring_state** handle) {
    if (handle != nullptr) *handle = nullptr;
    if (memory == nullptr || handle == nullptr || size < sizeof(State) ||
        reinterpret_cast<std::uintptr_t>(memory) % alignof(State) != 0)
        return ACTIONSTRING_INVALID_ARGUMENT;
    auto* state = new (memory) State();
    actionstring::AnnotatorConfig config = actionstring::annotator_config(model::kModel);
    config.window_rule = true;
    const actionstring::Status status =
        state->annotator.init(model::kModel, config, state->storage.data(), state->storage.size());
    if (status != actionstring::Status::ok) {
        state->magic = 0;
        return code(status);
    }
    state->self = state;
    *handle = reinterpret_cast<actionstring_state*>(state);
    return ACTIONSTRING_OK;
}

actionstring_status actionstring_push_frame(actionstring_state* handle, int64_t time_us, const float* positions,
                                            size_t position_count, actionstring_frame_result* result) {
    actionstring_frame_result out{ACTIONSTRING_OK, 0, 0, 0};
    State* state = live(handle);
    if (state == nullptr) out.status = ACTIONSTRING_NOT_INITIALIZED;
    else if (positions == nullptr || position_count != static_cast<size_t>(model::kModel.joint_count) * 3u)
        out.status = ACTIONSTRING_INVALID_ARGUMENT;
    else {
        const actionstring::FrameResult frame = state->annotator.push_frame(time_us, positions);
        out.status = code(frame.status);
        out.characters = frame.characters;
        out.windows_completed = frame.windows_completed;
        out.characters_settled = frame.characters_settled;
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

actionstring_online_settings actionstring_model_online_settings(void) {
    const actionstring::SegmenterConfig c = actionstring::segmenter_config(model::kModel);
    return actionstring_online_settings{c.settle_delay_us, c.segment_penalty, c.stay_penalty, c.skip_penalty,
                                        c.unknown_cost};
}

actionstring_status actionstring_set_online_settings(actionstring_state* handle,
                                                     const actionstring_online_settings* settings) {
    State* state = live(handle);
    if (state == nullptr) return ACTIONSTRING_NOT_INITIALIZED;
    if (settings == nullptr) return ACTIONSTRING_INVALID_ARGUMENT;
    actionstring::AnnotatorConfig config = actionstring::annotator_config(model::kModel);
    config.window_rule = true;
    config.segmenter.settle_delay_us = settings->settle_delay_us;
    config.segmenter.segment_penalty = settings->segment_penalty;
    config.segmenter.stay_penalty = settings->stay_penalty;
    config.segmenter.skip_penalty = settings->skip_penalty;
    config.segmenter.unknown_cost = settings->unknown_cost;
    // Checked first, so a refused setting leaves the state as it was.
    if (actionstring::ActionSegmenter::check(model::kModel, config.segmenter) != actionstring::Status::ok ||
        actionstring::Annotator::required_bytes(model::kModel, config) > state->storage.size())
        return ACTIONSTRING_INVALID_ARGUMENT;
    return code(state->annotator.init(model::kModel, config, state->storage.data(), state->storage.size()));
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

float actionstring_confidence(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? 0.0f : state->annotator.confidence();
}

const char* actionstring_label_name(const actionstring_state* handle) {
    const State* state = live(handle);
    return state == nullptr ? "unknown" : state->annotator.label_name();
}

uint32_t actionstring_joint_count(void) { return model::kModel.joint_count; }
uint32_t actionstring_label_count(void) { return model::kModel.label_count; }

const char* actionstring_label_name_of(int32_t label) {
    if (label < 0 || static_cast<uint32_t>(label) >= model::kModel.label_count) return "unknown";
    return model::kModel.label_names[static_cast<std::size_t>(label)];
}

const char* actionstring_model_checksum(void) { return model::kModelChecksum; }

const char* actionstring_status_name(actionstring_status status) {
    if (status < 0 || status > ACTIONSTRING_NOT_INITIALIZED) return "unknown_status";
    return actionstring::status_name(static_cast<actionstring::Status>(status));
}

}  // extern "C"
