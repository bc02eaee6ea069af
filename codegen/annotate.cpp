// `actionstring annotate MODEL FILE`: the label timeline of a recording.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "common/json.hpp"
#include "common/time.hpp"
#include "io/formats.hpp"
#include "model/artifact.hpp"
#include "live.hpp"
#include "options.hpp"
#include "run/skeleton.hpp"
#include "run/stream_labels.hpp"

namespace actionstring {
namespace cli {

int run_annotate(int argc, char** argv) {
    std::string model_path, file, skeleton;
    bool json = false, events = false, live = false;
    LiveSource live_source;
    host::ReadOptions read;
    OnlineOverrides overrides;
    ArgumentReader args("annotate", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: actionstring annotate --model MODEL FILE [--skeleton ASF] [--rate HZ] [--roles R,L,R]\n"
                "       actionstring annotate --model MODEL --live [--udp PORT [--idle-timeout S]] [options]\n"
                "                             [--json | --events] [--min-action S] [--time-unit s|ms|us] [--body N]\n"
                "                             [--columns time=COL,JOINT=X:Y:Z,...] [--length-unit U]\n"
                "                             [--settle S] [--settle-stable S] [--segment-penalty X] [--stay-penalty X]\n"
                "                             [--skip-penalty X] [--unknown-cost X] [--segment-votes X]\n"
                "                             [--segment-exemplars X] [--segment-directions X] [--label-lead S]\n"
                "                             [--spread-work]\n"
                "                             [--up X,Y,Z] [--max-pose-speed V]\n\n"
                "Streams FILE frame by frame through the annotator, as a device would, and prints\n"
                "the timeline of settled labels: start and end time in seconds, label (or\n"
                "'unknown') and the confidence, the share of the span's frames whose live label\n"
                "(decided without the settle delay) already said so; as TSV (default) or JSON.\n"
                "--events prints the action events instead, one JSON object per line: each\n"
                "action once when it starts and once when it ends (label, start and end time,\n"
                "confidence); an action shorter than --min-action seconds [the model's own] is\n"
                "flicker and is not reported, and the end of the file ends a running action.\n"
                "--live reads frames as they arrive, from standard input or (--udp PORT) from\n"
                "UDP datagrams on 127.0.0.1: a joint CSV header line, then one frame per line\n"
                "(the CSV spellings of 'info'; joints matched to the model's by name), and\n"
                "prints JSON lines the moment they are known, flushed: each change of the\n"
                "settled label ({\"settled\": …, \"time\": …}) and each action event. A malformed\n"
                "line is skipped and counted, never fatal; the end of the input (or\n"
                "--idle-timeout seconds without a datagram) ends the stream.\n"
                "--spread-work spreads each character's work (encoder and segmenter) over the\n"
                "frames until the next character: the same labels, each up to one string period\n"
                "later.\n"
                "--up X,Y,Z is the sensor's up direction in the file's coordinates, when it is\n"
                "known and differs from the model's up axis (a Kinect's floor plane normal, an\n"
                "IMU's gravity): every frame is turned to put it along the axis, so a sensor\n"
                "mounted higher or lower than the training one gives the poses it gave.\n"
                "The segmenter options and --max-pose-speed are those of 'actionstring eval'.\n");
            return 0;
        }
        if (arg == "--model") model_path = args.value(arg);
        else if (parse_read_option(args, arg, read, skeleton)) continue;
        else if (arg == "--json") json = true;
        else if (arg == "--events") events = true;
        else if (arg == "--live") live = true;
        else if (arg == "--udp") live_source.udp_port = static_cast<int>(args.whole(arg, 1, 65535));
        else if (arg == "--idle-timeout") live_source.idle_timeout_s = args.number(arg, 0.01, 3600);
        else if (parse_online_option(args, arg, overrides)) continue;
        else if (parse_up_option(args, arg, overrides.up)) continue;
        else if (!arg.empty() && arg[0] == '-') return args.unknown(arg);
        else if (file.empty()) file = arg;
        else return args.error("more than one FILE given");
    }
    if (!args.ok()) return 2;
    if (live) {
        if (model_path.empty() || !file.empty())
            return args.error("usage: actionstring annotate --model MODEL --live [--udp PORT] (see --help)");
        return run_reporting_errors("annotate", [&] {
            const host::ModelData model = host::load_model(model_path);
            const AnnotatorConfig config = overrides.over(model.view(), args);
            return run_live(model, config, read, live_source);
        });
    }
    if (live_source.udp_port != 0) return args.error("--udp needs --live");
    if (model_path.empty() || file.empty())
        return args.error("usage: actionstring annotate --model MODEL FILE (see --help)");
    return run_reporting_errors("annotate", [&] {
        const host::ModelData model = host::load_model(model_path);
        const ModelView view = model.view();
        host::Clip clip = host::read_clip(file, read, skeleton);
        for (const std::string& note : clip.notes)
            std::fprintf(stderr, "actionstring annotate: %s: %s\n", file.c_str(), note.c_str());
        host::conform_to_model(view, clip);
        if (events) {
            const AnnotatorConfig config = overrides.over(view, args);
            for (const ActionEvent& e : host::stream_events(view, clip, config)) {
                host::JsonWriter out;
                out.begin_object()
                    .field("event", e.kind == ActionEvent::Kind::started ? "started" : "ended")
                    .field("label", model.label_names[e.label])
                    .field("start", host::us_to_seconds(e.start_time_us))
                    .field("end", host::us_to_seconds(e.end_time_us))
                    .field("confidence", static_cast<double>(e.confidence))
                    .end_object();
                std::string line = out.str();
                while (!line.empty() && line.back() == '\n') line.pop_back();
                std::printf("%s\n", line.c_str());  // one event per line, out the moment it is known
                std::fflush(stdout);
            }
            return 0;
        }
        const auto spans = host::annotate_clip(view, clip, overrides.over(view, args));
        auto name = [&](int label) {
            return label < 0 ? std::string("unknown") : model.label_names[static_cast<std::size_t>(label)];
        };
        if (json) {
            host::JsonWriter out;
            out.begin_object().field("file", file).key("segments").begin_array();
            for (const host::LabelSpan& span : spans)
                out.begin_object()
                    .field("start", span.start_s)
                    .field("end", span.end_s)
                    .field("label", name(span.label))
                    .field("confidence", span.agreement)
                    .end_object();
            std::fputs(out.end_array().end_object().str().c_str(), stdout);
        } else {
            std::printf("start\tend\tlabel\tconfidence\n");
            for (const auto& span : spans)
                std::printf("%.4f\t%.4f\t%s\t%.4f\n", span.start_s, span.end_s, name(span.label).c_str(),
                            span.agreement);
        }
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
