// `actionstring demo`: a synthetic performance streamed through the runtime.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "actionstring/actionstring.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "actionstring_port.hpp"
#include "commands.hpp"

namespace actionstring {
namespace cli {
namespace {

void print_demo_usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: actionstring demo [--actions N] [--seed N] [--frame-rate HZ]\n"
                 "                         [--noise METRES] [--drop PROBABILITY]\n"
                 "\n"
                 "Builds the synthetic toy world (a 5-joint skeleton and four actions),\n"
                 "performs N random actions back to back at random places and facings, and\n"
                 "streams the frames one at a time through the allocation-free annotator.\n"
                 "Prints the true and predicted timelines, frame accuracy and per-frame time.\n"
                 "The toy world shows the runtime working; it is not an accuracy figure.\n");
}

bool parse_number(const char* text, double& out) {
    char* end = nullptr;
    out = std::strtod(text, &end);
    return end != text && *end == '\0';
}

}  // namespace

int run_demo(int argc, char** argv) {
    int action_count = 12;
    double seed = 1, frame_rate = 30.0, noise = 0.01, drop = 0.0;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            print_demo_usage(stdout);
            return 0;
        }
        double value = 0;
        if (i + 1 >= argc || !parse_number(argv[i + 1], value)) {
            std::fprintf(stderr, "actionstring demo: option '%s' needs a number\n", arg.c_str());
            return 2;
        }
        ++i;
        if (arg == "--actions" && value >= 1 && value <= 10000) action_count = static_cast<int>(value);
        else if (arg == "--seed" && value >= 0) seed = value;
        else if (arg == "--frame-rate" && value >= 1 && value <= 1000) frame_rate = value;
        else if (arg == "--noise" && value >= 0 && value <= 1) noise = value;
        else if (arg == "--drop" && value >= 0 && value < 1) drop = value;
        else {
            std::fprintf(stderr, "actionstring demo: bad option or value '%s %s'\n", arg.c_str(), argv[i]);
            return 2;
        }
    }

    host::ToyWorld world = host::make_toy_world();
    const ModelView model = world.model.view();
    // The model's settings, with the paper's window rule beside the segmenter.
    AnnotatorConfig config = annotator_config(model);
    config.window_rule = true;
    host::Stateful<Annotator> annotator;
    const Status status = annotator.init(model, config);
    if (status != Status::ok) {
        std::fprintf(stderr, "actionstring demo: model rejected: %s\n", status_name(status));
        return 1;
    }

    std::mt19937 rng(static_cast<std::uint32_t>(seed));
    std::uniform_int_distribution<int> pick(0, static_cast<int>(world.actions.size()) - 1);
    std::vector<int> sequence;
    for (int i = 0; i < action_count; ++i) sequence.push_back(pick(rng));
    host::ToyStreamOptions stream_options;
    stream_options.frame_rate_hz = frame_rate;
    stream_options.position_noise_m = noise;
    stream_options.drop_probability = drop;
    stream_options.seed = static_cast<std::uint32_t>(seed) + 1;
    const auto frames = host::toy_stream(world, sequence, stream_options);

    std::printf(
        "model: J=%u components, K=%u characters, %u representatives, window %u chars, step %u,"
        " string rate %.1f Hz\n",
        model.component_count, model.character_count, model.representative_count, model.window_chars, model.step_chars,
        1e6 / model.string_period_us);
    std::printf("state: %zu bytes of storage (Annotator::required_bytes for this model)\n",
                annotator.storage_bytes());
    std::printf("stream: %zu frames at %.0f Hz, %d actions\n\n", frames.size(), frame_rate, action_count);
    std::printf("%10s  %-12s  %-12s  %s\n", "time [s]", "true", "predicted", "confidence");

    std::vector<std::int64_t> costs;
    costs.reserve(frames.size());
    std::size_t correct = 0;
    int last_true = -2;
    LabelId last_label = 0xFFFE;
    for (const auto& frame : frames) {
        const std::int64_t begin = port::monotonic_ns();
        annotator->push_frame(frame.time_us, frame.positions.data());
        costs.push_back(port::monotonic_ns() - begin);
        const LabelId label = annotator->label();
        if (label == frame.action) ++correct;
        if (label != last_label || frame.action != last_true) {
            std::printf("%10.2f  %-12s  %-12s  %.2f\n", static_cast<double>(frame.time_us) * 1e-6,
                        world.actions[static_cast<std::size_t>(frame.action)].name.c_str(), annotator->label_name(),
                        static_cast<double>(annotator->confidence()));
            last_label = label;
            last_true = frame.action;
        }
    }
    std::sort(costs.begin(), costs.end());
    auto percentile = [&](double p) {
        return costs[std::min(costs.size() - 1, static_cast<std::size_t>(p * static_cast<double>(costs.size())))];
    };
    std::printf("\nframe accuracy (label of the latest window == action under way): %.3f of %zu frames\n",
                static_cast<double>(correct) / static_cast<double>(frames.size()), frames.size());
    std::printf("per-frame time (rough, one run, steady_clock): median %lld ns, p99 %lld ns, max %lld ns\n",
                static_cast<long long>(percentile(0.5)), static_cast<long long>(percentile(0.99)),
                static_cast<long long>(costs.back()));
    return 0;
}

}  // namespace cli
}  // namespace actionstring
