/* Runs the README's C snippet: opens every model file given at once, streams
 * a synthetic swaying skeleton through each (with a gap that restarts the
 * stream), ends the stream, and checks the actions it reported: each one
 * starts once and ends once with the same label, in time order, with a
 * confidence in [0, 1]; none is left running after the end.
 *   drive_c_snippet BLOB... */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include README_C_SNIPPET

/* What the handler saw of one model's stream. */
typedef struct action_log {
    int starts, ends, errors;
    int running; /* 1 between a start and its end */
    char label[64];
    double last_start_s;
} action_log;

static void log_action(void* user, const char* label, int started, double start_s, double end_s, float confidence) {
    action_log* log = (action_log*)user;
    if (label == NULL || strlen(label) == 0 || strlen(label) >= sizeof log->label || !(confidence >= 0.0f) ||
        !(confidence <= 1.0f) || !(start_s <= end_s)) {
        ++log->errors;
        return;
    }
    if (started) {
        if (log->running || start_s < log->last_start_s) ++log->errors; /* an action starts once, in order */
        ++log->starts;
        log->running = 1;
        log->last_start_s = start_s;
        strcpy(log->label, label);
    } else {
        if (!log->running || strcmp(log->label, label) != 0 || start_s != log->last_start_s) ++log->errors;
        ++log->ends;
        log->running = 0;
    }
}

int main(int argc, char** argv) {
    enum { kMaxModels = 4, kMaxJoints = 64 };
    static recogniser recognisers[kMaxModels];
    static action_log logs[kMaxModels];
    const int count = argc - 1;
    if (count < 1 || count > kMaxModels) {
        fprintf(stderr, "usage: drive_c_snippet BLOB...\n");
        return 2;
    }
    for (int m = 0; m < count; ++m)
        if (recogniser_open(&recognisers[m], argv[m + 1]) != 0) {
            fprintf(stderr, "%s: could not open\n", argv[m + 1]);
            return 1;
        }
    float xyz[3 * kMaxJoints];
    int reported[kMaxModels] = {0};
    for (int f = 0; f < 900; ++f) {
        if (f >= 400 && f < 490) continue; /* 1.5 s without frames: the stream restarts, its action ends */
        for (int m = 0; m < count; ++m) {
            const uint32_t joints = actionstring_model_joint_count(&recognisers[m].model);
            if (joints > kMaxJoints) return 1;
            for (uint32_t j = 0; j < joints; ++j) {
                xyz[3 * j + 0] = 0.1f * (float)(j % 5) - 0.2f + 0.05f * sinf(0.05f * (float)f);
                xyz[3 * j + 1] = 0.75f + 0.05f * (float)(j % 7);
                xyz[3 * j + 2] = 0.08f * (float)(j % 3) + 0.01f * (float)m;
            }
            const int events = recogniser_push(&recognisers[m], (int64_t)f * 16667, xyz, log_action, &logs[m]);
            if (events < 0) {
                fprintf(stderr, "%s: frame %d refused\n", argv[m + 1], f);
                return 1;
            }
            reported[m] += events;
        }
    }
    /* A frame 10 ms before the last one (a reordered packet) is refused, and reports nothing. */
    if (recogniser_push(&recognisers[0], (int64_t)899 * 16667 - 10000, xyz, log_action, &logs[0]) != -1) {
        fprintf(stderr, "%s: a frame before the last was not refused\n", argv[1]);
        return 1;
    }
    int failures = 0;
    for (int m = 0; m < count; ++m) {
        const int events = recogniser_finish(&recognisers[m], log_action, &logs[m]);
        if (events < 0) {
            fprintf(stderr, "%s: the stream could not end\n", argv[m + 1]);
            return 1;
        }
        reported[m] += events;
        const action_log* log = &logs[m];
        printf("%s: %d actions started, %d ended, %d events from 810 frames (a 1.5 s gap among 900)\n", argv[m + 1],
               log->starts, log->ends, reported[m]);
        failures += log->errors != 0 || log->starts == 0 || log->starts != log->ends || log->running ||
                    reported[m] != log->starts + log->ends;
        recogniser_close(&recognisers[m]);
    }
    return failures == 0 ? 0 : 1;
}
