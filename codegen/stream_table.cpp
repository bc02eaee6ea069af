// `actionstring stream-table`: a recorded stream as a header of constexpr
// tables, for the firmware replay and its host twin (port/firmware).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io/clip_list.hpp"
#include "io/stream.hpp"
#include "io/text.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {

int run_stream_table(int argc, char** argv) {
    std::string list_path, out_path, ns = "actionstring_stream";
    double first = 0, count = 1, stride = 1, max_seconds = 0;
    bool as_text = false;
    ArgumentReader args("stream-table", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: actionstring stream-table --clips LIST [--first I] [--count N] [--stride K]\n"
                "                                 [--max-seconds S]\n"
                "                                 [--namespace NS] [--text] --out HEADER\n\n"
                "Concatenates N clips of LIST, every K-th from clip I (in list order; each clip at\n"
                "most S seconds, 0 = whole) into one stream and writes it as a header of constexpr tables: frame\n"
                "times in microseconds, joint positions in metres exactly as read, and where each\n"
                "clip starts with its label. The firmware replay (port/firmware) embeds it. The\n"
                "header holds dataset content: generate it at build time, never commit it.\n"
                "--text writes the same frames as text instead: per line the time in microseconds\n"
                "and the coordinates as exact hexadecimal floats.\n");
            return 0;
        }
        if (arg == "--clips") list_path = args.value(arg);
        else if (arg == "--first") first = args.whole(arg, 0, 1e9);
        else if (arg == "--count") count = args.whole(arg, 1, 1e6);
        else if (arg == "--stride") stride = args.whole(arg, 1, 1e6);
        else if (arg == "--max-seconds") max_seconds = args.number(arg, 0, 1e6);
        else if (arg == "--namespace") ns = args.value(arg);
        else if (arg == "--out") out_path = args.value(arg);
        else if (arg == "--text") as_text = true;
        else return args.unknown(arg);
    }
    if (!args.ok()) return 2;
    if (list_path.empty() || out_path.empty())
        return args.error("usage: actionstring stream-table --clips LIST --out HEADER (see --help)");
    return run_reporting_errors("stream-table", [&] {
        const auto entries = host::read_clip_list(list_path);
        const auto begin = static_cast<std::size_t>(first);
        const auto step = static_cast<std::size_t>(stride);
        if (begin >= entries.size())
            return args.error(list_path + " has " + std::to_string(entries.size()) + " clips; --first is past the end");
        std::vector<std::size_t> picked;
        for (std::size_t i = begin; i < entries.size() && picked.size() < static_cast<std::size_t>(count); i += step)
            picked.push_back(i);
        std::vector<host::Clip> clips;
        clips.reserve(picked.size());  // segments point into it
        std::vector<host::StreamSegment> segments;
        for (const std::size_t i : picked) {
            clips.push_back(host::read_clip(entries[i]));
            segments.push_back({&clips.back(), entries[i].label, max_seconds});
        }
        char described[256];
        std::snprintf(described, sizeof described,
                      "actionstring stream-table --clips <%s> --first %zu --count %zu --stride %zu --max-seconds %g",
                      list_path.substr(list_path.find_last_of('/') + 1).c_str(), begin, picked.size(), step,
                      max_seconds);
        const std::string text =
            as_text ? host::generate_stream_text(segments) : host::generate_stream_header(segments, ns, described);
        host::write_file(out_path, text);
        std::fprintf(stderr, "actionstring stream-table: %zu clips, %zu bytes -> %s\n", picked.size(), text.size(),
                     out_path.c_str());
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
