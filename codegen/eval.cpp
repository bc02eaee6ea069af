// `actionstring eval`: clip recognition on a list, beside baselines.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "actionstring_host/artifact.hpp"
#include "actionstring_host/evaluation.hpp"
#include "actionstring_host/readers.hpp"
#include "actionstring_host/report.hpp"
#include "commands.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {
namespace {

void print_eval_usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: actionstring eval --model MODEL --clips LIST [--train LIST] [--json FILE]\n"
                 "                         [--online] [--seed N] [--rate HZ] [--roles R,L,R]\n"
                 "                         [--settle S] [--segment-penalty X] [--stay-penalty X]\n"
                 "                         [--skip-penalty X] [--unknown-cost X] [--report DIR]\n"
                 "\n"
                 "Classifies every clip of LIST with the runtime's own code and reports clip\n"
                 "accuracy, per-class precision and recall, the confusion matrix, the unknown rate\n"
                 "and the annotator's per-frame time. With --train (the model's training list) the\n"
                 "same run adds baselines on the same split: 1-NN over all training strings (no\n"
                 "representatives), the same with PCA-only characters (no GMM; paper Fig. 4),\n"
                 "and DTW 1-NN on normalised poses.\n"
                 "With --online it also concatenates each subject's clips in a seeded shuffled\n"
                 "order and streams them frame by frame through the annotator, as a device would,\n"
                 "reporting frame accuracy, segment F1 (IoU >= 0.5), label delay and flicker for\n"
                 "each rule: the segmenter's settled labels (the annotator's timeline, final\n"
                 "--settle seconds after the frame [2]), its live labels (no delay), and the\n"
                 "paper's latest-window rule. A list with 'start' and 'end' columns names labelled\n"
                 "intervals of continuous recordings: clips are the intervals, and --online\n"
                 "streams each recording whole (frames outside every interval: no action).\n"
                 "The segmenter options are AnnotatorConfig's\n"
                 "(defaults in segmenter.hpp; --unknown-cost inf turns 'no action' off).\n"
                 "--report DIR writes SVG pictures (confusion matrix, true vs predicted timelines)\n"
                 "and a Markdown summary linking them.\n");
}

std::vector<host::LabelledClip> load(const std::vector<host::ClipListEntry>& entries, const host::ReadOptions& read) {
    std::vector<host::LabelledClip> clips;
    for (const host::ClipListEntry& entry : entries)
        clips.push_back({host::read_clip(entry, read), entry.label, entry.subject});
    return clips;
}

void print_online(const char* rule, const host::OnlineResults& r) {
    std::printf("  %-28s frame accuracy %.3f", rule, r.frame_accuracy);
    if (r.no_action_frames > 0)
        std::printf(" (in actions %.3f, no action %.3f)", r.action_frame_accuracy, r.no_action_accuracy);
    std::printf(", segment F1 %.3f (P %.3f, R %.3f), mean delay %.2f s, %d missed, flicker %.1f/min\n",
                r.segment_f1, r.segment_precision, r.segment_recall, r.mean_delay_s, r.missed_segments,
                r.flicker_per_min);
}

std::string online_json(const host::OnlineResults& r) {
    std::ostringstream out;
    out.precision(6);
    out << "{\"frames\": " << r.frames << ", \"frame_accuracy\": " << r.frame_accuracy << ", \"no_action_frames\": " << r.no_action_frames
        << ", \"action_frame_accuracy\": " << r.action_frame_accuracy << ", \"no_action_accuracy\": " << r.no_action_accuracy
        << ", \"segment_f1\": " << r.segment_f1
        << ", \"segment_precision\": " << r.segment_precision << ", \"segment_recall\": " << r.segment_recall
        << ", \"mean_delay_s\": " << r.mean_delay_s << ", \"missed_segments\": " << r.missed_segments
        << ", \"flicker_per_min\": " << r.flicker_per_min << ", \"label_changes_per_min\": " << r.label_changes_per_min
        << ", \"true_changes_per_min\": " << r.true_changes_per_min << "}";
    return out.str();
}

void print_results(const host::ClipResults& r) {
    std::printf("  %-44s clip accuracy %.3f, unknown %.3f\n", r.method.c_str(), r.clip_accuracy, r.unknown_rate);
}

}  // namespace

int run_eval(int argc, char** argv) {
    std::string model_path, clips_path, train_path, json_path;
    host::ReadOptions read;
    bool online = false;
    std::uint32_t seed = 1;
    AnnotatorConfig config;
    std::string report_dir;
    ArgumentReader args("eval", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            print_eval_usage(stdout);
            return 0;
        }
        if (arg == "--model") model_path = args.value(arg);
        else if (arg == "--clips") clips_path = args.value(arg);
        else if (arg == "--train") train_path = args.value(arg);
        else if (arg == "--json") json_path = args.value(arg);
        else if (arg == "--rate") read.frame_rate_hz = args.number(arg, 0.001, 1e6);
        else if (arg == "--online") online = true;
        else if (arg == "--seed") seed = static_cast<std::uint32_t>(args.number(arg, 0, 4294967295.0));
        else if (arg == "--roles") read.roles = parse_roles(args, args.value(arg));
        else if (!parse_segmenter_option(args, arg, config.segmenter)) {
            if (arg == "--report") report_dir = args.value(arg);
            else return args.unknown(arg);
        }
    }
    if (!args.ok()) return 2;
    if (model_path.empty() || clips_path.empty()) {
        print_eval_usage(stderr);
        return 2;
    }
    try {
        host::ModelData model = host::load_model(model_path);
        const ModelView view = model.view();
        const std::vector<host::ClipListEntry> entries = host::read_clip_list(clips_path);
        const bool recordings = std::any_of(entries.begin(), entries.end(), [](const host::ClipListEntry& e) { return e.has_interval; });
        const std::vector<host::LabelledClip> clips = load(entries, read);
        std::vector<host::ClipResults> results{host::evaluate_model(view, clips)};
        if (!train_path.empty()) {
            const auto train = load(host::read_clip_list(train_path), read);
            results.push_back(host::evaluate_all_strings(view, train, clips));
            results.push_back(host::evaluate_pca_characters(view, train, clips));
            results.push_back(host::evaluate_pose_dtw(view, train, clips));
        }
        const std::vector<double> frame_ns = host::annotator_frame_times(view, clips);
        host::OnlineReport online_report;
        if (online)
            online_report = recordings ? host::evaluate_recordings(view, host::read_recordings(entries, read), config)
                                       : host::evaluate_online(view, clips, seed, config);
        const host::OnlineResults& stream = online_report.settled;
        auto at = [&](double q) {
            return frame_ns.empty() ? 0.0 : frame_ns[std::min(frame_ns.size() - 1, static_cast<std::size_t>(q * static_cast<double>(frame_ns.size())))];
        };

        const host::ClipResults& main = results.front();
        std::printf("%s: %zu clips\n", clips_path.c_str(), clips.size());
        for (const auto& r : results) print_results(r);
        std::printf("\nper class (action strings):\n  %-32s %9s %7s\n", "label", "precision", "recall");
        for (std::size_t l = 0; l < main.labels.size(); ++l)
            std::printf("  %-32s %9.3f %7.3f\n", main.labels[l].c_str(), main.precision[l], main.recall[l]);
        std::printf("\nconfusion (rows true, columns predicted in label order, last column unknown):\n");
        for (std::size_t t = 0; t < main.confusion.size(); ++t) {
            std::printf("  %-32s", main.labels[t].c_str());
            for (int v : main.confusion[t]) std::printf(" %3d", v);
            std::printf("\n");
        }
        if (online) {
            if (recordings)
                std::printf("\nonline: %zu continuous recordings streamed whole, %zu frames, %.1f true label changes/min;\n"
                            "%.3f of the frames are outside every interval (no action), so saying unknown everywhere scores that\n",
                            online_report.streams.size(), stream.frames, stream.true_changes_per_min,
                            stream.frames == 0 ? 0.0 : static_cast<double>(stream.no_action_frames) / static_cast<double>(stream.frames));
            else
                std::printf("\nonline: clips concatenated per subject (seed %u), %zu frames, %.1f true label changes/min\n", seed,
                            stream.frames, stream.true_changes_per_min);
            print_online("segmenter, settled labels", online_report.settled);
            print_online("segmenter, live labels", online_report.live);
            print_online("paper: latest window wins", online_report.window);
        }
        std::printf("\nannotator per frame (host build, HostCapacity, %zu frames): median %.0f ns, p99 %.0f ns, max %.0f ns\n",
                    frame_ns.size(), at(0.5), at(0.99), frame_ns.empty() ? 0.0 : frame_ns.back());
        if (!report_dir.empty()) {
            host::write_report(report_dir, "Evaluation of " + model_path + " on " + clips_path, results, online ? &online_report : nullptr,
                               std::vector<std::string>(view.label_names, view.label_names + view.label_count));
            std::printf("\nreport: %s/report.md\n", report_dir.c_str());
        }
        if (!json_path.empty()) {
            std::ofstream out(json_path);
            std::string json = host::to_json(main, clips);
            json.pop_back();  // extend the model's object with the rest
            out << json << ", \"model\": " << host::json_string(model_path) << ", \"frame_time_ns\": {\"median\": " << at(0.5) << ", \"p99\": " << at(0.99)
                << ", \"max\": " << (frame_ns.empty() ? 0.0 : frame_ns.back()) << "}, \"baselines\": [";
            for (std::size_t i = 1; i < results.size(); ++i) out << (i > 1 ? ", " : "") << host::to_json(results[i], clips);
            out << "]";
            if (online)
                out << ", \"frame_accuracy\": " << stream.frame_accuracy << ", \"online\": {\"streams\": " << (recordings ? "\"recordings\"" : "\"concatenated clips\"") << ", \"seed\": " << seed
                    << ", \"settle_delay_s\": " << static_cast<double>(config.segmenter.settle_delay_us) * 1e-6
                    << ", \"settled\": " << online_json(online_report.settled) << ", \"live\": " << online_json(online_report.live)
                    << ", \"latest_window\": " << online_json(online_report.window) << "}";
            out << "}\n";
            if (!out) {
                std::fprintf(stderr, "actionstring eval: cannot write %s\n", json_path.c_str());
                return 1;
            }
        }
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring eval: %s\n", error.what());
        return 1;
    }
}

}  // namespace cli
}  // namespace actionstring
