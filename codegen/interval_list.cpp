// `actionstring interval-list`: a continuous dataset's timeline file as a clip
// list with labelled intervals (columns start and end, in seconds), which
// train reads as cut clips and eval --online streams as whole recordings.
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "io/formats.hpp"
#include "io/recordings.hpp"
#include "io/text.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {

int run_interval_list(int argc, char** argv) {
    std::string labels_path, out_path, subjects_text;
    double rate_hz = 30.0;
    ArgumentReader args("interval-list", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: actionstring interval-list --utkinect LABELS [--subjects S1,S2,...] [--rate HZ]\n"
                "                                  --out LIST\n\n"
                "Writes a clip list (path label subject start end; times in seconds on the\n"
                "recording's time axis, frame id / HZ [30] as the UTKinect reader uses) from\n"
                "UTKinect's actionLabel.txt. Recordings are joints_<sequence>.txt beside LABELS;\n"
                "the subject is the sequence name before '_'. --subjects keeps only those\n"
                "subjects. Intervals marked NaN are left out (and reported): their frames count\n"
                "as 'no action' when the recording is streamed. Intervals of one sequence that\n"
                "overlap are written and reported: frames in both count as the one that starts\n"
                "later. Paths are written absolute, so the list can live anywhere.\n");
            return 0;
        }
        if (arg == "--utkinect") labels_path = args.value(arg);
        else if (arg == "--subjects") subjects_text = args.value(arg);
        else if (arg == "--rate") rate_hz = args.number(arg, 0.001, 1e6);
        else if (arg == "--out") out_path = args.value(arg);
        else return args.unknown(arg);
    }
    if (!args.ok()) return 2;
    if (labels_path.empty() || out_path.empty())
        return args.error("usage: actionstring interval-list --utkinect LABELS --out LIST (see --help)");
    std::set<std::string> subjects;
    for (std::size_t from = 0; !subjects_text.empty() && from <= subjects_text.size();) {
        const std::size_t comma = std::min(subjects_text.find(',', from), subjects_text.size());
        if (comma > from) subjects.insert(subjects_text.substr(from, comma - from));
        from = comma + 1;
    }
    return run_reporting_errors("interval-list", [&] {
        const auto sequences = host::parse_utkinect_labels(labels_path, host::read_file(labels_path));
        // Absolute, so the list reads the same wherever it is written.
        const std::string folder = std::filesystem::absolute(labels_path).parent_path().string() + "/";
        std::ostringstream list;
        list.precision(10);
        list << "path\tlabel\tsubject\tstart\tend\n";
        std::size_t written = 0;
        std::set<std::string> seen;
        for (const auto& [sequence, intervals] : sequences) {
            const std::string subject = sequence.substr(0, sequence.find('_'));
            if (!subjects.empty() && subjects.count(subject) == 0) continue;
            seen.insert(subject);
            // Overlapping intervals are written as they are, and said: they are
            // usually a slip in the timeline file (host::interval_overlaps()).
            std::vector<host::LabelledRecording::Interval> kept;
            for (const host::LabelInterval& interval : intervals)
                if (interval.valid) kept.push_back({interval.label, interval.start_frame, interval.end_frame, 0});
            for (const host::IntervalOverlap& overlap : host::interval_overlaps(kept)) {
                const auto& a = kept[overlap.first];
                const auto& b = kept[overlap.second];
                std::fprintf(stderr,
                             "interval-list: %s: %s (frames %g-%g) and %s (frames %g-%g) overlap; both are written, "
                             "and frames in both count as %s, the one that starts later (check %s)\n",
                             sequence.c_str(), a.label.c_str(), a.start_s, a.end_s, b.label.c_str(), b.start_s, b.end_s,
                             kept[overlap.later].label.c_str(), labels_path.c_str());
            }
            for (const host::LabelInterval& interval : intervals) {
                if (!interval.valid) {
                    std::fprintf(stderr, "interval-list: %s %s has no frames (NaN) and is left out\n", sequence.c_str(),
                                 interval.label.c_str());
                    continue;
                }
                list << folder << "joints_" << sequence << ".txt\t" << interval.label << '\t' << subject << '\t'
                     << interval.start_frame / rate_hz << '\t' << interval.end_frame / rate_hz << '\n';
                ++written;
            }
        }
        for (const std::string& subject : subjects)
            if (seen.count(subject) == 0)
                return args.error("no sequence of subject '" + subject + "' in " + labels_path);
        if (written == 0) return args.error("no labelled interval to write");
        host::write_file(out_path, list.str());
        std::printf("%s: %zu intervals\n", out_path.c_str(), written);
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
