// Pictures of an evaluation: SVG confusion matrix and timelines, Markdown summary.
#include "eval/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>

#include "eval/viewer.hpp"

namespace actionstring {
namespace host {
namespace {

std::string escape(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

}  // namespace

// Distinct hues for labels; unknown / "no action" is light grey.
std::string label_colour(int label) {
    if (label < 0) return label == unknown_frame ? "#d9d9d9" : "#000000";
    static const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                                    "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939", "#8c6d31", "#843c39",
                                    "#7b4173", "#3182bd", "#e6550d", "#31a354", "#756bb1", "#636363"};
    return palette[static_cast<std::size_t>(label) % (sizeof palette / sizeof palette[0])];
}

namespace {

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::string confusion_svg(const ClipResults& r) {
    const std::size_t L = r.labels.size();
    const int cell = 30, left = 230, top = 250;
    const int width = left + cell * static_cast<int>(L + 1) + 20, height = top + cell * static_cast<int>(L) + 60;
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"10\" y=\"20\" font-size=\"15\">" << escape(r.method) << ": clip accuracy " << std::fixed;
    svg.precision(3);
    svg << r.clip_accuracy << "</text>\n<text x=\"10\" y=\"40\">rows: true label; columns: predicted (last: unknown); "
        << "shade: share of the row</text>\n";
    for (std::size_t p = 0; p <= L; ++p) {
        const int x = left + cell * static_cast<int>(p) + cell / 2;
        svg << "<text transform=\"translate(" << x + 4 << "," << top - 6 << ") rotate(-60)\">"
            << escape(p < L ? r.labels[p] : std::string("unknown")) << "</text>\n";
    }
    for (std::size_t t = 0; t < L; ++t) {
        int support = 0;
        for (int v : r.confusion[t]) support += v;
        const int y = top + cell * static_cast<int>(t);
        svg << "<text x=\"" << left - 6 << "\" y=\"" << y + cell / 2 + 4 << "\" text-anchor=\"end\">"
            << escape(r.labels[t]) << "</text>\n";
        for (std::size_t p = 0; p <= L; ++p) {
            const int v = r.confusion[t][p];
            const double share = support > 0 ? static_cast<double>(v) / support : 0.0;
            const int shade = static_cast<int>(std::lround(255 - 200 * share));
            const bool diagonal = p == t;
            char fill[16];
            std::snprintf(fill, sizeof fill, diagonal ? "#%02x%02xff" : "#ff%02x%02x", shade, shade);
            svg << "<rect x=\"" << left + cell * static_cast<int>(p) << "\" y=\"" << y << "\" width=\"" << cell
                << "\" height=\"" << cell << "\" fill=\"" << (v == 0 ? "#ffffff" : fill) << "\" stroke=\"#bbbbbb\"/>\n";
            if (v != 0)
                svg << "<text x=\"" << left + cell * static_cast<int>(p) + cell / 2 << "\" y=\"" << y + cell / 2 + 4
                    << "\" text-anchor=\"middle\">" << v << "</text>\n";
        }
    }
    svg << "</svg>\n";
    return svg.str();
}

std::string timeline_svg(const StreamTimeline& stream, const std::vector<std::string>& labels) {
    const std::size_t n = stream.times_s.size();
    const double begin = n ? stream.times_s.front() : 0.0, end = n ? stream.times_s.back() : 1.0;
    const double seconds = std::max(end - begin, 1e-3);
    const int left = 150, row = 26, gap = 10, plot = std::max(600, static_cast<int>(seconds * 12));
    struct Row {
        const char* name;
        const std::vector<int>* labels;
    };
    const Row rows[] = {{"true", &stream.truth},
                        {"settled (final)", &stream.labels.settled},
                        {"live (no delay)", &stream.labels.live},
                        {"paper: latest window", &stream.labels.window}};
    const int legend_rows = static_cast<int>((labels.size() + 2 + 3) / 4);
    const int height = 50 + 4 * (row + gap) + 30 + legend_rows * 18 + 10;
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << left + plot + 20 << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"10\" y=\"20\" font-size=\"15\">" << escape(stream.name)
        << ": true vs predicted labels over time</text>\n";
    auto x_of = [&](double t) { return left + (t - begin) / seconds * plot; };
    for (int k = 0; k < 4; ++k) {
        const int y = 40 + k * (row + gap);
        svg << "<text x=\"" << left - 6 << "\" y=\"" << y + row / 2 + 4 << "\" text-anchor=\"end\">" << rows[k].name
            << "</text>\n";
        const std::vector<int>& v = *rows[k].labels;
        for (std::size_t i = 0; i < v.size();) {
            std::size_t j = i;
            while (j < v.size() && v[j] == v[i]) ++j;
            const double x0 = x_of(stream.times_s[i]);
            const double x1 = j < n ? x_of(stream.times_s[j]) : x_of(end);
            char geometry[96];
            std::snprintf(geometry, sizeof geometry, "x=\"%.1f\" y=\"%d\" width=\"%.1f\" height=\"%d\"", x0, y,
                          std::max(x1 - x0, 0.5), row);
            svg << "<rect " << geometry << " fill=\"" << label_colour(v[i]) << "\"><title>"
                << escape(v[i] >= 0 && static_cast<std::size_t>(v[i]) < labels.size()
                              ? labels[static_cast<std::size_t>(v[i])]
                              : std::string(v[i] == unknown_frame ? "unknown / no action" : "label not in the model"))
                << "</title></rect>\n";
            i = j;
        }
    }
    const int axis = 40 + 4 * (row + gap);
    for (double t = 0; t <= seconds + 1e-9; t += seconds > 120 ? 30 : 10) {
        char tick[160];
        std::snprintf(
            tick, sizeof tick,
            "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%d\" y2=\"%d\" stroke=\"#444\"/><text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">%.0f s</text>\n",
            x_of(begin + t), x_of(begin + t), axis - 4, axis + 2, x_of(begin + t), axis + 16, t);
        svg << tick;
    }
    for (std::size_t l = 0; l <= labels.size(); ++l) {
        const int x = 10 + static_cast<int>(l % 4) * 220, y = axis + 30 + static_cast<int>(l / 4) * 18;
        const int id = l < labels.size() ? static_cast<int>(l) : -1;
        svg << "<rect x=\"" << x << "\" y=\"" << y - 10 << "\" width=\"12\" height=\"12\" fill=\"" << label_colour(id)
            << "\"/><text x=\"" << x + 16 << "\" y=\"" << y << "\">"
            << escape(id >= 0 ? labels[l] : std::string("unknown / no action")) << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

void write_report(const std::string& dir, const std::string& title, const std::vector<ClipResults>& clip_results,
                  const OnlineReport* online, const std::vector<std::string>& labels) {
    ::mkdir(dir.c_str(), 0777);
    struct stat info {};
    if (::stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
        throw std::runtime_error("cannot create the folder " + dir);
    std::ostringstream md;
    md.precision(3);
    md << std::fixed << "# " << title << "\n\n## Clip recognition\n\n"
       << "The interval is the 95% Wilson interval of the accuracy; a baseline's last column counts the clips\n"
       << "only the model gets right and only the baseline does, with the exact McNemar p of that difference\n"
       << "(small: the two really differ on such clips).\n\n"
       << "| method | clip accuracy | 95% interval | unknown | paired with the model |\n|---|---:|---:|---:|---|\n";
    for (const ClipResults& r : clip_results) {
        md << "| " << r.method << " | " << r.clip_accuracy << " | " << r.accuracy_interval.low << "–"
           << r.accuracy_interval.high << " | " << r.unknown_rate << " | ";
        if (r.paired) md << r.model_only << " / " << r.method_only << ", p " << r.mcnemar_p;
        md << " |\n";
    }
    if (!clip_results.empty() && !clip_results.front().top_k.empty()) {
        // How near the model's errors are: the true label among its best-scored labels.
        md << "\nThe model's true label among the labels' k best scores (before rejection):";
        for (std::size_t k = 0; k < clip_results.front().top_k.size(); ++k)
            md << (k == 0 ? " " : ", ") << "top-" << k + 1 << " " << clip_results.front().top_k[k];
        md << ".\n";
    }
    if (!clip_results.empty() && !clip_results.front().per_subject.empty()) {
        md << "\nClip accuracy per subject (the methods in the order above):\n\n| subject | clips |";
        for (const ClipResults& r : clip_results) md << " " << r.method << " |";
        md << "\n|---|---:|";
        for (std::size_t m = 0; m < clip_results.size(); ++m) md << "---:|";
        md << "\n";
        for (std::size_t s = 0; s < clip_results.front().per_subject.size(); ++s) {
            const SubjectScore& score = clip_results.front().per_subject[s];
            md << "| " << score.subject << " | " << score.clips << " |";
            for (const ClipResults& r : clip_results)
                md << " " << (s < r.per_subject.size() ? r.per_subject[s].accuracy : 0.0) << " |";
            md << "\n";
        }
    }
    if (!clip_results.empty()) {
        write_file(dir + "/confusion.svg", confusion_svg(clip_results.front()));
        md << "\n![confusion matrix](confusion.svg)\n";
    }
    if (online != nullptr) {
        const OnlineResults& settled = online->settled;
        md << (online->recordings ? "\n## Online labelling of whole continuous recordings\n\n"
                                  : "\n## Online labelling of clips concatenated per subject\n\n")
           << settled.frames << " frames; " << settled.no_action_frames
           << " of them outside every action, so saying unknown everywhere scores "
           << settled.unknown_everywhere_accuracy << ".\n\n"
           << "Intervals are 95%, resampling the true actions and stretches of no action.\n\n"
           << "| rule | frame accuracy | in action | no action | frame F1 | segment F1 | mean delay (s) | missed "
              "segments | flicker (/min) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n"
           << "| baseline: unknown everywhere | " << settled.unknown_everywhere_accuracy
           << " | 0 | 1 | 0 | 0 | | | |\n";
        const std::pair<const char*, const OnlineResults*> rules[] = {{"segmenter, settled labels", &online->settled},
                                                                      {"segmenter, live labels", &online->live},
                                                                      {"paper: latest window wins", &online->window}};
        for (const auto& rule : rules)
            md << "| " << rule.first << " | " << rule.second->frame_accuracy << " ("
               << rule.second->frame_accuracy_interval.low << "–" << rule.second->frame_accuracy_interval.high << ") | "
               << rule.second->action_frame_accuracy << " | " << rule.second->no_action_accuracy << " | "
               << rule.second->frame_f1 << " | " << rule.second->segment_f1 << " ("
               << rule.second->segment_f1_interval.low << "–" << rule.second->segment_f1_interval.high << ") | "
               << rule.second->mean_delay_s << " | " << rule.second->missed_segments << " | "
               << rule.second->flicker_per_min << " |\n";
        md << "\nThe settled labels became final a median " << settled.final_after_median_s
           << " s after their frames (95th percentile " << settled.final_after_p95_s
           << " s): at most the settle delay, sooner where the model settles early.\n";
        if (settled.has_events)
            md << "\nAction events (each action once when it starts and once when it ends): " << settled.events
               << " reported, " << settled.matched_events << " matched to a true action (event F1 " << settled.event_f1
               << "; judged as segments, one-to-one at temporal IoU ≥ 0.5, " << settled.iou_matched_events
               << " matched, F1 " << settled.event_segment_f1 << ", 95% interval "
               << settled.event_segment_f1_interval.low << "–" << settled.event_segment_f1_interval.high
               << "), detection latency " << settled.detection_latency_s << " s, start error " << settled.start_error_s
               << " s (mean bias " << std::showpos << settled.start_bias_s << std::noshowpos << " s), end error "
               << settled.end_error_s << " s (mean bias " << std::showpos << settled.end_bias_s << std::noshowpos
               << " s), " << settled.false_events_per_min << " false events per "
               << (settled.false_events_per_stream_min ? "minute of stream" : "minute of no action") << ".\n";
        // Per class, where a stream's frame accuracy hides it: an action missed whole, one taken for another.
        md << "\nSettled frames per class (recall: its frames labelled with it; precision: the frames labelled with it "
              "that are it):\n\n| class | frames | recall | precision | F1 | its other frames most often taken for "
              "|\n|---|---:|---:|---:|---:|---|\n";
        auto name = [&labels](int label) { return frame_class_name(label, labels); };
        for (const FrameClassScore& c : frame_class_scores(settled)) {
            md << "| " << name(c.label) << " | " << c.frames << " | " << c.recall << " | " << c.precision << " | "
               << c.f1 << " | ";
            if (c.most_taken_for_frames > 0) md << name(c.most_taken_for) << " (" << c.most_taken_for_frames << ")";
            md << " |\n";
        }
        // Each stream alone: which subjects or recordings the pooled figures come from.
        md << "\nSettled labels per " << (online->recordings ? "recording" : "subject (its clips joined)")
           << ":\n\n| stream | frames | frame accuracy | in action | no action | unknown everywhere | frame F1 | "
              "segment F1 | event F1 |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (std::size_t s = 0; s < online->per_stream.size() && s < online->streams.size(); ++s) {
            const OnlineResults& r = online->per_stream[s];
            md << "| " << online->streams[s].name << " | " << r.frames << " | " << r.frame_accuracy << " | "
               << r.action_frame_accuracy << " | ";
            if (r.no_action_frames > 0) md << r.no_action_accuracy << " | " << r.unknown_everywhere_accuracy;
            else md << " | ";
            md << " | " << r.frame_f1 << " | " << r.segment_f1 << " | " << r.event_f1 << " |\n";
        }
        md << "\n";
        for (std::size_t s = 0; s < online->streams.size(); ++s) {
            const std::string file = "timeline_" + std::to_string(s + 1) + ".svg";
            const std::string page = "view_" + std::to_string(s + 1) + ".html";
            write_file(dir + "/" + file, timeline_svg(online->streams[s], labels));
            write_file(dir + "/" + page, viewer_html(online->streams[s], labels, title + ": " + online->streams[s].name));
            md << "![" << online->streams[s].name << "](" << file << ")\n\n[Watch " << online->streams[s].name
               << " with its labels](" << page << ") (a self-contained page: the skeleton, the timelines, the margin).\n\n";
        }
    }
    write_file(dir + "/report.md", md.str());
}

}  // namespace host
}  // namespace actionstring
