// Runs a README C++ snippet the way its text says a device would: setup()
// once, then on_frame() per frame. The frames are a synthetic performer on the
// example model's skeleton (HDM05 ASF, 31 joints): a body that turns, walks and
// moves its limbs, so every stage runs and characters settle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <vector>

bool setup();
void on_frame(std::int64_t time_us, const float* joint_xyz_metres);

// The snippet's user hook: here it counts the final labels and checks them:
// a name, and times in order that start at most a second (the model's label
// lead is less) before the stream's first frame, at 0.
static int settled_labels = 0;
static bool labels_ok = true;
static std::int64_t last_time_us = -1000000;
static bool saw_tail = false;  // a label of the last second before the gap: only the restart's flush gives those
void on_settled(std::int64_t time_us, const char* label) {
    labels_ok = labels_ok && label != nullptr && label[0] != '\0' && time_us >= last_time_us;
    last_time_us = time_us;
    saw_tail = saw_tail || (time_us >= 9000000 && time_us < 10000000);
    ++settled_labels;
}

int main() {
    if (!setup()) {
        std::fprintf(stderr, "README snippet: setup() refused the model\n");
        return 1;
    }
    constexpr std::size_t joints = 31;
    std::vector<float> frame(joints * 3);
    for (int f = 0; f < 120 * 20; ++f) {  // 20 s at 120 Hz, with a 2 s tracking loss from 10 s
        const double t = f / 120.0;
        if (t >= 10.0 && t < 12.0) continue;  // the stream restarts at 12 s: flushed labels
        for (std::size_t j = 0; j < joints; ++j) {
            // Each joint circles its own rest offset; joints 1 and 6 are the hips.
            const double phase = 0.7 * static_cast<double>(j) + 2.0 * t;
            frame[3 * j + 0] = static_cast<float>(0.3 * t + 0.1 * static_cast<double>(j % 5) + 0.05 * std::sin(phase));
            frame[3 * j + 1] = static_cast<float>(0.9 + 0.04 * static_cast<double>(j) + 0.05 * std::cos(phase));
            frame[3 * j + 2] = static_cast<float>(0.02 * static_cast<double>(j % 7) + 0.05 * std::sin(1.3 * phase));
        }
        frame[3 * 1 + 0] = static_cast<float>(0.3 * t + 0.1);  // left hip
        frame[3 * 6 + 0] = static_cast<float>(0.3 * t - 0.1);  // right hip
        on_frame(static_cast<std::int64_t>(std::llround(t * 1e6)), frame.data());
    }
    if (settled_labels == 0 || !labels_ok || !saw_tail) {
        std::fprintf(stderr, "README snippet: %d labels settled in 20 s%s%s\n", settled_labels,
                     labels_ok ? "" : ", some without a name or time",
                     saw_tail ? "" : ", none of the second before the gap (the restart's flushed labels)");
        return 1;
    }
    std::printf("README snippet ran: %d settled labels\n", settled_labels);
    return 0;
}
