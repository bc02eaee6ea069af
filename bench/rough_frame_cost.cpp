// Rough per-frame cost and state size of the annotator at the representative
// model size (J = 40, d = 24, K = 64, 30 representatives of 30 characters,
// 2 s windows every 0.5 s at 12 characters/s), on a 120 Hz stream.
// A first indication only: the full per-stage benchmark is separate.
//
//   actionstring_rough_frame_cost [runs]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "actionstring/actionstring.hpp"
#include "actionstring_port.hpp"
#include "run/state.hpp"
#include "synthetic_model.hpp"

using namespace actionstring;

namespace {

std::int64_t percentile(const std::vector<std::int64_t>& sorted, double q) {
    if (sorted.empty()) return 0;
    return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
}

void report(const char* name, std::vector<std::int64_t>& cost) {
    std::sort(cost.begin(), cost.end());
    std::printf("  %-26s n=%6zu  median %6lld  p90 %6lld  p99 %6lld  p99.9 %6lld  max %7lld\n", name, cost.size(),
                static_cast<long long>(percentile(cost, 0.5)), static_cast<long long>(percentile(cost, 0.9)),
                static_cast<long long>(percentile(cost, 0.99)), static_cast<long long>(percentile(cost, 0.999)),
                static_cast<long long>(cost.empty() ? 0 : cost.back()));
}

}  // namespace

int main(int argc, char** argv) {
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    std::printf(
        "annotator per frame [ns], 120 Hz stream of a jittering 31-joint skeleton,\n"
        "%d runs of 60 s after one warm-up run; a 'tick' frame computes a character\n",
        runs);
    for (const LengthNormalization normalization : {LengthNormalization::path, LengthNormalization::none})
        for (const Covariance covariance : {Covariance::full, Covariance::diagonal}) {
            host::ModelData data;
            bench::ModelSize size;
            size.covariance = covariance;
            bench::make_random_model(data, size);
            data.normalization = normalization;
            const ModelView model = data.view();
            host::Stateful<Annotator> annotator;
            AnnotatorConfig config = annotator_config(model);
            config.window_rule = true;
            const Status status = annotator.init(model, config);
            if (status != Status::ok) {
                std::fprintf(stderr, "model rejected: %s\n", status_name(status));
                return 1;
            }
            const int frames_per_run = 120 * 60;
            const auto frames = bench::random_walk_frames(31, frames_per_run);
            std::vector<std::int64_t> all, ticks, plain;
            for (int run = 0; run <= runs; ++run) {
                annotator->reset();
                for (int f = 0; f < frames_per_run; ++f) {
                    const std::int64_t t = static_cast<std::int64_t>(f) * 1000000 / 120;
                    const std::int64_t begin = port::monotonic_ns();
                    const FrameResult r = annotator->push_frame(t, frames[static_cast<std::size_t>(f)].data());
                    const std::int64_t elapsed = port::monotonic_ns() - begin;
                    if (run == 0) continue;  // warm-up
                    all.push_back(elapsed);
                    (r.characters > 0 ? ticks : plain).push_back(elapsed);
                }
            }
            std::printf("\n%s covariance, %s normalisation (J %u, d %u, K %u, R %u x %u, window %u step %u):\n",
                        covariance == Covariance::full ? "full" : "diagonal",
                        normalization == LengthNormalization::path ? "path-length" : "no length", model.component_count,
                        model.feature_dim, model.character_count, model.representative_count,
                        model.representative_length(0), model.window_chars, model.step_chars);
            report("all frames", all);
            report("tick frames", ticks);
            report("frames without a tick", plain);
        }
    host::ModelData data;
    bench::make_random_model(data, bench::ModelSize{});
    const ModelView model = data.view();
    AnnotatorConfig config = annotator_config(model);
    config.window_rule = true;
    std::printf("\nstate bytes (storage, path-length normalisation): Annotator %zu = StringEncoder %zu + WindowMatcher "
                "%zu + ActionSegmenter %zu (+ alignment); objects %zu\n",
                Annotator::required_bytes(model, config), StringEncoder::required_bytes(model),
                WindowMatcher::required_bytes(model), ActionSegmenter::required_bytes(model, config.segmenter),
                sizeof(Annotator));
    return 0;
}
