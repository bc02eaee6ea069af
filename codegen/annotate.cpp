// `actionstring annotate MODEL FILE`: the label timeline of a recording.
#include <cstdio>
#include <string>

#include "actionstring_host/artifact.hpp"
#include "actionstring_host/evaluation.hpp"
#include "actionstring_host/readers.hpp"
#include "commands.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {

int run_annotate(int argc, char** argv) {
    std::string model_path, file, skeleton;
    bool json = false;
    host::ReadOptions read;
    AnnotatorConfig config;
    ArgumentReader args("annotate", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf("usage: actionstring annotate --model MODEL FILE [--skeleton ASF] [--rate HZ] [--roles R,L,R] [--json]\n"
                        "                             [--settle S] [--segment-penalty X] [--stay-penalty X]\n"
                        "                             [--skip-penalty X] [--unknown-cost X]\n\n"
                        "Streams FILE frame by frame through the annotator, as a device would, and prints\n"
                        "the timeline of settled labels: start and end time in seconds, label (or\n"
                        "'unknown') and the confidence, the share of the span's frames whose live label\n"
                        "(decided without the settle delay) already said so; as TSV (default) or JSON.\n"
                        "The segmenter options are those of 'actionstring eval'.\n");
            return 0;
        }
        if (arg == "--model") model_path = args.value(arg);
        else if (arg == "--skeleton") skeleton = args.value(arg);
        else if (arg == "--rate") read.frame_rate_hz = args.number(arg, 0.001, 1e6);
        else if (arg == "--roles") read.roles = parse_roles(args, args.value(arg));
        else if (arg == "--json") json = true;
        else if (parse_segmenter_option(args, arg, config.segmenter)) continue;
        else if (!arg.empty() && arg[0] == '-') return args.unknown(arg);
        else if (file.empty()) file = arg;
        else return args.error("more than one FILE given");
    }
    if (!args.ok()) return 2;
    if (model_path.empty() || file.empty()) return args.error("usage: actionstring annotate --model MODEL FILE (see --help)");
    try {
        host::ModelData model = host::load_model(model_path);
        const ModelView view = model.view();
        const host::Clip clip = host::read_clip(file, read, skeleton);
        const auto spans = host::annotate_clip(view, clip, config);
        auto name = [&](int label) { return label < 0 ? std::string("unknown") : model.label_names[static_cast<std::size_t>(label)]; };
        if (json) {
            std::printf("{\"file\": %s, \"segments\": [", host::json_string(file).c_str());
            for (std::size_t i = 0; i < spans.size(); ++i)
                std::printf("%s{\"start\": %.4f, \"end\": %.4f, \"label\": %s, \"confidence\": %.4f}", i ? ", " : "", spans[i].start_s,
                            spans[i].end_s, host::json_string(name(spans[i].label)).c_str(), spans[i].agreement);
            std::printf("]}\n");
        } else {
            std::printf("start\tend\tlabel\tconfidence\n");
            for (const auto& span : spans)
                std::printf("%.4f\t%.4f\t%s\t%.4f\n", span.start_s, span.end_s, name(span.label).c_str(), span.agreement);
        }
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring annotate: %s\n", error.what());
        return 1;
    }
}

}  // namespace cli
}  // namespace actionstring
