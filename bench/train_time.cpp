// End-to-end training time on a clip list with the default settings (no
// self-tuning: TrainingOptions{} as `train --no-tune` uses them).
//
//   actionstring_train_time [LIST...] [--mirror] [--scaling] [--runs N]
//
// Several lists train as one (MSR Action3D's train.tsv and test.tsv: all 557
// clips, 1,114 with --mirror). Reads the clips once (timed separately), then trains N times (3) and prints
// the median total and each stage's median. EM uses every core, like the
// trainer. --mirror also trains on every clip mirrored (twice the clips);
// --scaling trains on every 4th clip, every 2nd clip and all of them, and
// prints samples, EM iterations, convergence and seconds per 10,000 samples,
// so a time that grows faster than the data shows.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "train/pipeline.hpp"

using namespace actionstring::host;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

struct Timing {
    std::map<std::string, std::vector<double>> stages;
    std::vector<double> totals;
    TrainingReport last;
};

Timing time_training(const std::vector<LabelledClip>& clips, const TrainingOptions& options, int runs) {
    Timing t;
    for (int run = 0; run < runs; ++run) {
        TrainingReport report;
        const auto start = std::chrono::steady_clock::now();
        train_model(clips, options, &report);
        t.totals.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        for (const auto& stage : report.stage_seconds) t.stages[stage.first].push_back(stage.second);
        t.last = report;
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    const char* env = std::getenv("ACTIONSTRING_DATA");
    const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
    std::vector<std::string> lists;
    bool scaling = false;
    int runs = 3;
    TrainingOptions options;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--mirror") == 0) {
            options.mirror = true;
        } else if (std::strcmp(argv[i], "--scaling") == 0) {
            scaling = true;
        } else if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
            runs = std::max(1, std::atoi(argv[++i]));
        } else if (argv[i][0] == '-') {
            std::fprintf(stderr, "usage: actionstring_train_time [LIST...] [--mirror] [--scaling] [--runs N]\n");
            return 2;
        } else {
            lists.push_back(argv[i]);
        }
    }
    if (lists.empty()) lists.push_back(data + "/hdm05/train.tsv");
    std::string named = lists[0];
    for (std::size_t i = 1; i < lists.size(); ++i) named += " + " + lists[i];
    std::vector<LabelledClip> clips;
    const auto read_start = std::chrono::steady_clock::now();
    try {
        for (const std::string& list : lists)
            for (const auto& entry : read_clip_list(list)) clips.push_back({read_clip(entry), entry.label, entry.subject});
    } catch (const ReadError& error) {
        std::fprintf(stderr, "SKIPPED: %s (set ACTIONSTRING_DATA or pass a clip list)\n", error.what());
        return 0;
    }
    const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
    const std::size_t trained = clips.size() * (options.mirror ? 2 : 1);

    if (scaling) {
        std::printf("training on %s%s, default settings (J = %d, %s covariance), median of %d runs:\n", named.c_str(),
                    options.mirror ? " and its mirror images" : "", options.components,
                    options.covariance == actionstring::Covariance::full ? "full" : "diagonal", runs);
        std::printf("  %-12s %9s %11s %8s %10s %8s %9s %18s\n", "clips", "samples", "EM iter.", "conv.", "EM s",
                    "total s", "J kept", "EM s / 10k samples");
        for (const std::size_t every : {std::size_t{4}, std::size_t{2}, std::size_t{1}}) {
            std::vector<LabelledClip> part;
            for (std::size_t i = 0; i < clips.size(); i += every) part.push_back(clips[i]);
            const Timing t = time_training(part, options, runs);
            const double em = median(t.stages.at("GMM (EM)"));
            const double samples = static_cast<double>(t.last.feature_samples);
            std::printf("  %-12zu %9zu %11zu %8s %10.2f %8.2f %9zu %18.2f\n", part.size() * (options.mirror ? 2 : 1),
                        t.last.feature_samples, t.last.em.objective.size() - 1, t.last.em.converged ? "yes" : "NO", em,
                        median(t.totals), static_cast<std::size_t>(options.components - t.last.em.dropped),
                        em / samples * 1e4);
        }
        return 0;
    }

    const Timing t = time_training(clips, options, runs);
    std::printf("training on %s (%zu clips%s), default settings, median of %d runs:\n", named.c_str(), trained,
                options.mirror ? ", half of them mirrored" : "", runs);
    std::printf("  %-30s %7.2f s (once)\n", "reading + FK", read_seconds);
    for (const auto& stage : t.stages) std::printf("  %-30s %7.2f s\n", stage.first.c_str(), median(stage.second));
    std::printf("  EM: %zu iterations, %s\n", t.last.em.objective.size() - 1,
                t.last.em.converged ? "converged" : "NOT converged (the iteration budget ended it)");
    std::printf("  %-30s %7.2f s (reading included: %.2f s)\n", "training total", median(t.totals),
                median(t.totals) + read_seconds);
    return 0;
}
