// `actionstring eval`: clip recognition on a list, beside baselines.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/json.hpp"
#include "common/paths.hpp"
#include "common/stats.hpp"
#include "common/time.hpp"
#include "eval/baselines.hpp"
#include "eval/clip_eval.hpp"
#include "eval/evaluation.hpp"
#include "eval/json.hpp"
#include "eval/online.hpp"
#include "eval/perturb.hpp"
#include "eval/report.hpp"
#include "io/clip_list.hpp"
#include "io/recordings.hpp"
#include "io/text.hpp"
#include "model/artifact.hpp"
#include "run/skeleton.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {
namespace {

void print_eval_usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: actionstring eval --model MODEL --clips LIST [--train LIST] [--json FILE]\n"
                 "                         [--online] [--seed N] [--rate HZ] [--roles R,L,R] [--length-unit U]\n"
                 "                         [--parents P,P,...]\n"
                 "                         [--settle S] [--settle-stable S] [--segment-penalty X]\n"
                 "                         [--stay-penalty X]\n"
                 "                         [--skip-penalty X] [--unknown-cost X] [--segment-votes X]\n"
                 "                         [--segment-exemplars X] [--segment-directions X]\n"
                 "                         [--min-action S] [--label-lead S]\n"
                 "                         [--max-pose-speed V] [--spread-work]\n"
                 "                         [--report DIR] [--perturb SPEC] [--up X,Y,Z]\n"
                 "\n"
                 "Classifies every clip of LIST with the runtime's own code and reports clip\n"
                 "accuracy, per-class precision and recall, each subject's clip accuracy, the\n"
                 "confusion matrix, the unknown rate, the model's top-1 to top-3 accuracy (the\n"
                 "true label among the labels' best scores, before rejection; --json: top_k)\n"
                 "and the annotator's per-frame time. With\n"
                 "--train (the model's training list) the same run adds baselines on the same\n"
                 "split: 1-NN over all training strings (no representatives), the same with\n"
                 "PCA-only characters (no GMM; paper Fig. 4), and DTW 1-NN on normalised poses.\n"
                 "With --online it also concatenates each subject's clips in a seeded shuffled\n"
                 "order and streams them frame by frame through the annotator, as a device would,\n"
                 "reporting frame accuracy, segment F1 (IoU >= 0.5), label delay and flicker (and\n"
                 "for settled labels how long after its frame each became final) for\n"
                 "each rule: the segmenter's settled labels (the annotator's timeline, final\n"
                 "--settle seconds after the frame [2], or sooner once the best explanation has\n"
                 "kept it --settle-stable seconds), its live labels (no delay), and the\n"
                 "paper's latest-window rule, then each class's settled frames: recall, precision,\n"
                 "F1 and what its other frames were most often taken for (in --json the whole\n"
                 "frame confusion), and the settled labels' figures on each stream alone (a\n"
                 "subject's clips joined, or one recording). A list with 'start' and 'end' columns names labelled\n"
                 "intervals of continuous recordings: clips are the intervals, and --online\n"
                 "streams each recording whole (frames outside every interval: no action).\n"
                 "The online options override the settings the model carries (chosen at\n"
                 "training): --unknown-cost inf turns 'no action' off; --segment-votes X weighs\n"
                 "the characters' label votes in the explanation, --segment-exemplars X the\n"
                 "exemplars, --segment-directions X the last characters' motion directions (a\n"
                 "model trained with --direction-window); --min-action S: a settled run of one\n"
                 "label shorter than S seconds is flicker, never reported as an action event (as\n"
                 "annotate --min-action);\n"
                 "--label-lead S: each character's label applies S seconds before its tick\n"
                 "(the feature's motion looks back, so actions show in it late), for the\n"
                 "frames' labels and the events' times.\n"
                 "--max-pose-speed V: a pose that moved faster than V m/s since the previous\n"
                 "frame (the mean over its coordinates), and by three times what the stream's\n"
                 "frames typically move, jumped (tracking lost and found, clips joined), and its\n"
                 "motion starts again from it [3; 0: never].\n"
                 "--spread-work spreads each character's work (encoder and segmenter) over the\n"
                 "frames until the next character (AnnotatorConfig::spread_work): the same labels and\n"
                 "events, each reported up to one string period later (the latency shows it).\n"
                 "--report DIR writes SVG pictures (confusion matrix, true vs predicted timelines)\n"
                 "and a Markdown summary linking them.\n"
                 "--up X,Y,Z is the sensor's up direction in the files' coordinates, when it is\n"
                 "tilted and known (a Kinect's floor plane normal): every frame of both lists is\n"
                 "turned upright as it is read (a list's own 'up' column wins for its lines).\n"
                 "--perturb SPEC changes the evaluated clips and recordings (never the training\n"
                 "clips) as another sensor or person would, so every figure, the baselines'\n"
                 "too, is measured on the changed clips: SPEC is name=value items separated by\n"
                 "commas: scale=F (positions times F: 0.7 is a child beside an adult),\n"
                 "mirror=1 (the other side of the body: a left-handed performer),\n"
                 "tilt=DEG (each frame turned DEG degrees about the hips' horizontal line, as\n"
                 "a sensor mounted higher or lower sees the performer), noise=M (Gaussian\n"
                 "noise of M metres on every coordinate), rate=HZ (resampled to HZ by linear\n"
                 "interpolation), jitter=S (timestamps moved by up to +-S seconds), drop=P\n"
                 "(each frame but the first and last missing with probability P), seed=N [1];\n"
                 "e.g. --perturb scale=0.7,noise=0.01.\n");
}

void print_online(const char* rule, const host::OnlineResults& r) {
    std::printf("  %-28s frame accuracy %.3f (95%% %.3f-%.3f)", rule, r.frame_accuracy, r.frame_accuracy_interval.low,
                r.frame_accuracy_interval.high);
    if (r.no_action_frames > 0)
        std::printf(" (in actions %.3f, no action %.3f; %+.3f over unknown everywhere, 95%% %+.3f to %+.3f)",
                    r.action_frame_accuracy, r.no_action_accuracy, r.frame_accuracy - r.unknown_everywhere_accuracy,
                    r.gain_over_unknown_interval.low, r.gain_over_unknown_interval.high);
    std::printf(
        ", frame F1 %.3f, segment F1 %.3f (95%% %.3f-%.3f; P %.3f, R %.3f), mean delay %.2f s, %d missed, flicker "
        "%.1f/min\n",
        r.frame_f1, r.segment_f1, r.segment_f1_interval.low, r.segment_f1_interval.high, r.segment_precision,
        r.segment_recall, r.mean_delay_s, r.missed_segments, r.flicker_per_min);
    if (r.final_after_p95_s > 0)
        std::printf("  %-28s labels final a median %.2f s after their frame (95th percentile %.2f s)\n", "",
                    r.final_after_median_s, r.final_after_p95_s);
    if (r.has_events)
        std::printf(
            "  %-28s %zu actions reported, %zu matched (event F1 %.3f; as segments, IoU >= 0.5: %zu, F1 %.3f,\n"
            "  %-28s 95%% %.3f-%.3f), detection latency %.2f s, start error %.2f s (bias %+.2f),\n"
            "  %-28s end error %.2f s (bias %+.2f), %.2f false events per %s\n",
            "  events (once per action)", r.events, r.matched_events, r.event_f1, r.iou_matched_events,
            r.event_segment_f1, "", r.event_segment_f1_interval.low, r.event_segment_f1_interval.high,
            r.detection_latency_s, r.start_error_s, r.start_bias_s, "", r.end_error_s, r.end_bias_s,
            r.false_events_per_min, r.false_events_per_stream_min ? "minute of stream" : "minute of no action");
}

// Each class's settled frames: how many were labelled with it (recall), how
// many labelled with it were it (precision), and what its other frames were
// taken for, where a stream's frame accuracy hides it (a short action missed
// entirely, one action called another).
void print_frame_classes(const host::OnlineResults& r, const std::vector<std::string>& labels) {
    auto name = [&labels](int label) { return host::frame_class_name(label, labels); };
    std::printf(
        "\nsettled frames per class (recall: its frames labelled with it; precision: frames labelled with it "
        "that are it):\n  %-32s %7s %7s %9s %6s  %s\n",
        "label", "frames", "recall", "precision", "F1", "its other frames most often taken for");
    for (const host::FrameClassScore& c : host::frame_class_scores(r)) {
        std::printf("  %-32s %7zu %7.3f %9.3f %6.3f", name(c.label).c_str(), c.frames, c.recall, c.precision, c.f1);
        if (c.most_taken_for_frames > 0)
            std::printf("  %s (%zu)", name(c.most_taken_for).c_str(), c.most_taken_for_frames);
        std::printf("\n");
    }
}

// The settled labels on each stream alone: which subjects or recordings the pooled figures come from.
void print_streams(const host::OnlineReport& report) {
    const bool no_action = report.settled.no_action_frames > 0;
    std::printf("\nsettled labels per stream (%s):\n  %-32s %7s %9s", report.recordings ? "recordings" : "subjects",
                "stream", "frames", "accuracy");
    if (no_action) std::printf(" %9s %9s %9s", "in action", "no action", "unknown*");
    std::printf(" %8s %10s %8s\n", "frame F1", "segment F1", "event F1");
    // A stream where saying unknown everywhere would do better is named: the pooled
    // figure can be above the trivial baseline while a recording is below it.
    std::string below;
    std::size_t below_count = 0;
    for (std::size_t s = 0; s < report.per_stream.size() && s < report.streams.size(); ++s) {
        const host::OnlineResults& r = report.per_stream[s];
        std::printf("  %-32s %7zu %9.3f", report.streams[s].name.c_str(), r.frames, r.frame_accuracy);
        if (no_action) std::printf(" %9.3f %9.3f %9.3f", r.action_frame_accuracy, r.no_action_accuracy,
                                   r.unknown_everywhere_accuracy);
        std::printf(" %8.3f %10.3f %8.3f\n", r.frame_f1, r.segment_f1, r.event_f1);
        if (no_action && r.frame_accuracy < r.unknown_everywhere_accuracy) {
            below += (below_count++ ? ", " : "") + report.streams[s].name;
        }
    }
    if (no_action) {
        std::printf("  * unknown everywhere on that stream alone (its share of no-action frames)\n");
        if (below_count > 0)
            std::printf("  below unknown everywhere: %zu of %zu streams (%s)\n", below_count, report.per_stream.size(),
                        below.c_str());
        else
            std::printf("  every stream above unknown everywhere\n");
    }
}

void print_results(const host::ClipResults& r) {
    std::printf("  %-44s clip accuracy %.3f (95%% %.3f-%.3f), unknown %.3f\n", r.method.c_str(), r.clip_accuracy,
                r.accuracy_interval.low, r.accuracy_interval.high, r.unknown_rate);
    if (!r.top_k.empty()) {
        std::printf("  %-44s   true label among the labels' k best scores (before rejection):", "");
        for (std::size_t k = 0; k < r.top_k.size(); ++k) std::printf(" top-%zu %.3f", k + 1, r.top_k[k]);
        std::printf("\n");
    }
    if (r.paired)
        std::printf(
            "  %-44s   paired with the model: the model alone right on %zu clips, this alone on %zu; McNemar p %.3f\n",
            "", r.model_only, r.method_only, r.mcnemar_p);
}

using host::Evaluation;

// Reads the list (and the training list for the baselines), then evaluates.
Evaluation evaluate(const ModelView& view, const std::string& clips_path, const std::string& train_path,
                    const host::ReadOptions& read, bool online, std::uint32_t seed, const AnnotatorConfig& config,
                    const host::Perturbation& perturbation) {
    const std::vector<host::ClipListEntry> entries = host::read_clip_list(clips_path);
    std::vector<host::LabelledClip> train;
    if (!train_path.empty()) train = host::load_labelled_clips(train_path, read);
    std::vector<host::LabelledRecording> recordings;
    if (online && host::has_intervals(entries)) recordings = host::read_recordings(entries, read);
    for (const host::LabelledRecording& recording : recordings)
        for (const std::string& note : recording.notes) std::fprintf(stderr, "eval: note: %s\n", note.c_str());
    Evaluation e = host::evaluate(view, host::load_labelled_clips(entries, read), std::move(train),
                                  std::move(recordings), online, seed, config, perturbation);
    e.recordings = host::has_intervals(entries);
    return e;
}

void print_evaluation(const Evaluation& e, const std::string& clips_path, std::uint32_t seed) {
    const host::ClipResults& main = e.results.front();
    std::printf("%s: %zu clips\n", clips_path.c_str(), e.clips.size());
    if (e.perturbation != "none")
        std::printf("evaluated clips perturbed: %s; training clips as read\n", e.perturbation.c_str());
    for (const auto& r : e.results) print_results(r);
    std::printf("  %-44s %zu of %zu synthetic non-actions from these clips come out unknown\n",
                "rejection (model, label_bounds)", e.synthetic_unknown, e.synthetic_negatives);
    std::printf("\nper class (action strings):\n  %-32s %9s %7s\n", "label", "precision", "recall");
    for (std::size_t l = 0; l < main.labels.size(); ++l)
        std::printf("  %-32s %9.3f %7.3f\n", main.labels[l].c_str(), main.precision[l], main.recall[l]);
    if (!main.per_subject.empty()) {
        // Every method's accuracy on each subject's clips, the model's first: the baselines' results
        // are in the same order as e.results.
        std::printf("\nper subject (clip accuracy; the model, then each baseline in the order above):\n");
        for (std::size_t s = 0; s < main.per_subject.size(); ++s) {
            const host::SubjectScore& score = main.per_subject[s];
            std::printf("  %-32s %4zu clips", score.subject.c_str(), score.clips);
            for (const auto& r : e.results)
                if (s < r.per_subject.size()) std::printf(" %7.3f", r.per_subject[s].accuracy);
            std::printf("\n");
        }
    }
    std::printf("\nconfusion (rows true, columns predicted in label order, last column unknown):\n");
    for (std::size_t t = 0; t < main.confusion.size(); ++t) {
        std::printf("  %-32s", main.labels[t].c_str());
        for (int v : main.confusion[t]) std::printf(" %3d", v);
        std::printf("\n");
    }
    if (e.online) {
        const host::OnlineResults& stream = e.online_report.settled;
        if (e.recordings)
            std::printf(
                "\nonline: %zu continuous recordings streamed whole, %zu frames, %.1f true label changes/min;\n"
                "%.3f of the frames are outside every interval (no action), so saying unknown everywhere scores that\n",
                e.online_report.streams.size(), stream.frames, stream.true_changes_per_min,
                stream.frames == 0 ? 0.0
                                   : static_cast<double>(stream.no_action_frames) / static_cast<double>(stream.frames));
        else
            std::printf("\nonline: clips concatenated per subject (seed %u), %zu frames, %.1f true label changes/min\n",
                        seed, stream.frames, stream.true_changes_per_min);
        if (e.no_action_stretches > 0)
            std::printf("  %-28s %zu of %zu unlabelled stretches (>= 1 s) classified as clips come out unknown\n",
                        "rejection of no action", e.no_action_unknown, e.no_action_stretches);
        std::printf("  %-28s frame accuracy %.3f\n", "baseline: unknown everywhere",
                    e.online_report.settled.unknown_everywhere_accuracy);
        print_online("segmenter, settled labels", e.online_report.settled);
        print_online("segmenter, live labels", e.online_report.live);
        print_online("paper: latest window wins", e.online_report.window);
        print_frame_classes(e.online_report.settled, main.labels);
        print_streams(e.online_report);
    }
    std::printf(
        "\nannotator per frame (host build, the online figures' settings%s, %zu frames): median %.0f ns, p99 %.0f ns, "
        "max %.0f ns\n",
        e.frame_spread ? ", work spread" : "", e.frame_ns.size(), host::sorted_quantile(e.frame_ns, 0.5),
        host::sorted_quantile(e.frame_ns, 0.99), host::sorted_quantile(e.frame_ns, 1.0));
}

}  // namespace

int run_eval(int argc, char** argv) {
    std::string model_path, clips_path, train_path, json_path;
    host::ReadOptions read;
    bool online = false;
    std::uint32_t seed = 1;
    OnlineOverrides overrides;
    std::string report_dir, perturb_spec;
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
        else if (arg == "--length-unit") read.length_scale = parse_length_unit(args, args.value(arg));
        else if (arg == "--parents") read.parents = parse_parents(args, args.value(arg));
        else if (arg == "--online") online = true;
        else if (arg == "--seed") seed = static_cast<std::uint32_t>(args.whole(arg, 0, 4294967295.0));
        else if (arg == "--roles") read.roles = parse_roles(args, args.value(arg));
        else if (arg == "--report") report_dir = args.value(arg);
        else if (arg == "--perturb") perturb_spec = args.value(arg);
        else if (parse_up_option(args, arg, read.up)) continue;
        else if (!parse_online_option(args, arg, overrides)) return args.unknown(arg);
    }
    if (!args.ok()) return 2;
    if (model_path.empty() || clips_path.empty()) {
        print_eval_usage(stderr);
        return 2;
    }
    return run_reporting_errors("eval", [&] {
        const host::ModelData model = host::load_model(model_path);
        const ModelView view = model.view();
        const AnnotatorConfig config = overrides.over(view, args);
        const host::Perturbation perturbation =
            perturb_spec.empty() ? host::Perturbation{} : host::parse_perturbation(perturb_spec);
        const Evaluation e = evaluate(view, clips_path, train_path, read, online, seed, config, perturbation);
        print_evaluation(e, clips_path, seed);
        if (!report_dir.empty()) {
            std::string title = "Evaluation of " + host::short_path(model_path) + " on " + host::short_path(clips_path);
            if (e.perturbation != "none") title += ", perturbed: " + e.perturbation;
            host::write_report(report_dir, title, e.results, online ? &e.online_report : nullptr,
                               model.label_names.strings());
            std::printf("\nreport: %s/report.md\n", report_dir.c_str());
        }
        if (!json_path.empty()) host::write_file(json_path, host::evaluation_json(e, model_path, seed, config));
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
