/* actionstring C API — for engines (Unity through P/Invoke, Unreal, plain C).
 *
 * The library is built around one generated model header (by default the
 * committed HDM05 example, models/hdm05_model.hpp). The caller owns the state's
 * memory: ask for its size and alignment, pass a buffer to actionstring_init(),
 * and keep that buffer alive and unmoved until the last call with the state.
 * No call allocates, throws or keeps a pointer to a caller's frame. Every call
 * reports through actionstring_status; none aborts on bad input.
 *
 * Threading: a state is used by one thread at a time; different states are
 * independent. */
#ifndef ACTIONSTRING_C_H
#define ACTIONSTRING_C_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(ACTIONSTRING_C_SHARED)
#if defined(ACTIONSTRING_C_BUILDING)
#define ACTIONSTRING_C_API __declspec(dllexport)
#else
#define ACTIONSTRING_C_API __declspec(dllimport)
#endif
#elif defined(ACTIONSTRING_C_SHARED) && defined(__GNUC__)
#define ACTIONSTRING_C_API __attribute__((visibility("default")))
#else
#define ACTIONSTRING_C_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Status codes; the values equal actionstring::Status and never change. */
typedef int32_t actionstring_status;
enum {
    ACTIONSTRING_OK = 0,
    ACTIONSTRING_NON_FINITE_INPUT = 1,    /**< frame rejected: NaN or infinity */
    ACTIONSTRING_TRACKING_LOST = 2,       /**< frame rejected: every joint at the origin */
    ACTIONSTRING_DEGENERATE_POSE = 3,     /**< frame rejected: hips give no facing direction */
    ACTIONSTRING_POSE_OUT_OF_RANGE = 4,   /**< frame rejected: too far from every key-pose */
    ACTIONSTRING_TIME_WENT_BACKWARDS = 5, /**< frame rejected: earlier than the previous frame */
    ACTIONSTRING_STREAM_RESTARTED = 6,    /**< frame accepted after a long gap; windows restarted */
    ACTIONSTRING_INVALID_MODEL = 7,
    ACTIONSTRING_MODEL_EXCEEDS_CAPACITY = 8,
    ACTIONSTRING_INVALID_ARGUMENT = 9, /**< null pointer, short or misaligned buffer, wrong count */
    ACTIONSTRING_NOT_INITIALIZED = 10  /**< the state was not set up by actionstring_init() */
};

/** Opaque state: lives in caller-owned memory. */
typedef struct actionstring_state actionstring_state;

/** What one actionstring_push_frame() did. */
typedef struct actionstring_frame_result {
    actionstring_status status;  /**< OK or STREAM_RESTARTED when accepted, else why rejected */
    uint32_t characters;         /**< characters appended to the action string */
    uint32_t windows_completed;  /**< windows that completed (and may have changed the label) */
    uint32_t characters_settled; /**< characters whose final label the segmenter decided */
} actionstring_frame_result;

/** Bytes and alignment the state needs. */
ACTIONSTRING_C_API size_t actionstring_state_size(void);
ACTIONSTRING_C_API size_t actionstring_state_alignment(void);

/** Sets up a state in `memory` (`size` bytes, aligned to actionstring_state_alignment())
 *  and stores its handle in *state. The memory stays the caller's; the state needs no
 *  release, the caller may simply reuse or free the memory after its last call. */
ACTIONSTRING_C_API actionstring_status actionstring_init(void* memory, size_t size, actionstring_state** state);

/** Feeds one frame: `positions` holds actionstring_joint_count() × 3 floats (xyz per joint,
 *  metres) and is read only during the call; `position_count` must equal that number.
 *  `result` may be NULL. Returns the frame's status (also in result->status). */
ACTIONSTRING_C_API actionstring_status actionstring_push_frame(actionstring_state* state, int64_t time_us,
                                                               const float* positions, size_t position_count,
                                                               actionstring_frame_result* result);

/** Forgets the stream (string, windows, label); the model stays bound. */
ACTIONSTRING_C_API actionstring_status actionstring_reset(actionstring_state* state);

/** The segmenter's online settings. A model carries its own, chosen at
 *  training; actionstring_init() uses them. */
typedef struct actionstring_online_settings {
    int64_t settle_delay_us; /**< a character's label is final this long after it */
    float segment_penalty;   /**< cost of starting another segment */
    float stay_penalty;      /**< cost of two stream characters on one representative character */
    float skip_penalty;      /**< cost of skipping a representative character */
    float unknown_cost;      /**< cost per character of "no action"; INFINITY turns it off */
} actionstring_online_settings;

/** The model's own online settings. */
ACTIONSTRING_C_API actionstring_online_settings actionstring_model_online_settings(void);

/** Replaces a state's online settings and restarts its stream. INVALID_ARGUMENT
 *  (and the state unchanged) for a negative, NaN or too long setting, or a
 *  settle delay longer than the state holds; NOT_INITIALIZED for a bad state. */
ACTIONSTRING_C_API actionstring_status actionstring_set_online_settings(actionstring_state* state,
                                                                        const actionstring_online_settings* settings);

/** Current label index (0 .. actionstring_label_count()-1), or -1 for unknown or a bad state. */
ACTIONSTRING_C_API int32_t actionstring_label(const actionstring_state* state);
/** Confidence of the current label in [0, 1]; 0 when unknown. */
ACTIONSTRING_C_API float actionstring_confidence(const actionstring_state* state);
/** Name of the current label, or "unknown". Static storage; never NULL. */
ACTIONSTRING_C_API const char* actionstring_label_name(const actionstring_state* state);

/** The segmenter's label for the newest character (no delay, may still change), or -1. */
ACTIONSTRING_C_API int32_t actionstring_live_label(const actionstring_state* state);
/** Index of the last character whose label is final, or -1 before the first one. */
ACTIONSTRING_C_API int64_t actionstring_settled_character(const actionstring_state* state);
/** Final label of a settled character (one of the most recent, e.g. those the last frame
 *  reported in characters_settled), or -1 for unknown or a character not remembered. */
ACTIONSTRING_C_API int32_t actionstring_settled_label(const actionstring_state* state, int64_t character);

/** The model: joints per frame, labels, a label's name ("unknown" when out of range). */
ACTIONSTRING_C_API uint32_t actionstring_joint_count(void);
ACTIONSTRING_C_API uint32_t actionstring_label_count(void);
ACTIONSTRING_C_API const char* actionstring_label_name_of(int32_t label);
/** Checksum of the model artifact the library was generated from ("fnv1a64:…"). */
ACTIONSTRING_C_API const char* actionstring_model_checksum(void);
/** Short stable name of a status code; static storage; never NULL. */
ACTIONSTRING_C_API const char* actionstring_status_name(actionstring_status status);

#ifdef __cplusplus
}
#endif

#endif /* ACTIONSTRING_C_H */
