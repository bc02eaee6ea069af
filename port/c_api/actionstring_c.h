/* actionstring C API — for engines (Unity through P/Invoke, Unreal, plain C).
 *
 * Models are data. Load a model blob at run time (written by
 * `actionstring codegen MODEL --blob FILE`) with actionstring_model_from_blob(),
 * or take the model compiled into the library, if it was built with one
 * (actionstring_model_builtin()). Any number of models and states may be used
 * at once; each state runs one model.
 *
 * Memory belongs to the caller, and no call allocates:
 *  - a model handle (actionstring_model) is a plain struct the caller
 *    declares; a model read from a blob points into the blob's bytes, which
 *    must stay alive, unchanged and aligned to 16 bytes while the model (and
 *    any state running it) is used; the handle must not move either;
 *  - a state lives in caller memory of actionstring_state_size() bytes,
 *    aligned to actionstring_state_alignment(), alive and unmoved until the
 *    last call with it; it needs no release (reuse or free the memory).
 * No call throws, aborts on bad input, or keeps a pointer to a caller's frame;
 * every call reports through actionstring_status.
 *
 * Threading: a state is used by one thread at a time; different states, and
 * states sharing one model, are independent. */
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
    ACTIONSTRING_STREAM_RESTARTED = 6,    /**< frame accepted after a long gap; the stream restarted */
    ACTIONSTRING_INVALID_MODEL = 7,       /**< a blob that is damaged, of another version, or not a valid model */
    ACTIONSTRING_MODEL_EXCEEDS_CAPACITY = 8,
    ACTIONSTRING_INVALID_ARGUMENT = 9,  /**< null pointer, wrong count, bad setting, no built-in model */
    ACTIONSTRING_NOT_INITIALIZED = 10,  /**< not a model or state set up by this API (or overwritten since) */
    ACTIONSTRING_STORAGE_TOO_SMALL = 11 /**< memory null, misaligned or smaller than actionstring_state_size() */
};

/** A model handle: declared by the caller (stack, static, or inside an engine
 *  object), filled by actionstring_model_from_blob() or actionstring_model_builtin(). */
typedef struct actionstring_model {
    uint64_t opaque[80];
} actionstring_model;

/** Opaque state: lives in caller-owned memory. */
typedef struct actionstring_state actionstring_state;

/** The segmenter's online settings. A model carries its own, chosen at training. */
typedef struct actionstring_online_settings {
    int64_t settle_delay_us; /**< a character's label is final this long after it */
    float segment_penalty;   /**< cost of starting another segment */
    float stay_penalty;      /**< cost of two stream characters on one representative character */
    float skip_penalty;      /**< cost of skipping a representative character */
    float unknown_cost;      /**< cost per character of "no action"; INFINITY turns it off */
    float vote_weight;       /**< weight of the characters' label votes in the explanation; 0 = off */
    float exemplar_weight;   /**< weight of the exemplars in the explanation; 0 = off (needs exemplars in the model) */
    int64_t settle_stable_us; /**< or final sooner, once every best explanation has given a character the same label
                                   this long (0: the delay alone); more state (actionstring_state_size()) */
    float direction_weight;   /**< weight of the last characters' motion directions in the explanation; 0 = off
                                  (needs window directions in the model); more state (actionstring_state_size()) */
} actionstring_online_settings;

/** Everything a state is set up with. actionstring_default_config() gives the model's own. */
typedef struct actionstring_config {
    actionstring_online_settings online;
    int64_t max_gap_us;      /**< a longer gap between accepted frames restarts the stream (default 1 s) */
    int64_t max_backward_us; /**< a frame this much earlier than the last is rejected as jitter (100 ms) */
    int32_t window_rule;     /**< nonzero: also run the paper's window rule (actionstring_label()); default 0 */
    int64_t min_action_us;   /**< events: a shorter action is flicker and not reported (the model's own) */
    int32_t spread_work;     /**< nonzero: each character's work (encoder and segmenter) is spread over the
                                  frames until the next one, for a flat frame cost; the same labels and events,
                                  each reported up to one string period later (actionstring_finish_work()); more
                                  state (actionstring_state_size()); default 0 */
    int64_t label_lead_us;   /**< a character's label applies this long before its tick (actionstring_label_time_us(),
                                  the events' times): the feature's motion looks back, so actions show in it late
                                  (the model's own, 0 to 600 s) */
    float up[3];             /**< the sensor's up direction in the positions' coordinates, when the device knows
                                  it (a Kinect's floor plane normal, an IMU's gravity): every frame is turned to put
                                  it along the model's up axis, so a sensor mounted higher or lower gives the poses
                                  the training one gave; all zero (default): no turn. Not finite or shorter than
                                  1e-6: INVALID_ARGUMENT */
    float max_pose_speed;    /**< a pose that moved faster than this since the previous frame (metres per second,
                                  the mean over the normalised pose's coordinates), and by three times what the
                                  stream's frames typically move, jumped: the tracker lost and found the body, or
                                  clips were joined, and the motion starts again from it (default 3; 0: never).
                                  Negative or NaN: INVALID_ARGUMENT */
} actionstring_config;

/** What one actionstring_push_frame() did. */
typedef struct actionstring_frame_result {
    actionstring_status status;  /**< OK or STREAM_RESTARTED when accepted, else why rejected */
    uint32_t characters;         /**< characters appended to the action string */
    uint32_t windows_completed;  /**< windows that completed (with the window rule) */
    uint32_t characters_settled; /**< characters whose final label the segmenter decided */
    uint32_t events;             /**< action events this frame produced (actionstring_event()) */
    uint32_t characters_flushed; /**< when the frame restarted the stream: the ended stream's last characters,
                                      whose labels became final with it (actionstring_flushed_label()) */
} actionstring_frame_result;

/** An action event: each detected action is reported once when it starts and
 *  once when it ends (runs shorter than config.min_action_us are not reported). */
typedef struct actionstring_event {
    int32_t started;         /**< 1: the action started; 0: it ended */
    int32_t label;           /**< label index */
    int64_t start_time_us;   /**< label time of its first character, on the frames' clock */
    int64_t end_time_us;     /**< where its last character's label stops applying (so far, for a start):
                                  the label time of the character after it */
    int64_t first_character; /**< stream index of its first character */
    int64_t last_character;
    float confidence; /**< share of its characters whose live label already said this label */
} actionstring_event;

/* ---- the library ------------------------------------------------------------------- */

/** The library's version, "major.minor.patch" (static storage). Before 1.0 the
 *  minor number changes whenever a program built against an earlier release
 *  could break: a struct or function here, or a model format (actionstring/version.hpp). */
ACTIONSTRING_C_API const char* actionstring_version(void);

/* ---- models ------------------------------------------------------------------------ */

/** Reads a model blob in place: `blob` (`size` bytes, aligned to 16) is checked
 *  once (version, checksum, every table's bounds, every value) and then used
 *  where it lies. INVALID_MODEL for a damaged, truncated, foreign or hostile
 *  blob, INVALID_ARGUMENT for a null or misaligned one; the model is then unusable. */
ACTIONSTRING_C_API actionstring_status actionstring_model_from_blob(const void* blob, size_t size,
                                                                    actionstring_model* model);
/** The model compiled into the library (a generated header), or INVALID_ARGUMENT
 *  when the library was built without one. */
ACTIONSTRING_C_API actionstring_status actionstring_model_builtin(actionstring_model* model);

/** Joints per frame (frames hold 3 × this many floats), or 0 for a bad handle. */
ACTIONSTRING_C_API uint32_t actionstring_model_joint_count(const actionstring_model* model);
/** A joint's name in frame order, or "" when out of range or unnamed. Points into the model. */
ACTIONSTRING_C_API const char* actionstring_model_joint_name(const actionstring_model* model, uint32_t joint);
/** Labels, and a label's name ("unknown" when out of range). Points into the model. */
ACTIONSTRING_C_API uint32_t actionstring_model_label_count(const actionstring_model* model);
ACTIONSTRING_C_API const char* actionstring_model_label_name(const actionstring_model* model, int32_t label);
/** Where the model came from: "fnv1a64:…" of the artifact a built-in header was
 *  generated from, or "blob-fnv1a64:…" of a blob. Points into the handle; "" for a bad one. */
ACTIONSTRING_C_API const char* actionstring_model_checksum(const actionstring_model* model);
/** Fills *config with the model's own settings and the default timing. */
ACTIONSTRING_C_API actionstring_status actionstring_default_config(const actionstring_model* model,
                                                                   actionstring_config* config);

/* ---- states ------------------------------------------------------------------------ */

/** Bytes a state needs for this model and config (NULL: the model's own), or 0
 *  for a bad handle or a config actionstring_init() would refuse. */
ACTIONSTRING_C_API size_t actionstring_state_size(const actionstring_model* model, const actionstring_config* config);
/** Alignment the state's memory needs (16). */
ACTIONSTRING_C_API size_t actionstring_state_alignment(void);

/** Sets up a state for `model` (which must outlive it) in `memory` (`size`
 *  bytes, aligned) and stores its handle in *state. config NULL: the model's own. */
ACTIONSTRING_C_API actionstring_status actionstring_init(const actionstring_model* model,
                                                         const actionstring_config* config, void* memory, size_t size,
                                                         actionstring_state** state);

/** Feeds one frame: `positions` holds 3 × the model's joint count floats (xyz per joint,
 *  metres) and is read only during the call; `position_count` must equal that number
 *  (INVALID_ARGUMENT otherwise). `result` may be NULL. Returns the frame's status. */
ACTIONSTRING_C_API actionstring_status actionstring_push_frame(actionstring_state* state, int64_t time_us,
                                                               const float* positions, size_t position_count,
                                                               actionstring_frame_result* result);

/** Event `index` (< result.events) of the last push_frame() or flush(); INVALID_ARGUMENT
 *  when there is no such event, NOT_INITIALIZED for a bad state. */
ACTIONSTRING_C_API actionstring_status actionstring_event_at(const actionstring_state* state, uint32_t index,
                                                             actionstring_event* event);
/** Ends the stream: characters not settled yet take their labels and a running action
 *  ends; *events (if not NULL) receives how many events that made (read them with
 *  actionstring_event_at()), and the labels are actionstring_flushed_label(). The next
 *  frame starts a new stream. */
ACTIONSTRING_C_API actionstring_status actionstring_flush(actionstring_state* state, uint32_t* events);

/** The characters of the stream that ended with the last push_frame() (a restart: its
 *  result's characters_flushed) or actionstring_flush(), whose labels became final then
 *  and which no result reported settled (the last the state remembers: always its whole
 *  unsettled tail); 0 after any other call or for a bad state. */
ACTIONSTRING_C_API uint32_t actionstring_flushed_count(const actionstring_state* state);
/** Final label of flushed character `index` (< actionstring_flushed_count()), or -1 for
 *  unknown, an index out of range or a bad state. */
ACTIONSTRING_C_API int32_t actionstring_flushed_label(const actionstring_state* state, uint32_t index);
/** Where flushed character `index`'s label applies from, on the ended stream's clock
 *  (its tick less the label lead, as actionstring_label_time_us()); 0 when out of range. */
ACTIONSTRING_C_API int64_t actionstring_flushed_label_time_us(const actionstring_state* state, uint32_t index);

/** With config.spread_work: finishes the work of the characters in progress now and
 *  reports it as a frame would (`result` may be NULL: characters_settled, events), e.g.
 *  before a pause in the frames. Does nothing otherwise. NOT_INITIALIZED for a bad state. */
ACTIONSTRING_C_API actionstring_status actionstring_finish_work(actionstring_state* state,
                                                                actionstring_frame_result* result);

/** Forgets the stream (string, windows, label); the model stays bound. */
ACTIONSTRING_C_API actionstring_status actionstring_reset(actionstring_state* state);

/** The model's own online settings (zeros for a bad handle). */
ACTIONSTRING_C_API actionstring_online_settings actionstring_model_online_settings(const actionstring_model* model);
/** Replaces a state's online settings and restarts its stream. INVALID_ARGUMENT
 *  for a negative, NaN or too long setting; STORAGE_TOO_SMALL when the state's
 *  memory cannot hold them (a longer settle delay needs more: ask
 *  actionstring_state_size()); NOT_INITIALIZED for a bad state. On failure the
 *  state is unchanged. */
ACTIONSTRING_C_API actionstring_status actionstring_set_online_settings(actionstring_state* state,
                                                                        const actionstring_online_settings* settings);
/** Replaces a state's shortest action for events (config.min_action_us; a
 *  model carries its own, which actionstring_default_config() gives) and
 *  restarts its stream. INVALID_ARGUMENT for a negative one or one over 10
 *  minutes; NOT_INITIALIZED for a bad state. On failure the state is unchanged. */
ACTIONSTRING_C_API actionstring_status actionstring_set_min_action(actionstring_state* state, int64_t min_action_us);
/** Replaces a state's label lead (config.label_lead_us; a model carries its own) and
 *  restarts its stream. INVALID_ARGUMENT for a negative one or one over 10 minutes;
 *  NOT_INITIALIZED for a bad state. On failure the state is unchanged. */
ACTIONSTRING_C_API actionstring_status actionstring_set_label_lead(actionstring_state* state, int64_t label_lead_us);
/** Replaces a state's sensor up direction (config.up; 0, 0, 0 for none) and restarts
 *  its stream. INVALID_ARGUMENT for one not finite or shorter than 1e-6;
 *  NOT_INITIALIZED for a bad state. On failure the state is unchanged. */
ACTIONSTRING_C_API actionstring_status actionstring_set_up_direction(actionstring_state* state, float x, float y,
                                                                     float z);

/** The paper's window rule (needs config.window_rule): the current label index, or -1. */
ACTIONSTRING_C_API int32_t actionstring_label(const actionstring_state* state);
/** Confidence of actionstring_label() in [0, 1]; 0 when unknown. */
ACTIONSTRING_C_API float actionstring_confidence(const actionstring_state* state);
/** Name of actionstring_label(), or "unknown". Never NULL. */
ACTIONSTRING_C_API const char* actionstring_label_name(const actionstring_state* state);

/** The segmenter's label for the newest character (no delay, may still change), or -1. */
ACTIONSTRING_C_API int32_t actionstring_live_label(const actionstring_state* state);
/** How far the live label leads every other label, "no action" included, in units of
 *  the model's character distances: a confidence for it (0 before the first character
 *  or on a tie; INFINITY when no other label can explain the stream). */
ACTIONSTRING_C_API float actionstring_live_margin(const actionstring_state* state);
/** Index of the last character whose label is final, or -1 before the first one. */
ACTIONSTRING_C_API int64_t actionstring_settled_character(const actionstring_state* state);
/** Final label of a settled character (one of the most recent, e.g. those the last frame
 *  reported in characters_settled), or -1 for unknown or a character not remembered. */
ACTIONSTRING_C_API int32_t actionstring_settled_label(const actionstring_state* state, int64_t character);
/** The time on the frames' clock from which a character's label applies: its tick less
 *  the label lead (config.label_lead_us). A frame at time t takes the label of the last
 *  character whose label time is at most t. 0 for a bad state or a negative index. */
ACTIONSTRING_C_API int64_t actionstring_label_time_us(const actionstring_state* state, int64_t character);
/** The model a state runs, or NULL for a bad state. */
ACTIONSTRING_C_API const actionstring_model* actionstring_state_model(const actionstring_state* state);

/* ---- whole clips: a gesture between two events --------------------------------------- */

/** A clip recorder: the characters of a clip's frames, kept in caller memory,
 *  labelled as a whole when asked (the same label `actionstring eval` gives the
 *  clip). Like a state, it lives in memory of actionstring_clip_size() bytes,
 *  aligned to actionstring_state_alignment(), and its model must outlive it. */
typedef struct actionstring_clip actionstring_clip;

/** Bytes a recorder of up to `max_characters` characters (the model's string rate
 *  times the longest gesture, in seconds) needs, or 0 for a bad handle, 0
 *  characters or a size no memory could hold. */
ACTIONSTRING_C_API size_t actionstring_clip_size(const actionstring_model* model, uint32_t max_characters);

/** Sets up a recorder in `memory` (`size` bytes, aligned) and stores its handle in *clip. */
ACTIONSTRING_C_API actionstring_status actionstring_clip_init(const actionstring_model* model, uint32_t max_characters,
                                                              void* memory, size_t size, actionstring_clip** clip);

/** Feeds one frame of the clip (as actionstring_push_frame()). Returns the frame's
 *  status, or STORAGE_TOO_SMALL when the clip already holds max_characters and this
 *  frame's characters were dropped (the clip keeps its beginning). */
ACTIONSTRING_C_API actionstring_status actionstring_clip_push_frame(actionstring_clip* clip, int64_t time_us,
                                                                    const float* positions, size_t position_count);

/** Characters recorded since the last reset (0 for a bad handle). */
ACTIONSTRING_C_API uint32_t actionstring_clip_length(const actionstring_clip* clip);

/** Labels the clip recorded so far: *label the label index or -1 for unknown (no
 *  characters yet, or nothing near enough), *confidence in [0, 1] (either may be
 *  NULL). The clip goes on recording. NOT_INITIALIZED for a bad handle. */
ACTIONSTRING_C_API actionstring_status actionstring_clip_classify(actionstring_clip* clip, int32_t* label,
                                                                  float* confidence);

/** Each label's score for the clip recorded so far, the numbers
 *  actionstring_clip_classify() decides by: the distance of the label's nearest
 *  representative with what the clip's votes, exemplars and descriptors add
 *  (smaller is nearer; +inf before the first character). For ranking labels, as a
 *  game's "did you mean" list or a second opinion; the unknown distance and learned
 *  rejection apply only to actionstring_clip_classify(). Writes `count` floats to
 *  `distances`, which must be at least actionstring_model_label_count(): INVALID_ARGUMENT
 *  (nothing written) when it is smaller or NULL; NOT_INITIALIZED for a bad handle. */
ACTIONSTRING_C_API actionstring_status actionstring_clip_label_distances(actionstring_clip* clip, float* distances,
                                                                         size_t count);

/** Forgets the recorded clip: the next frame begins a new one. */
ACTIONSTRING_C_API actionstring_status actionstring_clip_reset(actionstring_clip* clip);

/** Gives the recorder the sensor's up direction (as config.up of a state; 0, 0, 0 for
 *  none) and forgets the recorded clip. INVALID_ARGUMENT for one not finite or shorter
 *  than 1e-6; NOT_INITIALIZED for a bad handle. On failure the recorder is unchanged. */
ACTIONSTRING_C_API actionstring_status actionstring_clip_set_up_direction(actionstring_clip* clip, float x, float y,
                                                                          float z);

/** Short stable name of a status code; static storage; never NULL. */
ACTIONSTRING_C_API const char* actionstring_status_name(actionstring_status status);

#ifdef __cplusplus
}
#endif

#endif /* ACTIONSTRING_C_H */
