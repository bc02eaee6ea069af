/* Runs the README's C snippet: opens every model file given at once, streams
 * a synthetic swaying skeleton through each, and checks what comes out.
 *   drive_c_snippet BLOB... */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include README_C_SNIPPET

int main(int argc, char** argv) {
    enum { kMaxModels = 4, kMaxJoints = 64 };
    static recogniser recognisers[kMaxModels];
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
    int settled[kMaxModels] = {0};
    float xyz[3 * kMaxJoints];
    for (int f = 0; f < 900; ++f) {
        if (f >= 400 && f < 490) continue; /* 1.5 s without frames: the stream restarts, its tail flushed */
        for (int m = 0; m < count; ++m) {
            const uint32_t joints = actionstring_model_joint_count(&recognisers[m].model);
            if (joints > kMaxJoints) return 1;
            for (uint32_t j = 0; j < joints; ++j) {
                xyz[3 * j + 0] = 0.1f * (float)(j % 5) - 0.2f + 0.05f * sinf(0.05f * (float)f);
                xyz[3 * j + 1] = 0.75f + 0.05f * (float)(j % 7);
                xyz[3 * j + 2] = 0.08f * (float)(j % 3) + 0.01f * (float)m;
            }
            const char* label = recogniser_push(&recognisers[m], (int64_t)f * 16667, xyz);
            if (label == NULL) continue;
            if (strlen(label) == 0) return 1;
            ++settled[m];
        }
    }
    int failures = 0;
    for (int m = 0; m < count; ++m) {
        printf("%s: %d final labels from 810 frames (a 1.5 s gap among 900)\n", argv[m + 1], settled[m]);
        failures += settled[m] == 0;
        recogniser_close(&recognisers[m]);
    }
    return failures == 0 ? 0 : 1;
}
