// `actionstring view FILE --model MODEL --out page.html`: a page to watch a
// recording with its labels.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/paths.hpp"
#include "eval/online.hpp"
#include "eval/viewer.hpp"
#include "io/formats.hpp"
#include "model/artifact.hpp"
#include "options.hpp"
#include "run/skeleton.hpp"

namespace actionstring {
namespace cli {

int run_view(int argc, char** argv) {
    std::string model_path, file, out_path, skeleton, label, title;
    host::ReadOptions read;
    OnlineOverrides overrides;
    ArgumentReader args("view", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: actionstring view FILE --model MODEL --out PAGE.html [--label NAME] [--title TEXT]\n"
                "                         [--skeleton ASF] [--rate HZ] [--roles R,L,R] [--time-unit s|ms|us]\n"
                "                         [--body N] [--columns time=COL,JOINT=X:Y:Z,...] [--up X,Y,Z]\n"
                "                         [--length-unit m|dm|cm|mm|in]\n"
                "                         [segmenter options]\n\n"
                "Streams FILE through the annotator as 'annotate' does and writes one\n"
                "self-contained HTML page (no network access, no external scripts) to look at\n"
                "it: the skeleton playing in 3D (drag to turn it) with a time slider, and\n"
                "under it the label timelines (the truth when --label names the whole file's\n"
                "action, the settled, live and latest-window labels), the live label's margin\n"
                "(its confidence) and the action events. 'eval --report DIR' writes one such\n"
                "page per stream, with the truth. The segmenter options are those of 'eval';\n"
                "--up is the sensor's up direction, as 'annotate' takes it.\n");
            return 0;
        }
        if (arg == "--model") model_path = args.value(arg);
        else if (arg == "--out") out_path = args.value(arg);
        else if (arg == "--label") label = args.value(arg);
        else if (arg == "--title") title = args.value(arg);
        else if (parse_read_option(args, arg, read, skeleton)) continue;
        else if (parse_online_option(args, arg, overrides)) continue;
        else if (parse_up_option(args, arg, overrides.up)) continue;
        else if (!arg.empty() && arg[0] == '-') return args.unknown(arg);
        else if (file.empty()) file = arg;
        else return args.error("more than one FILE given");
    }
    if (!args.ok()) return 2;
    if (model_path.empty() || file.empty() || out_path.empty())
        return args.error("usage: actionstring view FILE --model MODEL --out PAGE.html (see --help)");
    return run_reporting_errors("view", [&] {
        const host::ModelData model = host::load_model(model_path);
        const ModelView view = model.view();
        host::Clip clip = host::read_clip(file, read, skeleton);
        for (const std::string& note : clip.notes)
            std::fprintf(stderr, "actionstring view: %s: %s\n", file.c_str(), note.c_str());
        host::conform_to_model(view, clip);
        std::vector<host::LabelledRecording::Interval> whole;
        if (!label.empty() && clip.frame_count() > 0) whole.push_back({label, clip.times.front(), clip.times.back()});
        const host::StreamTimeline timeline =
            host::stream_recording(view, clip, label.empty() ? nullptr : &whole, overrides.over(view, args));
        const std::string page =
            host::viewer_html(timeline, model.label_names.strings(), title.empty() ? host::short_path(file) + " with " + host::short_path(model_path) : title);
        std::ofstream out(out_path, std::ios::binary);
        out << page;
        out.close();
        if (!out) throw std::runtime_error("cannot write " + out_path);
        std::printf("wrote %s (%zu bytes, %zu frames)\n", out_path.c_str(), page.size(), clip.frame_count());
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
