/* The C API from C: contract checks on a synthetic stream, then (given a
 * stream file written by `actionstring stream-table --text`) a real recording,
 * printing each change of the settled label in the replay firmware's format so
 * port/firmware/run_replay.sh can compare it with the C++ build. Given blobs
 * (`actionstring codegen MODEL --blob FILE`), loads each at run time and runs
 * them all at once.
 *   test_c_api [--blob FILE]... [STREAM.txt] */
#include <math.h>
#include <stdalign.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "actionstring_c.h"

static int failures = 0;
#define CHECK(condition)                                                                  \
    do {                                                                                  \
        if (!(condition)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
            ++failures;                                                                   \
        }                                                                                 \
    } while (0)

/* Room for a state wherever the platform's strictest alignment suffices. */
static alignas(16) unsigned char state_memory[256 * 1024];

enum { kMaxJoints = 64 };

/* A standing skeleton swaying slowly: every joint offset from a hip centre. */
static void synthetic_frame(uint32_t joints, int frame, float* xyz) {
    const float sway = 0.05f * sinf(0.05f * (float)frame);
    for (uint32_t j = 0; j < joints; ++j) {
        xyz[3 * j + 0] = 0.1f * (float)(j % 5) - 0.2f + sway;
        xyz[3 * j + 1] = 0.9f + 0.05f * (float)(j % 7) - 0.15f;
        xyz[3 * j + 2] = 0.08f * (float)(j % 3) + 0.02f * (float)(j % 11);
    }
}

static void contract_checks(const actionstring_model* model) {
    actionstring_config config;
    CHECK(actionstring_default_config(model, &config) == ACTIONSTRING_OK);
    config.window_rule = 1; /* both rules, so the window label is checked too */
    const size_t size = actionstring_state_size(model, &config);
    const size_t alignment = actionstring_state_alignment();
    const uint32_t joints = actionstring_model_joint_count(model);
    actionstring_state* state = NULL;
    float frame[3 * kMaxJoints];
    actionstring_frame_result result;

    CHECK(size > 0 && size <= sizeof state_memory);
    CHECK(actionstring_state_size(model, NULL) < size); /* the segmenter alone needs less */
    CHECK(alignment == 16);
    CHECK(joints > 0 && joints <= kMaxJoints);
    CHECK(actionstring_model_label_count(model) > 0);
    CHECK(strncmp(actionstring_model_checksum(model), "fnv1a64:", 8) == 0);
    CHECK(strcmp(actionstring_model_joint_name(model, 0), "root") == 0);
    CHECK(strcmp(actionstring_model_joint_name(model, joints), "") == 0);

    /* Bad set-up never yields a state. */
    CHECK(actionstring_init(model, &config, NULL, size, &state) == ACTIONSTRING_STORAGE_TOO_SMALL && state == NULL);
    CHECK(actionstring_init(model, &config, state_memory, size - 1, &state) == ACTIONSTRING_STORAGE_TOO_SMALL &&
          state == NULL);
    CHECK(actionstring_init(model, &config, state_memory, size, NULL) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_init(NULL, &config, state_memory, size, &state) == ACTIONSTRING_NOT_INITIALIZED &&
          state == NULL);
    CHECK(actionstring_init(model, &config, state_memory + 1, size, &state) == ACTIONSTRING_STORAGE_TOO_SMALL &&
          state == NULL);
    actionstring_config bad_config = config;
    bad_config.online.segment_penalty = -1.0f;
    CHECK(actionstring_state_size(model, &bad_config) == 0);
    CHECK(actionstring_init(model, &bad_config, state_memory, size, &state) == ACTIONSTRING_INVALID_ARGUMENT);

    /* A model handle that never went through this API is refused. */
    actionstring_model stray;
    memset(&stray, 0x4D, sizeof stray);
    CHECK(actionstring_model_joint_count(&stray) == 0);
    CHECK(actionstring_state_size(&stray, NULL) == 0);
    CHECK(strcmp(actionstring_model_label_name(&stray, 0), "unknown") == 0);

    /* Memory that never went through init is refused, not trusted. */
    memset(state_memory, 0xAB, sizeof state_memory);
    synthetic_frame(joints, 0, frame);
    CHECK(actionstring_push_frame((actionstring_state*)(void*)state_memory, 0, frame, 3 * joints, &result) ==
          ACTIONSTRING_NOT_INITIALIZED);
    CHECK(result.status == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_push_frame(NULL, 0, frame, 3 * joints, NULL) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_reset(NULL) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_label(NULL) == -1);
    CHECK(strcmp(actionstring_label_name(NULL), "unknown") == 0);

    /* Memory full of the magic word is not a state. */
    for (size_t i = 0; i + 4 <= sizeof state_memory; i += 4) {
        const uint32_t magic = 0x41535452u; /* the state magic, in this machine's byte order */
        memcpy(state_memory + i, &magic, 4);
    }
    CHECK(actionstring_push_frame((actionstring_state*)(void*)state_memory, 0, frame, 3 * joints, &result) ==
          ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_reset((actionstring_state*)(void*)state_memory) == ACTIONSTRING_NOT_INITIALIZED);

    /* A real state copied elsewhere, overwritten after init, overrun at its end,
     * or reached through a misaligned handle is refused too. */
    static alignas(16) unsigned char copy_memory[sizeof state_memory];
    CHECK(actionstring_init(model, &config, state_memory, size, &state) == ACTIONSTRING_OK && state != NULL);
    CHECK(actionstring_state_model(state) == model);
    memcpy(copy_memory, state_memory, size);
    CHECK(actionstring_push_frame((actionstring_state*)(void*)copy_memory, 0, frame, 3 * joints, NULL) ==
          ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_push_frame((actionstring_state*)(void*)(state_memory + 1), 0, frame, 3 * joints, NULL) ==
          ACTIONSTRING_NOT_INITIALIZED);
    memset(state_memory + 4, 0x5A, size - 4); /* everything after the magic */
    CHECK(actionstring_push_frame(state, 0, frame, 3 * joints, NULL) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_init(model, &config, state_memory, size, &state) == ACTIONSTRING_OK && state != NULL);
    memset(state_memory + size - 16, 0, 16); /* an overrun into the end of a state */
    CHECK(actionstring_push_frame(state, 0, frame, 3 * joints, NULL) == ACTIONSTRING_NOT_INITIALIZED);

    CHECK(actionstring_init(model, &config, state_memory, size, &state) == ACTIONSTRING_OK && state != NULL);
    CHECK(actionstring_label(state) == -1);
    CHECK(strcmp(actionstring_label_name(state), "unknown") == 0);
    CHECK(actionstring_confidence(state) == 0.0f);

    /* The model's online settings, and replacing them: a bad one changes nothing. */
    const actionstring_online_settings own = actionstring_model_online_settings(model);
    CHECK(own.settle_delay_us > 0 && own.segment_penalty >= 0.0f);
    actionstring_online_settings bad = own;
    bad.vote_weight = -1.0f; /* a negative vote weight is refused */
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    bad = own;
    bad.exemplar_weight = -1.0f; /* and a negative exemplar weight */
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    bad = own;
    bad.segment_penalty = -1.0f;
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    bad = own;
    bad.settle_delay_us = (int64_t)3600 * 1000000; /* an hour: beyond the runtime's 10 minutes */
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    bad = own;
    bad.settle_delay_us = own.settle_delay_us * 8; /* valid, but needs a longer ring than the memory holds */
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_STORAGE_TOO_SMALL);
    CHECK(actionstring_set_online_settings(state, NULL) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_online_settings(NULL, &own) == ACTIONSTRING_NOT_INITIALIZED);
    /* Early settling: checked as the delay is; it needs two more rings than a state sized without it. */
    bad = own;
    bad.settle_stable_us = -1;
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    bad.settle_stable_us = (int64_t)3600 * 1000000;
    CHECK(actionstring_set_online_settings(state, &bad) == ACTIONSTRING_INVALID_ARGUMENT);
    {
        actionstring_config alone = config, early = config;
        alone.online.settle_stable_us = 0;
        early.online.settle_stable_us = own.settle_delay_us / 2;
        const size_t alone_size = actionstring_state_size(model, &alone);
        CHECK(actionstring_state_size(model, &early) > alone_size);
        early.online.settle_stable_us = own.settle_delay_us; /* settles nothing sooner: no more state */
        CHECK(actionstring_state_size(model, &early) == alone_size);
        /* A state sized for the delay alone refuses early settling and keeps its settings. */
        early.online.settle_stable_us = own.settle_delay_us / 2;
        actionstring_state* small = NULL;
        CHECK(actionstring_init(model, &alone, state_memory, alone_size, &small) == ACTIONSTRING_OK && small != NULL);
        CHECK(actionstring_set_online_settings(small, &early.online) == ACTIONSTRING_STORAGE_TOO_SMALL);
        CHECK(actionstring_set_online_settings(small, &alone.online) == ACTIONSTRING_OK);
        CHECK(actionstring_init(model, &config, state_memory, size, &state) == ACTIONSTRING_OK && state != NULL);
        /* A state sized for a model's own early settling takes any other early settling. */
        if (own.settle_stable_us > 0 && own.settle_stable_us < own.settle_delay_us) {
            CHECK(actionstring_state_size(model, &early) == size);
            CHECK(actionstring_set_online_settings(state, &early.online) == ACTIONSTRING_OK);
            CHECK(actionstring_set_online_settings(state, &own) == ACTIONSTRING_OK);
        }
    }
    actionstring_online_settings eager = own;
    eager.settle_delay_us = 1000000;
    eager.unknown_cost = 0.5f;
    eager.vote_weight = 0.25f;
    eager.exemplar_weight = 0.1f; /* no exemplars in this model: accepted, no effect */
    CHECK(actionstring_set_online_settings(state, &eager) == ACTIONSTRING_OK);
    CHECK(actionstring_set_online_settings(state, &own) == ACTIONSTRING_OK);
    /* The events' shortest action: the model's own by default, replaceable, checked. */
    CHECK(config.min_action_us >= 0 && config.min_action_us <= (int64_t)600 * 1000000);
    CHECK(actionstring_set_min_action(state, -1) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_min_action(state, (int64_t)3600 * 1000000) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_min_action(NULL, 500000) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_set_min_action(state, 1000000) == ACTIONSTRING_OK);
    CHECK(actionstring_set_min_action(state, config.min_action_us) == ACTIONSTRING_OK);
    /* The label lead: the model's own by default, replaceable, checked; the stream below runs with 0.25 s. */
    CHECK(config.label_lead_us >= 0 && config.label_lead_us <= (int64_t)600 * 1000000);
    CHECK(actionstring_set_label_lead(state, -1) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_label_lead(state, (int64_t)3600 * 1000000) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_label_lead(NULL, 0) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_set_label_lead(state, 250000) == ACTIONSTRING_OK);
    /* The sensor's up direction: none by default; a direction, or none again; not a direction refused. */
    CHECK(config.up[0] == 0.0f && config.up[1] == 0.0f && config.up[2] == 0.0f);
    CHECK(actionstring_set_up_direction(state, 0.0f, 0.0f, 0.0f) == ACTIONSTRING_OK);
    CHECK(actionstring_set_up_direction(state, 0.1f, 0.9f, 0.2f) == ACTIONSTRING_OK);
    CHECK(actionstring_set_up_direction(state, 1e-9f, 0.0f, 0.0f) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_up_direction(state, NAN, 1.0f, 0.0f) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_set_up_direction(NULL, 0.0f, 1.0f, 0.0f) == ACTIONSTRING_NOT_INITIALIZED);
    {
        actionstring_config tilted = config;
        tilted.up[2] = INFINITY;
        CHECK(actionstring_state_size(model, &tilted) == 0); /* a config init() would refuse */
        tilted.up[2] = 1.0f;
        CHECK(actionstring_state_size(model, &tilted) == actionstring_state_size(model, &config));
    }
    CHECK(actionstring_set_up_direction(state, 0.0f, 0.0f, 0.0f) == ACTIONSTRING_OK);
    /* The jump bound: 3 m/s by default, 0 never restarts the motion, a negative or NaN one refused. */
    CHECK(config.max_pose_speed == 3.0f);
    {
        actionstring_config jumps = config;
        jumps.max_pose_speed = 0.0f;
        CHECK(actionstring_state_size(model, &jumps) == actionstring_state_size(model, &config));
        jumps.max_pose_speed = -1.0f;
        CHECK(actionstring_state_size(model, &jumps) == 0);
        jumps.max_pose_speed = NAN;
        CHECK(actionstring_state_size(model, &jumps) == 0);
    }

    /* Wrong element count or a null frame: rejected before the runtime sees it. */
    CHECK(actionstring_push_frame(state, 0, frame, 3 * joints - 1, NULL) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_push_frame(state, 0, frame, 3 * joints + 3, NULL) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_push_frame(state, 0, NULL, 3 * joints, NULL) == ACTIONSTRING_INVALID_ARGUMENT);

    /* Ten seconds at 60 Hz; one NaN frame, one lost-tracking frame, one frame from the past. */
    uint32_t accepted = 0, characters = 0;
    for (int f = 0; f < 600; ++f) {
        const int64_t time_us = (int64_t)f * 16667;
        synthetic_frame(joints, f, frame);
        if (f == 100) frame[4] = NAN;
        if (f == 200) memset(frame, 0, sizeof(float) * 3 * joints);
        const int64_t stamp = f == 300 ? time_us - 100000 : time_us;
        const actionstring_status status = actionstring_push_frame(state, stamp, frame, 3 * joints, &result);
        CHECK(status == result.status);
        if (f == 100) CHECK(status == ACTIONSTRING_NON_FINITE_INPUT);
        else if (f == 200) CHECK(status == ACTIONSTRING_TRACKING_LOST);
        else if (f == 300) CHECK(status == ACTIONSTRING_TIME_WENT_BACKWARDS);
        else CHECK(status == ACTIONSTRING_OK);
        if (status == ACTIONSTRING_OK) ++accepted;
        characters += result.characters;
        const int32_t label = actionstring_label(state);
        CHECK(label >= -1 && label < (int32_t)actionstring_model_label_count(model));
        const float confidence = actionstring_confidence(state);
        CHECK(confidence >= 0.0f && confidence <= 1.0f);
        CHECK(strcmp(actionstring_label_name(state), actionstring_model_label_name(model, label)) == 0);
        /* A settled character's label applies from its tick less the lead: before this frame by at least the lead. */
        const int64_t settled = actionstring_settled_character(state);
        if (result.characters_settled > 0) {
            CHECK(actionstring_label_time_us(state, settled) <= stamp - 250000);
            if (settled > 0)
                CHECK(actionstring_label_time_us(state, settled) > actionstring_label_time_us(state, settled - 1));
        }
        /* The events' times are label times. */
        for (uint32_t i = 0; i < result.events; ++i) {
            actionstring_event e;
            CHECK(actionstring_event_at(state, i, &e) == ACTIONSTRING_OK);
            CHECK(e.start_time_us == actionstring_label_time_us(state, e.first_character));
            CHECK(e.end_time_us == actionstring_label_time_us(state, e.last_character + 1));
        }
    }
    CHECK(accepted == 597);
    CHECK(characters > 50);                /* about 12 characters per second of accepted frames */
    CHECK(actionstring_label(state) >= 0); /* windows completed: a label was chosen */
    CHECK(actionstring_live_label(state) >= 0);
    CHECK(actionstring_live_margin(state) >= 0.0f); /* a number, never NaN */
    CHECK(actionstring_live_margin(NULL) == 0.0f);
    CHECK(actionstring_settled_character(state) >= 0);
    CHECK(actionstring_settled_label(state, actionstring_settled_character(state)) >= -1);
    CHECK(actionstring_settled_label(state, -5) == -1);
    CHECK(actionstring_settled_label(NULL, 0) == -1);
    CHECK(actionstring_settled_character(NULL) == -1);
    CHECK(actionstring_label_time_us(NULL, 0) == 0);
    CHECK(actionstring_label_time_us(state, -1) == 0);

    /* Events: pairs, started before ended; the flush ends a running action. */
    actionstring_event event;
    CHECK(actionstring_event_at(state, 99, &event) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_event_at(NULL, 0, &event) == ACTIONSTRING_NOT_INITIALIZED);
    /* A frame 10 s after the last restarts the stream: the ended stream's unsettled tail is
     * flushed, labels final, times in order on its clock (the lead before each tick). */
    const int64_t last_settled = actionstring_settled_character(state);
    const int64_t last_settled_time = actionstring_label_time_us(state, last_settled);
    synthetic_frame(joints, 0, frame);
    CHECK(actionstring_push_frame(state, (int64_t)20 * 1000000, frame, 3 * joints, &result) ==
          ACTIONSTRING_STREAM_RESTARTED);
    CHECK(result.characters_flushed > 0);
    CHECK(result.characters_flushed == actionstring_flushed_count(state));
    CHECK(actionstring_flushed_count(NULL) == 0);
    CHECK(actionstring_flushed_label(NULL, 0) == -1);
    CHECK(actionstring_flushed_label(state, result.characters_flushed) == -1);
    CHECK(actionstring_flushed_label_time_us(state, result.characters_flushed) == 0);
    /* The flushed characters are those after the last one reported settled. */
    CHECK(actionstring_flushed_label_time_us(state, 0) > last_settled_time);
    for (uint32_t i = 0; i < result.characters_flushed; ++i) {
        const int32_t label = actionstring_flushed_label(state, i);
        CHECK(label >= -1 && label < (int32_t)actionstring_model_label_count(model));
        CHECK(actionstring_flushed_label_time_us(state, i) < (int64_t)10 * 1000000);
        if (i > 0)
            CHECK(actionstring_flushed_label_time_us(state, i) > actionstring_flushed_label_time_us(state, i - 1));
    }
    CHECK(last_settled >= 0);
    /* The next frame starts afresh. */
    CHECK(actionstring_push_frame(state, (int64_t)20 * 1000000 + 16667, frame, 3 * joints, &result) == ACTIONSTRING_OK);
    CHECK(result.characters_flushed == 0 && actionstring_flushed_count(state) == 0);
    uint32_t flushed = 99;
    CHECK(actionstring_flush(state, &flushed) == ACTIONSTRING_OK);
    CHECK(actionstring_flushed_count(state) >= 1); /* the new stream's first characters */
    CHECK(flushed <= 16);
    for (uint32_t i = 0; i < flushed; ++i) {
        CHECK(actionstring_event_at(state, i, &event) == ACTIONSTRING_OK);
        CHECK(event.label >= 0 && event.label < (int32_t)actionstring_model_label_count(model));
        CHECK(event.end_time_us >= event.start_time_us);
        CHECK(event.confidence >= 0.0f && event.confidence <= 1.0f);
    }
    if (flushed > 0) {
        CHECK(actionstring_event_at(state, flushed - 1, &event) == ACTIONSTRING_OK);
        CHECK(event.started == 0); /* the last event of a flush ends the action */
    }
    CHECK(actionstring_flush(NULL, &flushed) == ACTIONSTRING_NOT_INITIALIZED && flushed == 0);

    CHECK(actionstring_reset(state) == ACTIONSTRING_OK);
    CHECK(actionstring_label(state) == -1);
    CHECK(actionstring_live_label(state) == -1);
    CHECK(actionstring_live_margin(state) == 0.0f);
    CHECK(actionstring_settled_character(state) == -1);
    CHECK(strcmp(actionstring_status_name(ACTIONSTRING_TRACKING_LOST), "tracking_lost") == 0);
    CHECK(strcmp(actionstring_status_name(ACTIONSTRING_STORAGE_TOO_SMALL), "storage_too_small") == 0);
    CHECK(strcmp(actionstring_status_name(12345), "unknown_status") == 0);
    CHECK(strcmp(actionstring_model_label_name(model, -1), "unknown") == 0);
    CHECK(strcmp(actionstring_model_label_name(model, (int32_t)actionstring_model_label_count(model)), "unknown") == 0);
}

/* config.spread_work: the same settled labels as without, each reported no
 * earlier, some later; actionstring_finish_work() finishes the last. */
static void spread_checks(const actionstring_model* model) {
    enum { kFrames = 600, kMaxChars = 200 };
    actionstring_config plain, spread;
    CHECK(actionstring_default_config(model, &plain) == ACTIONSTRING_OK);
    CHECK(plain.spread_work == 0);
    spread = plain;
    spread.spread_work = 1;
    const size_t size = actionstring_state_size(model, &plain);
    /* Spread, the state also queues two poses (the encoder's work waits for later frames). */
    const size_t spread_size = actionstring_state_size(model, &spread);
    const size_t second = (size + 15u) & ~(size_t)15u;
    CHECK(size > 0 && spread_size > size && second + spread_size <= sizeof state_memory);
    actionstring_state *a = NULL, *b = NULL;
    CHECK(actionstring_init(model, &plain, state_memory, size, &a) == ACTIONSTRING_OK);
    CHECK(actionstring_init(model, &spread, state_memory + second, spread_size - 1, &b) ==
          ACTIONSTRING_STORAGE_TOO_SMALL);
    CHECK(actionstring_init(model, &spread, state_memory + second, spread_size, &b) == ACTIONSTRING_OK);
    const uint32_t joints = actionstring_model_joint_count(model);
    float frame[3 * kMaxJoints];
    int32_t labels_a[kMaxChars], labels_b[kMaxChars];
    int settled_at_a[kMaxChars], settled_at_b[kMaxChars];
    for (int i = 0; i < kMaxChars; ++i) labels_a[i] = labels_b[i] = -2, settled_at_a[i] = settled_at_b[i] = -1;
    actionstring_frame_result ra, rb;
    for (int f = 0; f < kFrames; ++f) { /* ten seconds at 60 Hz */
        synthetic_frame(joints, f, frame);
        CHECK(actionstring_push_frame(a, (int64_t)f * 16667, frame, 3 * joints, &ra) == ACTIONSTRING_OK);
        CHECK(actionstring_push_frame(b, (int64_t)f * 16667, frame, 3 * joints, &rb) == ACTIONSTRING_OK);
        CHECK(ra.characters == rb.characters);
        for (uint32_t k = 0; k < ra.characters_settled; ++k) {
            const int64_t c = actionstring_settled_character(a) - (int64_t)(ra.characters_settled - 1 - k);
            if (c >= 0 && c < kMaxChars) labels_a[c] = actionstring_settled_label(a, c), settled_at_a[c] = f;
        }
        for (uint32_t k = 0; k < rb.characters_settled; ++k) {
            const int64_t c = actionstring_settled_character(b) - (int64_t)(rb.characters_settled - 1 - k);
            if (c >= 0 && c < kMaxChars) labels_b[c] = actionstring_settled_label(b, c), settled_at_b[c] = f;
        }
    }
    CHECK(actionstring_finish_work(a, &ra) == ACTIONSTRING_OK && ra.characters_settled == 0);
    /* At most the character in progress and one queued. */
    CHECK(actionstring_finish_work(b, &rb) == ACTIONSTRING_OK && rb.characters_settled <= 2);
    for (uint32_t k = 0; k < rb.characters_settled; ++k) {
        const int64_t c = actionstring_settled_character(b) - (int64_t)(rb.characters_settled - 1 - k);
        if (c >= 0 && c < kMaxChars) labels_b[c] = actionstring_settled_label(b, c), settled_at_b[c] = kFrames;
    }
    CHECK(actionstring_settled_character(a) == actionstring_settled_character(b));
    int settled = 0, later = 0;
    for (int c = 0; c < kMaxChars; ++c) {
        CHECK(labels_a[c] == labels_b[c]);
        if (settled_at_a[c] < 0) continue;
        ++settled;
        CHECK(settled_at_b[c] >= settled_at_a[c]);
        later += settled_at_b[c] > settled_at_a[c];
    }
    CHECK(settled > 50);
    CHECK(later * 2 > settled); /* five frames per character: most were spread */
    CHECK(actionstring_finish_work(NULL, &rb) == ACTIONSTRING_NOT_INITIALIZED &&
          rb.status == ACTIONSTRING_NOT_INITIALIZED);
}

/* A blob file in memory aligned to 16 bytes (as the runtime reads it in place). */
static unsigned char* read_blob(const char* path, size_t* size) {
    FILE* file = fopen(path, "rb");
    if (file == NULL) return NULL;
    fseek(file, 0, SEEK_END);
    const long length = ftell(file);
    fseek(file, 0, SEEK_SET);
    unsigned char* bytes = length > 0 ? aligned_alloc(16, ((size_t)length + 15) / 16 * 16) : NULL;
    if (bytes != NULL && fread(bytes, 1, (size_t)length, file) != (size_t)length) {
        free(bytes);
        bytes = NULL;
    }
    fclose(file);
    *size = (size_t)length;
    return bytes;
}

enum { kMaxBlobs = 4 };

/* Models read from blobs at run time, several at once, each with its own state. */
/* Whole clips: a recorder in caller memory, its errors, and a clip labelled as a whole. */
static void clip_checks(const actionstring_model* model) {
    static alignas(16) unsigned char clip_memory[512 * 1024];
    const uint32_t joints = actionstring_model_joint_count(model);
    const int32_t labels = (int32_t)actionstring_model_label_count(model);
    float frame[3 * kMaxJoints];
    actionstring_clip* clip = NULL;
    const size_t size = actionstring_clip_size(model, 64);
    CHECK(size > 0 && size <= sizeof clip_memory);
    CHECK(actionstring_clip_size(model, 128) > size); /* room grows with the characters */
    CHECK(actionstring_clip_size(model, 0) == 0);
    CHECK(actionstring_clip_size(NULL, 64) == 0);
    CHECK(actionstring_clip_size(model, UINT32_MAX) == 0 || actionstring_clip_size(model, UINT32_MAX) > size);
    CHECK(actionstring_clip_init(model, 64, NULL, size, &clip) == ACTIONSTRING_STORAGE_TOO_SMALL && clip == NULL);
    CHECK(actionstring_clip_init(model, 64, clip_memory, size - 1, &clip) == ACTIONSTRING_STORAGE_TOO_SMALL);
    CHECK(actionstring_clip_init(model, 64, clip_memory + 1, size, &clip) == ACTIONSTRING_STORAGE_TOO_SMALL);
    CHECK(actionstring_clip_init(model, 0, clip_memory, size, &clip) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_clip_init(model, 64, clip_memory, size, NULL) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_clip_init(NULL, 64, clip_memory, size, &clip) == ACTIONSTRING_NOT_INITIALIZED);
    int32_t label = 7;
    float confidence = 7.0f;
    CHECK(actionstring_clip_classify(NULL, &label, &confidence) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(label == -1 && confidence == 0.0f);
    CHECK(actionstring_clip_push_frame(NULL, 0, frame, 3 * joints) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_clip_reset(NULL) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_clip_length(NULL) == 0);
    /* A state's handle is not a clip's. */
    actionstring_state* state = NULL;
    CHECK(actionstring_init(model, NULL, state_memory, actionstring_state_size(model, NULL), &state) ==
          ACTIONSTRING_OK);
    CHECK(actionstring_clip_reset((actionstring_clip*)(void*)state) == ACTIONSTRING_NOT_INITIALIZED);

    CHECK(actionstring_clip_init(model, 64, clip_memory, size, &clip) == ACTIONSTRING_OK && clip != NULL);
    CHECK(actionstring_clip_classify(clip, &label, &confidence) == ACTIONSTRING_OK);
    CHECK(label == -1); /* nothing recorded yet */
    CHECK(actionstring_clip_push_frame(clip, 0, frame, 3 * joints - 1) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_clip_push_frame(clip, 0, NULL, 3 * joints) == ACTIONSTRING_INVALID_ARGUMENT);
    /* Two seconds at 60 Hz: characters, and a label or unknown with a confidence in [0, 1]. */
    for (int f = 0; f < 120; ++f) {
        synthetic_frame(joints, f, frame);
        CHECK(actionstring_clip_push_frame(clip, (int64_t)f * 16667, frame, 3 * joints) == ACTIONSTRING_OK);
    }
    const uint32_t length = actionstring_clip_length(clip);
    CHECK(length > 0 && length <= 64);
    CHECK(actionstring_clip_classify(clip, &label, &confidence) == ACTIONSTRING_OK);
    CHECK(label >= -1 && label < labels);
    CHECK(confidence >= 0.0f && confidence <= 1.0f);
    CHECK(label >= 0 || confidence == 0.0f);
    CHECK(actionstring_clip_classify(clip, NULL, NULL) == ACTIONSTRING_OK);
    CHECK(actionstring_clip_length(clip) == length); /* classifying does not end the clip */
    {
        /* Each label's score: the label (when not unknown) is the nearest; too little room writes nothing. */
        float distances[64];
        CHECK(labels > 0 && labels <= 64);
        for (int l = 0; l < 64; ++l) distances[l] = -1.0f;
        CHECK(actionstring_clip_label_distances(clip, distances, (size_t)labels - 1) == ACTIONSTRING_INVALID_ARGUMENT);
        CHECK(distances[0] == -1.0f);
        CHECK(actionstring_clip_label_distances(clip, NULL, (size_t)labels) == ACTIONSTRING_INVALID_ARGUMENT);
        CHECK(actionstring_clip_label_distances(NULL, distances, (size_t)labels) == ACTIONSTRING_NOT_INITIALIZED);
        CHECK(actionstring_clip_label_distances(clip, distances, (size_t)labels) == ACTIONSTRING_OK);
        CHECK(distances[labels] == -1.0f); /* nothing past the labels */
        int32_t nearest = 0;
        for (int32_t l = 0; l < labels; ++l) {
            CHECK(distances[l] >= 0.0f); /* distances and penalties: never negative, never NaN */
            if (distances[l] < distances[nearest]) nearest = l;
        }
        CHECK(label < 0 || label == nearest);
        CHECK(actionstring_clip_length(clip) == length);
    }
    /* The same frames again after a reset: the same clip, the same label. */
    CHECK(actionstring_clip_reset(clip) == ACTIONSTRING_OK);
    CHECK(actionstring_clip_length(clip) == 0);
    for (int f = 0; f < 120; ++f) {
        synthetic_frame(joints, f, frame);
        CHECK(actionstring_clip_push_frame(clip, (int64_t)f * 16667, frame, 3 * joints) == ACTIONSTRING_OK);
    }
    int32_t again = -2;
    float again_confidence = -1.0f;
    CHECK(actionstring_clip_classify(clip, &again, &again_confidence) == ACTIONSTRING_OK);
    CHECK(actionstring_clip_length(clip) == length && again == label && again_confidence == confidence);
    /* The sensor's up direction: the model's own axis, as given, labels the same frames the same;
       a bad one is refused and the recorded clip kept; a good one starts a new clip. */
    CHECK(actionstring_clip_set_up_direction(clip, 0.0f, NAN, 1.0f) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_clip_set_up_direction(clip, 0.0f, 1e-9f, 0.0f) == ACTIONSTRING_INVALID_ARGUMENT);
    CHECK(actionstring_clip_set_up_direction(NULL, 0.0f, 1.0f, 0.0f) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_clip_length(clip) == length);
    {
        float up[3] = {0.0f, 0.0f, 0.0f};
        up[1] = 1.0f; /* the committed models are y-up */
        CHECK(actionstring_clip_set_up_direction(clip, up[0], up[1], up[2]) == ACTIONSTRING_OK);
    }
    CHECK(actionstring_clip_length(clip) == 0);
    for (int f = 0; f < 120; ++f) {
        synthetic_frame(joints, f, frame);
        CHECK(actionstring_clip_push_frame(clip, (int64_t)f * 16667, frame, 3 * joints) == ACTIONSTRING_OK);
    }
    CHECK(actionstring_clip_classify(clip, &again, &again_confidence) == ACTIONSTRING_OK);
    CHECK(actionstring_clip_length(clip) == length && again == label && again_confidence == confidence);
    /* A frame that is not a pose changes nothing. */
    memset(frame, 0, sizeof frame);
    CHECK(actionstring_clip_push_frame(clip, 2100000, frame, 3 * joints) == ACTIONSTRING_TRACKING_LOST);
    CHECK(actionstring_clip_length(clip) == length);
    /* Longer than its room: the clip keeps its beginning and the frame says so. */
    int full = 0;
    for (int f = 0; f < 60 * 30 && !full; ++f) {
        synthetic_frame(joints, f, frame);
        full = actionstring_clip_push_frame(clip, 3000000 + (int64_t)f * 16667, frame, 3 * joints) ==
               ACTIONSTRING_STORAGE_TOO_SMALL;
    }
    CHECK(full);
    CHECK(actionstring_clip_length(clip) == 64);
    /* Overwritten after init, or overrun at its end: refused. */
    memset(clip_memory + size - 16, 0, 16);
    CHECK(actionstring_clip_classify(clip, &label, NULL) == ACTIONSTRING_NOT_INITIALIZED);
    CHECK(actionstring_clip_init(model, 64, clip_memory, size, &clip) == ACTIONSTRING_OK);
    memset(clip_memory, 0, 8);
    CHECK(actionstring_clip_reset(clip) == ACTIONSTRING_NOT_INITIALIZED);
}

static void blob_checks(const char* const* paths, int count) {
    static actionstring_model models[kMaxBlobs];
    static alignas(16) unsigned char memory[kMaxBlobs][128 * 1024];
    unsigned char* blobs[kMaxBlobs] = {0};
    size_t sizes[kMaxBlobs] = {0};
    actionstring_state* states[kMaxBlobs] = {0};
    float frame[3 * kMaxJoints];
    for (int b = 0; b < count; ++b) {
        blobs[b] = read_blob(paths[b], &sizes[b]);
        CHECK(blobs[b] != NULL);
        if (blobs[b] == NULL) return;
        CHECK(actionstring_model_from_blob(blobs[b], sizes[b], &models[b]) == ACTIONSTRING_OK);
        CHECK(strncmp(actionstring_model_checksum(&models[b]), "blob-fnv1a64:", 13) == 0);
        CHECK(actionstring_model_joint_count(&models[b]) > 0 &&
              actionstring_model_joint_count(&models[b]) <= kMaxJoints);
        const size_t size = actionstring_state_size(&models[b], NULL);
        CHECK(size > 0 && size <= sizeof memory[b]);
        CHECK(actionstring_init(&models[b], NULL, memory[b], size, &states[b]) == ACTIONSTRING_OK);
    }
    /* A damaged blob is refused, and so is a misaligned one. */
    if (count > 0) {
        static actionstring_model damaged;
        blobs[0][sizes[0] / 2] ^= 0x10;
        CHECK(actionstring_model_from_blob(blobs[0], sizes[0], &damaged) == ACTIONSTRING_INVALID_MODEL);
        blobs[0][sizes[0] / 2] ^= 0x10;
        CHECK(actionstring_model_from_blob(blobs[0] + 1, sizes[0] - 1, &damaged) == ACTIONSTRING_INVALID_ARGUMENT);
        CHECK(actionstring_model_joint_count(&damaged) == 0);
        CHECK(actionstring_model_from_blob(blobs[0], sizes[0] - 16, &damaged) == ACTIONSTRING_INVALID_MODEL);
    }
    /* Every state fed at once, each with its own model's skeleton. */
    uint32_t labelled[kMaxBlobs] = {0}, events[kMaxBlobs] = {0};
    for (int f = 0; f < 900; ++f)
        for (int b = 0; b < count; ++b) {
            const uint32_t joints = actionstring_model_joint_count(&models[b]);
            synthetic_frame(joints, f + 37 * b, frame);
            actionstring_frame_result result;
            CHECK(actionstring_push_frame(states[b], (int64_t)f * 16667, frame, 3 * joints, &result) ==
                  ACTIONSTRING_OK);
            events[b] += result.events;
            const int32_t live = actionstring_live_label(states[b]);
            CHECK(live >= -1 && live < (int32_t)actionstring_model_label_count(&models[b]));
            if (live >= 0) ++labelled[b];
            /* A frame of another model's skeleton is refused. */
            if (b > 0 && joints != actionstring_model_joint_count(&models[0]))
                CHECK(actionstring_push_frame(states[b], (int64_t)f * 16667 + 1, frame,
                                              3 * actionstring_model_joint_count(&models[0]),
                                              NULL) == ACTIONSTRING_INVALID_ARGUMENT);
        }
    for (int b = 0; b < count; ++b) {
        uint32_t flushed = 0;
        CHECK(actionstring_flush(states[b], &flushed) == ACTIONSTRING_OK);
        events[b] += flushed;
        CHECK(events[b] >= 2 && events[b] % 2 == 0); /* whole actions: a start and an end each */
        CHECK(labelled[b] > 0);
        CHECK(actionstring_state_model(states[b]) == &models[b]);
        printf("blob %s: %u joints, %u labels, state %zu bytes, live label on %u of 900 frames\n", paths[b],
               actionstring_model_joint_count(&models[b]), actionstring_model_label_count(&models[b]),
               actionstring_state_size(&models[b], NULL), labelled[b]);
        free(blobs[b]);
    }
}

/* Each line: time_us, then joints × 3 floats (C99 hex or decimal). */
static int replay_file(const char* path) {
    FILE* file = fopen(path, "r");
    if (file == NULL) {
        fprintf(stderr, "%s: cannot open\n", path);
        return 1;
    }
    static actionstring_model model;
    if (actionstring_model_builtin(&model) != ACTIONSTRING_OK) {
        fclose(file);
        return 1;
    }
    const uint32_t joints = actionstring_model_joint_count(&model);
    actionstring_state* state = NULL;
    actionstring_config config;
    actionstring_default_config(&model, &config);
    config.window_rule = 1;
    if (actionstring_init(&model, &config, state_memory, sizeof state_memory, &state) != ACTIONSTRING_OK) {
        fclose(file);
        return 1;
    }
    static char line[64 * 1024];
    float frame[3 * kMaxJoints];
    uint32_t index = 0, windows = 0, settled = 0;
    int32_t shown = -1;
    while (fgets(line, sizeof line, file) != NULL) {
        char* cursor = line;
        char* end = NULL;
        const long long time_us = strtoll(cursor, &end, 10);
        int ok = end != cursor;
        for (uint32_t k = 0; ok && k < 3 * joints; ++k) {
            cursor = end;
            frame[k] = strtof(cursor, &end);
            ok = end != cursor;
        }
        if (!ok) {
            fprintf(stderr, "%s:%u: expected a time and %u coordinates\n", path, index + 1, 3 * joints);
            fclose(file);
            return 1;
        }
        actionstring_frame_result result;
        actionstring_push_frame(state, time_us, frame, 3 * joints, &result);
        windows += result.windows_completed;
        for (uint32_t k = 0; k < result.characters_settled; ++k) {
            const int64_t character =
                actionstring_settled_character(state) - (int64_t)(result.characters_settled - 1u - k);
            const int32_t label = actionstring_settled_label(state, character);
            ++settled;
            if (label == shown) continue;
            shown = label;
            printf("settled %u char %lld %s\n", index, (long long)character,
                   actionstring_model_label_name(&model, label));
        }
        ++index;
    }
    fclose(file);
    CHECK(index > 0 && windows > 0 && settled > 0);
    return 0;
}

int main(int argc, char** argv) {
    const char* blobs[kMaxBlobs] = {0};
    int blob_count = 0;
    const char* stream = NULL;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--blob") == 0 && i + 1 < argc && blob_count < kMaxBlobs) blobs[blob_count++] = argv[++i];
        else if (stream == NULL) stream = argv[i];
        else {
            fprintf(stderr, "usage: test_c_api [--blob FILE]... [STREAM.txt]\n");
            return 2;
        }
    }
    /* The version the build's CMake project read from version.hpp. */
    CHECK(strcmp(actionstring_version(), ACTIONSTRING_EXPECTED_VERSION) == 0);
    static actionstring_model builtin;
    if (actionstring_model_builtin(&builtin) == ACTIONSTRING_OK) {
        contract_checks(&builtin);
        spread_checks(&builtin);
        clip_checks(&builtin);
    } else CHECK(blob_count > 0); /* a library without a built-in model is tested through blobs */
    blob_checks(blobs, blob_count);
    if (stream != NULL && replay_file(stream) != 0) return 1;
    if (failures != 0) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    return 0;
}
