// `actionstring train`: a model from a clip list (settings, config files, sweeps).
#include <chrono>
#include <set>
#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "common/json.hpp"
#include "common/time.hpp"
#include "io/clip_list.hpp"
#include "io/recordings.hpp"
#include "io/text.hpp"
#include "model/artifact.hpp"
#include "options.hpp"
#include "run/classify.hpp"
#include "train/cross_validation.hpp"
#include "train/pipeline.hpp"
#include "train/online_tuning.hpp"
#include "train/tuning.hpp"

namespace actionstring {
namespace cli {
namespace {

void print_train_usage(std::FILE* out) {
    const host::TrainingOptions d;
    std::fprintf(out,
                 "usage: actionstring train --clips LIST --out MODEL [options] [--config FILE]\n"
                 "                          [--validate LIST] [--sweep] [--json FILE]\n"
                 "\n"
                 "Trains a model from a clip list (TSV: path label subject [skeleton]) and writes\n"
                 "the checksummed model artifact. Options (defaults in brackets):\n"
                 "  --components J          GMM key-poses; 0 = no GMM, the tree on projected poses\n"
                 "                          (the paper's \"PCA only\" characters) [%d]\n"
                 "  --covariance full|diagonal                     [full]\n"
                 "  --covariance-floor V    MAP variance floor per average component, units^2 [%g]\n"
                 "  --pca D                 project poses to D dimensions, 0 = none [%d]\n"
                 "  --feature-rate HZ       frames per second used to fit the GMM and tree [%g]\n"
                 "  --em-iterations N       [%d]     --em-tolerance X  relative [%g]\n"
                 "  --em-restarts N         EM runs from seeds seed..seed+N-1; the highest training\n"
                 "                          likelihood is kept [%d]\n"
                 "  --scale none|hip-width|bones|torso  size normalisation of poses: none, by\n"
                 "                          hip width, every bone at its mean training length,\n"
                 "                          or the whole pose by the torso's length [none]\n"
                 "  --velocity W            weight of the pose's velocity beside the pose, 0 = none [%g]\n"
                 "  --velocity-span S       seconds the velocity (and acceleration) is taken over [%g]\n"
                 "  --acceleration W        weight of the change of that velocity across the span, 0 = none [%g]\n"
                 "  --epsilon E             split clusters whose L1 diameter is >= E [%g]\n"
                 "  --max-characters K      cap on tree leaves [%d]\n"
                 "  --string-rate HZ        characters per second [%g]\n"
                 "  --variant paper|whole|subsequence              [whole]\n"
                 "  --normalization none|path|query                [none]\n"
                 "  --sigma S               merge string clusters while their distance <= S [%g]\n"
                 "  --keep-singletons       keep clusters of one string as representatives\n"
                 "  --reject                learn each label's rejection bound from held-out training\n"
                 "                          clips and synthetic negatives (spliced halves, sped-up and\n"
                 "                          slowed-down clips; with recordings, their unlabelled\n"
                 "                          stretches): what is unlike a label's clips is unknown\n"
                 "  --reject-keep F         fraction of each label's held-out clips its bound keeps [0.95]\n"
                 "  --max-representative-chars N  bound on all representatives' characters, which the\n"
                 "                          segmenter passes over once per character (its cost per\n"
                 "                          frame): clusters keep merging past sigma until they fit [none]\n"
                 "  --max-representative-share F  the same bound as a share (0 < F < 1) of the characters\n"
                 "                          sigma's clusters leave: it means the same on lists of any size [none]\n"
                 "  --mirror                also train on every clip mirrored (left and right swapped)\n"
                 "  --pose-joints A,B,...   the joints the model reads (root and hips added); default:\n"
                 "                          an engine rig's body joints (CC_Base, Mixamo, Unreal, Unity\n"
                 "                          humanoid: no fingers, twist or face bones), else every joint\n"
                 "  --neighbours K          k of the kNN vote [%d]\n"
                 "  --exemplars N           k-means centres of each label's training features, compared\n"
                 "                          with a clip's features beside its string, 0 = none [0]\n"
                 "  --exemplar-weight W     their weight beside DTW and the votes, 0 = none [0]\n"
                 "  --exemplar-dims K       the features' first K coordinates the centres keep and\n"
                 "                          compare, for speed (K multiply-adds per centre), 0 = all [0]\n"
                 "  --descriptor-levels N   the clip descriptor: a pyramid of N levels (level v cuts a clip\n"
                 "                          in v parts) of the features' means and covariances, scored\n"
                 "                          per label by ridge regression, beside the strings, 0 = none [0]\n"
                 "  --descriptor-weight W   its weight beside DTW, the votes and the exemplars [0]\n"
                 "  --descriptor-dims K     the features' first K coordinates it reads, 0 = all (at most 64) [0]\n"
                 "  --descriptor-ridge X    the ridge regression's penalty on squared weights [1000]\n"
                 "  --direction-levels N    the motion directions: a pyramid of N levels of each pose\n"
                 "                          joint's step directions (8 sectors in 3 planes, the clip\n"
                 "                          turned by its first facing), scored per label by a second\n"
                 "                          ridge regression beside the descriptor, 0 = none [0]\n"
                 "  --direction-weight W    its weight [0]\n"
                 "  --direction-ridge X     its ridge regression's penalty on squared weights [1000]\n"
                 "  --direction-window S    the same histograms over a stream's last S seconds of\n"
                 "                          characters, scored per label by a third ridge regression\n"
                 "                          fitted on every training clip's windows, for the segmenter\n"
                 "                          (--segment-directions weighs it), 0 = none [0]\n"
                 "  --direction-window-ridge X  its ridge regression's penalty [1000]\n"
                 "  --no-action-exemplars true|false  with a list of recordings, centres of their\n"
                 "                          unlabelled stretches too, for the segmenter [true]\n"
                 "  --window S, --step S    sliding window and step in seconds [%g, %g]\n"
                 "  --unknown-distance X    label unknown above this distance [never]\n"
                 "  --settle S, --segment-penalty X, --stay-penalty X, --skip-penalty X, --unknown-cost X\n"
                 "                          the segmenter's online settings, stored in the model for\n"
                 "                          devices, eval and annotate [2, 3, 0.3, 0.3, inf]\n"
                 "  --settle-stable S       stored in the model: a label is also final once every best\n"
                 "                          explanation has given it for S seconds, before the settle\n"
                 "                          delay (a clear action settles early); 0 = the delay alone [0]\n"
                 "  --min-action S          the events' shortest action, stored in the model: a\n"
                 "                          shorter settled run is flicker, never reported [0.25]\n"
                 "  --label-lead S          stored in the model: each character's label applies S\n"
                 "                          seconds before its tick, as the feature's motion looks\n"
                 "                          back and actions show in it late [0]\n"
                 "  --seed N                [%u]\n"
                 "  --rate HZ               frame rate of files without timing (AMC 120, MSR 15)\n"
                 "  --roles R,L,R           root, left hip, right hip joint names\n"
                 "  --length-unit U         m, dm, cm, mm or in: the length unit of files that state\n"
                 "                          none (a CSV's is read off the body's height otherwise)\n"
                 "  --parents P,P,...       each joint's parent by name in the files' joint order, - for\n"
                 "                          a root: the bone tree of a rig whose files give none (a CSV\n"
                 "                          of joints no Kinect SDK names), for --scale bones or torso\n"
                 "  --up X,Y,Z              the sensor's up direction in the files' coordinates, when\n"
                 "                          tilted and known: every frame is turned upright as read\n"
                 "                          (a list's own 'up' column wins for its lines)\n"
                 "  --config FILE           'option value' lines, same names without dashes\n"
                 "  --validate LIST         report clip accuracy on LIST after training\n"
                 "  --json FILE             write the training report (sizes, stage times) as JSON\n"
                 "  --no-tune               with no settings given, train with the defaults instead of\n"
                 "                          choosing ε, σ, the string rate, velocity, size scaling and\n"
                 "                          PCA by leave-one-subject-out cross-validation (the default)\n"
                 "  --tune-online           with settings given (a config of clip settings), still\n"
                 "                          choose the online ones as self-tuning does: the segmenter's,\n"
                 "                          the window's directions (a window of 1.5 s when the config\n"
                 "                          has none), the events' shortest action and the label lead,\n"
                 "                          by streaming each held-out subject; they replace the given\n"
                 "                          online settings\n"
                 "  --cv                    leave-one-subject-out cross-validation over the list's\n"
                 "                          subject column: a fold table and the mean (no model written)\n"
                 "  --sweep                 with --validate: vary one setting at a time around the\n"
                 "                          given ones and print a table (choose on validation data)\n",
                 d.components, d.covariance_floor, d.pca_dim, d.feature_rate_hz, d.em_max_iterations, d.em_tolerance,
                 d.em_restarts, d.velocity_weight, d.velocity_span_s, d.acceleration_weight, d.epsilon,
                 d.max_characters, d.string_rate_hz, d.sigma, d.neighbours, d.window_seconds, d.step_seconds, d.seed);
}

bool apply(ArgumentReader& args, const std::string& name, const std::string& value, host::TrainingOptions& o,
           host::ReadOptions& read) {
    try {
        return host::apply_training_setting(name, value, o, read);
    } catch (const std::invalid_argument& error) {
        args.error(error.what());
        return true;
    }
}

const char* variant_name(MatchVariant v) {
    return v == MatchVariant::paper ? "paper" : v == MatchVariant::whole ? "whole" : "subsequence";
}
const char* normalization_name(LengthNormalization n) {
    return n == LengthNormalization::none ? "none" : n == LengthNormalization::path ? "path" : "query";
}

// A config file (host::read_training_config), a problem reported through `args`.
bool read_config(ArgumentReader& args, const std::string& path, host::TrainingOptions& options,
                 host::ReadOptions& read) {
    try {
        host::read_training_config(path, options, read);
        return true;
    } catch (const host::ReadError& error) {
        args.error(std::string("--config: ") + error.what());
        return false;
    }
}

// The training run as JSON: the model's sizes, what each stage saw and took.
std::string training_json(const std::string& model_path, const ModelView& view, const host::TrainingReport& report,
                          const host::TrainingOptions& options) {
    host::JsonWriter out;
    out.begin_object()
        .field("model", model_path)
        .field("settings", host::options_as_config(options))
        .field("frames_read", report.frames_read)
        .field("frames_rejected", report.frames_rejected)
        .field("feature_samples", report.feature_samples)
        .field("components", static_cast<int>(view.component_count))
        .field("em_iterations", report.em.objective.size())
        .field("em_converged", report.em.converged)
        .field("characters", report.characters)
        .field("strings", report.strings)
        .field("representatives", report.representatives)
        .field("representative_chars", static_cast<unsigned long>(view.total_representative_chars()))
        .field("table_bytes", host::table_bytes(view));
    out.key("stage_seconds").begin_object();
    double total = 0;
    for (const auto& stage : report.stage_seconds) {
        out.field(stage.first, stage.second);
        total += stage.second;
    }
    out.field("total", total).end_object();
    return out.end_object().str();
}

// With no settings given: tune them by cross-validation over the list's
// subjects (one subject only: the starting settings), showing each step.
host::TuningResult tune(const std::vector<host::LabelledClip>& clips, const host::TrainingOptions& given) {
    host::TrainingOptions start = host::tuning_start();
    // The skeleton and the cost bound are the user's choices, not tuned
    // settings: the folds train with them, so the choice fits within the bound.
    start.pose_joints = given.pose_joints;
    start.max_representative_chars = given.max_representative_chars;
    start.max_representative_share = given.max_representative_share;
    start.reject = given.reject;  // the folds learn their bounds too, so the choice is made with them
    start.reject_keep = given.reject_keep;
    start.latency_budget_s = given.latency_budget_s;  // a constraint on the online search
    std::set<std::string> subjects;
    for (const host::LabelledClip& c : clips) subjects.insert(c.subject);
    if (subjects.size() < 2) {
        std::fprintf(stderr, "train: one subject in the list, so no cross-validation: the default settings\n");
        host::TuningResult fixed;
        fixed.options = start;
        return fixed;
    }
    // Beyond tuning_max_folds subjects the folds hold several each (subject_folds()).
    if (subjects.size() <= host::tuning_max_folds)
        std::fprintf(stderr,
                     "train: no settings given: choosing them by leave-one-subject-out cross-validation over "
                     "%zu subjects (--no-tune to skip)\n",
                     subjects.size());
    else
        std::fprintf(stderr,
                     "train: no settings given: choosing them by cross-validation over %zu subjects in %zu folds "
                     "(--no-tune to skip)\n",
                     subjects.size(), host::tuning_max_folds);
    // Self-tuning normalises size only through the skeleton's tree; say so when there is none.
    const host::Clip& first = clips.front().clip;
    if (first.parents.size() != first.joint_count())
        std::fprintf(stderr,
                     "train: note: %s has no bone tree (the file gives none and its joint names are not all one "
                     "Kinect SDK's), so size is left alone: people of other sizes will be measured in metres "
                     "(--parents gives a tree)\n",
                     first.source.c_str());
    const host::TuningResult tuned = host::tune_training(clips, start, [](const host::TuningStep& step) {
        std::fprintf(stderr, "train:   %-28s fold mean %.3f  margin %+.3f%s\n", step.setting.c_str(),
                     step.mean_accuracy, step.mean_margin, step.kept ? "  <- kept" : "");
    });
    std::printf(
        "tuning:           %zu settings tried in %.0f s; folds of the choice (chosen on them, so optimistic):\n",
        tuned.steps.size(), tuned.seconds);
    for (const host::FoldResult& f : tuned.folds)
        std::printf("  held out %-12s %4zu clips  accuracy %.3f\n", f.subject.c_str(), f.clips, f.clip_accuracy);
    std::printf("  mean %.3f\n", host::mean_accuracy(tuned.folds));
    return tuned;
}

// With no settings given, after the clip settings: the online settings (the
// segmenter's, the window's directions, early settling, the events' shortest
// action, the label lead) by leave-one-subject-out streaming (the held-out
// subject's clips joined, or its whole recordings), shown as tables, and set in `options`.
void tune_online_settings(const std::vector<host::LabelledClip>& clips, host::TrainingOptions& options,
                          const std::vector<host::LabelledRecording>* recordings) {
    std::fprintf(stderr, "train: choosing the online settings by streaming each held-out subject's %s\n",
                 recordings != nullptr ? "recordings" : "clips joined");
    const host::OnlineTuningResult tuned = host::tune_online(clips, options, recordings);
    host::adopt_online_tuning(tuned, options);
    if (tuned.steps.empty()) return;
    std::printf("online tuning:    %zu settings in %.0f s; mean over the held-out subjects' streams:\n",
                tuned.steps.size(), tuned.seconds);
    for (const host::OnlineTuningStep& step : tuned.steps)
        std::printf("  %-60s segment F1 %.3f  settled frames %.3f  latency %.2f s%s\n", step.settings.c_str(),
                    step.segment_f1, step.frame_accuracy, step.detection_latency_s, step.kept ? "  <- chosen" : "");
    if (options.latency_budget_s > 0)
        std::printf(tuned.latency_budget_met
                        ? "(only settings whose latency is within the budget of %g s were chosen from)\n"
                        : "NO setting met the latency budget of %g s on the folds: the fastest was kept\n",
                    options.latency_budget_s);
    std::printf(
        "the window's directions with them, over the last %g s (the best settled frames; within %g, the "
        "smaller weight):\n",
        tuned.direction_window_s_tried, host::direction_window_tie);
    for (const host::DirectionWindowStep& step : tuned.direction_window_steps)
        std::printf("  segment-directions %-6g settled frames %.3f  segment F1 %.3f%s\n",
                    static_cast<double>(step.direction_weight), step.frame_accuracy, step.segment_f1,
                    step.kept ? "  <- chosen" : "");
    std::printf(
        "early settling with them (0: the delay alone), then the events' shortest action: the fastest\n"
        "whose events' segment F1 is short of the best by at most a standard error, fold by fold:\n");
    for (const host::SettleStableStep& step : tuned.settle_stable_steps)
        std::printf(
            "  settle-stable %-6g events' segment F1 %.3f (%+.3f ± %.3f)  detection latency %.2f s  "
            "settled frames %.3f%s\n",
            host::us_to_seconds(step.settle_stable_us), step.event_segment_f1, step.difference, step.difference_error,
            step.detection_latency_s, step.frame_accuracy, step.kept ? "  <- chosen" : "");
    for (const host::MinActionStep& step : tuned.min_action_steps)
        std::printf("  min-action %-6g events' segment F1 %.3f (%+.3f ± %.3f)  detection latency %.2f s%s\n",
                    host::us_to_seconds(step.min_action_us), step.event_segment_f1, step.difference,
                    step.difference_error, step.detection_latency_s, step.kept ? "  <- chosen" : "");
    std::printf("the label lead with both (the best settled frames):\n");
    for (const host::LabelLeadStep& step : tuned.label_lead_steps)
        std::printf("  label-lead %-6g settled frames %.3f  segment F1 %.3f%s\n",
                    host::us_to_seconds(step.label_lead_us), step.frame_accuracy, step.segment_f1,
                    step.kept ? "  <- chosen" : "");
}

// Leave-one-subject-out over the list's subjects: a fold table, then the mean.
int run_cross_validation(const std::vector<host::LabelledClip>& clips, const host::TrainingOptions& options) {
    std::fprintf(stderr, "train: leave-one-subject-out cross-validation\n");
    const auto start = std::chrono::steady_clock::now();
    const std::vector<host::FoldResult> folds = host::cross_validate(clips, options);
    std::printf("%-12s %6s %6s %9s\n", "held out", "clips", "reps", "accuracy");
    for (const host::FoldResult& f : folds)
        std::printf("%-12s %6zu %6d %9.3f\n", f.subject.c_str(), f.clips, f.representatives, f.clip_accuracy);
    std::printf("%-12s %6s %6s %9.3f   (%.1f s)\n", "mean", "", "", host::mean_accuracy(folds),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
}

int run_sweep(const std::vector<host::LabelledClip>& train, const std::vector<host::LabelledClip>& validation,
              const host::TrainingOptions& base) {
    struct Variation {
        std::string setting;
        host::TrainingOptions options;
    };
    std::vector<Variation> grid{{"(given settings)", base}};
    auto vary = [&](const std::string& setting, auto change) {
        host::TrainingOptions o = base;
        change(o);
        grid.push_back({setting, o});
    };
    for (int j : {20, 60}) vary("components " + std::to_string(j), [j](auto& o) { o.components = j; });
    for (int p : {0, 12, 24})
        if (p != base.pca_dim) vary("pca " + std::to_string(p), [p](auto& o) { o.pca_dim = p; });
    vary("covariance diagonal", [](auto& o) { o.covariance = Covariance::diagonal; });
    for (double e : {0.5, 1.9}) vary("epsilon " + std::to_string(e).substr(0, 4), [e](auto& o) { o.epsilon = e; });
    for (double s : {0.5, 2.0}) vary("sigma x" + std::to_string(s).substr(0, 3), [s](auto& o) { o.sigma *= s; });
    vary("keep-singletons", [](auto& o) { o.keep_singletons = true; });
    for (double r : {8.0, 20.0})
        vary("string-rate " + std::to_string(static_cast<int>(r)), [r](auto& o) { o.string_rate_hz = r; });
    for (auto v : {MatchVariant::paper, MatchVariant::whole, MatchVariant::subsequence})
        if (v != base.variant) vary(std::string("variant ") + variant_name(v), [v](auto& o) { o.variant = v; });
    for (auto n : {LengthNormalization::none, LengthNormalization::path, LengthNormalization::query})
        if (n != base.normalization)
            vary(std::string("normalization ") + normalization_name(n), [n](auto& o) {
                o.normalization = n;
                if (n == LengthNormalization::path) o.sigma /= 20.0;  // σ in per-cell units
                if (n == LengthNormalization::query) o.sigma /= 20.0;
            });
    std::printf("%-26s %5s %5s %5s %9s %9s %8s\n", "setting", "J", "K", "reps", "train acc", "val acc", "train s");
    for (const Variation& v : grid) {
        host::TrainingReport report;
        const auto start = std::chrono::steady_clock::now();
        try {
            host::ModelData m = host::train_model(train, v.options, &report);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const ModelView view = m.view();
            std::printf("%-26s %5d %5d %5d %9.3f %9.3f %8.1f\n", v.setting.c_str(), v.options.components,
                        report.characters, report.representatives, host::clip_accuracy(view, train),
                        host::clip_accuracy(view, validation), seconds);
        } catch (const std::exception& e) {
            std::printf("%-26s failed: %s\n", v.setting.c_str(), e.what());
        }
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int run_train(int argc, char** argv) {
    host::TrainingOptions options;
    host::ReadOptions read;
    std::string clips_path, out_path, validate_path, json_path;
    bool sweep = false, cv = false, settings_given = false, no_tune = false, tune_online = false;
    ArgumentReader args("train", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            print_train_usage(stdout);
            return 0;
        }
        if (arg == "--clips") clips_path = args.value(arg);
        else if (arg == "--out") out_path = args.value(arg);
        else if (arg == "--validate") validate_path = args.value(arg);
        else if (arg == "--json") json_path = args.value(arg);
        else if (arg == "--sweep") sweep = true;
        else if (arg == "--cv") cv = true;
        else if (arg == "--mirror") {
            options.mirror = true;
            settings_given = true;
        } else if (arg == "--no-tune") no_tune = true;
        else if (arg == "--tune-online") tune_online = true;
        else if (arg == "--keep-singletons") {
            options.keep_singletons = true;
            settings_given = true;
        } else if (arg == "--reject") {
            options.reject = true;  // a deployment choice, not a tuned setting: self-tuning still runs
        } else if (arg == "--config") {
            if (!read_config(args, args.value(arg), options, read)) return 2;
            settings_given = true;
        } else if (arg.rfind("--", 0) == 0 && arg != "--") {
            const std::string name = arg.substr(2);
            const std::string value = args.value(arg);
            if (args.ok() && !apply(args, name, value, options, read)) return args.unknown(arg);
            // Reading, skeleton and cost choices are not tuned settings: self-tuning still runs.
            if (name != "rate" && name != "roles" && name != "time-unit" && name != "length-unit" && name != "body" &&
                name != "columns" && name != "parents" && name != "up" && name != "pose-joints" &&
                name != "max-representative-chars" && name != "max-representative-share" && name != "reject" &&
                name != "reject-keep" && name != "latency-budget")
                settings_given = true;
        } else {
            return args.unknown(arg);
        }
        if (!args.ok()) return 2;
    }
    if (!args.ok()) return 2;
    if (clips_path.empty() || (out_path.empty() && !sweep && !cv)) {
        print_train_usage(stderr);
        return 2;
    }
    if (sweep && validate_path.empty()) return args.error("--sweep needs --validate LIST");
    return run_reporting_errors("train", [&] {
        std::fprintf(stderr, "train: reading %s\n", clips_path.c_str());
        const auto train = host::load_labelled_clips(clips_path, read);
        std::vector<host::LabelledClip> validation;
        if (!validate_path.empty()) validation = host::load_labelled_clips(validate_path, read);
        if (sweep) return run_sweep(train, validation, options);
        if (cv) return run_cross_validation(train, options);
        // A list of intervals of recordings: what lies outside every interval is no action.
        std::vector<host::LabelledRecording> recordings;
        const std::vector<host::ClipListEntry> entries = host::read_clip_list(clips_path);
        if (host::has_intervals(entries)) recordings = host::read_recordings(entries, read);
        for (const host::LabelledRecording& recording : recordings)
            for (const std::string& note : recording.notes) std::fprintf(stderr, "train: note: %s\n", note.c_str());
        const std::vector<host::LabelledClip> no_action = host::unlabelled_stretches(recordings, 1.0);
        const bool tune_clips = !settings_given && !no_tune;
        if (tune_clips) {
            const bool reject = options.reject;
            const double reject_keep = options.reject_keep;
            options = tune(train, options).options;
            options.reject = reject, options.reject_keep = reject_keep;
        }
        if (tune_clips || tune_online) {
            // The online settings on the clip ones (chosen above, or as given); then, once,
            // what a config needs to train this model again.
            tune_online_settings(train, options, recordings.empty() ? nullptr : &recordings);
            std::printf("%s (keep them with --config):\n%s",
                        tune_clips ? "the chosen settings, clip and online"
                                   : "the settings, the clip ones as given and the online ones chosen",
                        host::options_as_config(options).c_str());
        }
        auto stage_start = std::chrono::steady_clock::now();
        options.progress = [&](const char* stage) {
            std::fprintf(stderr, "train: %s\n", stage);
            stage_start = std::chrono::steady_clock::now();
        };
        // EM: every tenth iteration, re-seeds and the last (restarts report from two threads).
        std::mutex em_lines;
        options.em_progress = [&em_lines](int restart, const host::EmProgress& step) {
            const bool last = step.converged || step.iteration == step.max_iterations;
            if (step.iteration % 10 != 0 && !step.reseeded && !last) return;
            const std::lock_guard<std::mutex> lock(em_lines);
            std::fprintf(stderr, "train: EM restart %d, iteration %d of at most %d: objective %.1f, change %.2g%s%s\n",
                         restart + 1, step.iteration, step.max_iterations, step.objective, step.change,
                         step.reseeded ? " (a component re-seeded)" : "",
                         !last ? "" : step.converged ? ", converged" : ", NOT converged");
        };
        host::TrainingReport report;
        host::ModelData model = host::train_model(train, options, &report, &no_action);
        host::save_model(model, out_path);
        const ModelView view = model.view();
        std::printf("model:            %s\n", out_path.c_str());
        if (!report.skeleton.empty()) std::printf("skeleton:         %s\n", report.skeleton.c_str());
        if (report.no_action_stretches > 0)
            std::printf("no action:        votes learned from %d unlabelled stretches of the recordings (>= 1 s)\n",
                        report.no_action_stretches);
        std::printf("frames:           %zu read, %zu rejected; %zu feature samples at %g Hz\n", report.frames_read,
                    report.frames_rejected, report.feature_samples, options.feature_rate_hz);
        if (view.has_gmm()) {
            std::printf(
                "features:         D %zu -> d %u, J %u (%s covariance), EM %zu iterations%s%s, log-likelihood %.1f\n",
                view.pose_dim(), view.feature_dim, view.component_count,
                view.covariance == Covariance::full ? "full" : "diagonal", report.em.objective.size(),
                report.em.converged ? ", converged" : ", NOT converged",
                report.em.reseeded.empty() ? "" : " (components re-seeded)",
                report.em.log_likelihood.empty() ? 0.0 : report.em.log_likelihood.back());
            std::printf("EM restarts:      %zu, kept seed %u (objectives:", report.em_restart_objectives.size(),
                        options.seed + static_cast<std::uint32_t>(report.em_restart_chosen));
            for (double objective : report.em_restart_objectives) std::printf(" %.1f", objective);
            std::printf(")\n");
        } else {
            std::printf("features:         D %zu -> d %u, no GMM: the tree is built on the projected poses\n",
                        view.pose_dim(), view.feature_dim);
        }
        std::printf("characters:       K %d (epsilon %g)\n", report.characters, options.epsilon);
        std::printf("representatives:  %d of %d strings, %zu characters (sigma %g, %s, %s normalisation)\n",
                    report.representatives, report.strings, report.representative_chars, options.sigma,
                    variant_name(options.variant), normalization_name(options.normalization));
        if (options.max_representative_chars > 0 || options.max_representative_share > 0)
            std::printf("                  bounded to %zu characters%s: %s\n",
                        options.max_representative_share > 0
                            ? report.representative_budget
                            : static_cast<std::size_t>(options.max_representative_chars),
                        options.max_representative_share > 0 ? " (the share of sigma's)" : "",
                        report.budget_merge_distance > 0
                            ? ("clusters merged up to distance " + std::to_string(report.budget_merge_distance)).c_str()
                            : "sigma already fits");
        for (std::size_t l = 0; l < model.label_names.size(); ++l)
            std::printf("  %-32s %d%s\n", model.label_names[l].c_str(), report.representatives_per_label[l],
                        report.representatives_per_label[l] == 0
                            ? "   <- no representative: this class cannot be recognised"
                            : "");
        if (view.has_exemplars())
            std::printf("exemplars:        %u centres in %zu of the feature's coordinates, weight %g\n",
                        view.exemplar_count, view.exemplar_dims(), static_cast<double>(view.exemplar_weight));
        if (view.has_descriptor())
            std::printf(
                "clip descriptor:  %u levels over %zu coordinates, %zu weights per label (ridge %g), "
                "weight %g\n",
                view.descriptor_levels, view.descriptor_dims(), view.descriptor_size(), options.descriptor_ridge,
                static_cast<double>(view.descriptor_weight));
        if (view.has_directions())
            std::printf(
                "motion directions: %u levels over %u pose joints, %zu weights per label (ridge %g), weight %g\n",
                view.direction_levels, view.pose_joint_count, view.direction_size(), options.direction_ridge,
                static_cast<double>(view.direction_weight));
        if (view.has_window_directions())
            std::printf(
                "window directions: the last %u characters, %zu weights per label (ridge %g); "
                "in the explanation with weight %g\n",
                view.window_direction_chars, view.window_direction_size(), options.direction_window_ridge,
                static_cast<double>(view.segment_direction_weight));
        if (!report.label_bounds.empty()) {
            std::printf("rejection:        each label's bound, from its held-out training clips (positives) and\n"
                        "                  what lands on it but is not it (negatives; keep >= %g of positives):\n",
                        options.reject_keep);
            for (std::size_t l = 0; l < report.label_bounds.size(); ++l) {
                const host::LabelBoundReport& b = report.label_bounds[l];
                std::printf("  %-32s bound %-9s positives %4zu kept %.2f  negatives %4zu rejected %.2f\n",
                            model.label_names[l].c_str(),
                            detail::is_finite(b.bound) ? std::to_string(b.bound).substr(0, 8).c_str() : "none",
                            b.positives, b.positives_kept, b.negatives, b.negatives_rejected);
            }
        }
        std::printf("tables:           %zu bytes\n", host::table_bytes(view));
        double total = 0;
        for (const auto& stage : report.stage_seconds) {
            std::printf("  %-30s %7.2f s\n", stage.first.c_str(), stage.second);
            total += stage.second;
        }
        std::printf("  %-30s %7.2f s\n", "total", total);
        if (!validation.empty())
            std::printf("validation:       clip accuracy %.3f on %zu clips (%s)\n",
                        host::clip_accuracy(view, validation), validation.size(), validate_path.c_str());
        if (!json_path.empty()) host::write_file(json_path, training_json(out_path, view, report, options));
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
