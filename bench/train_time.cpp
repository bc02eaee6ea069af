// End-to-end training time on a clip list with the default settings (or a config).
//
//   actionstring_train_time [LIST]   (default: hdm05/train.tsv)
// Reads the clips once (timed separately), then trains 3 times; prints the
// median total and each stage's median. EM uses every core, like the trainer.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "train/gmm_em.hpp"
#include "train/pca.hpp"
#include "train/pipeline.hpp"

using namespace actionstring::host;

int main(int argc, char** argv) {
    const char* env = std::getenv("ACTIONSTRING_DATA");
    const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
    const std::string list = argc > 1 ? argv[1] : data + "/hdm05/train.tsv";
    std::vector<LabelledClip> clips;
    const auto read_start = std::chrono::steady_clock::now();
    try {
        for (const auto& entry : read_clip_list(list)) clips.push_back({read_clip(entry), entry.label, entry.subject});
    } catch (const ReadError& error) {
        std::fprintf(stderr, "SKIPPED: %s (set ACTIONSTRING_DATA or pass a clip list)\n", error.what());
        return 0;
    }
    const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
    std::map<std::string, std::vector<double>> stages;
    std::vector<double> totals;
    for (int run = 0; run < 3; ++run) {
        TrainingReport report;
        const auto start = std::chrono::steady_clock::now();
        train_model(clips, TrainingOptions{}, &report);
        totals.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        for (const auto& stage : report.stage_seconds) stages[stage.first].push_back(stage.second);
    }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    std::printf("training on %s (%zu clips), default settings, median of 3 runs:\n", list.c_str(), clips.size());
    std::printf("  %-30s %7.2f s (once)\n", "reading + FK", read_seconds);
    for (const auto& stage : stages) std::printf("  %-30s %7.2f s\n", stage.first.c_str(), median(stage.second));
    std::printf("  %-30s %7.2f s (reading included: %.2f s)\n", "training total", median(totals),
                median(totals) + read_seconds);
    return 0;
}
