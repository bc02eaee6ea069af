// actionstring host library — the segmenter's online settings chosen by
// leave-one-subject-out cross-validation at training, so a model carries
// settings that were judged on streams of people it did not see.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "actionstring/segmenter.hpp"
#include "io/clip_list.hpp"
#include "io/recordings.hpp"
#include "train/options.hpp"

namespace actionstring {
namespace host {

/// One set of online settings tried, and what the held-out streams gave.
struct OnlineTuningStep {
    std::string settings;  ///< As config lines joined by ", ": "segment-votes 0.1, segment-penalty 1".
    SegmenterConfig config;
    double segment_f1 = 0;      ///< Mean over the folds of the settled labels' segment F1 (IoU ≥ 0.5).
    double frame_accuracy = 0;  ///< Mean over the folds of settled frame accuracy.
    /// Mean over the folds of the events' detection latency, at the options'
    /// shortest action (what a latency budget is held against).
    double detection_latency_s = 0;
    bool kept = false;
};

/// What the held-out streams' events gave under one setting: the figures a
/// latency-for-accuracy choice (one_standard_error_choice()) reads.
struct EventsScore {
    double event_segment_f1 = 0;     ///< Mean over the folds of the events' segment F1 (IoU ≥ 0.5).
    double standard_error = 0;       ///< Of that mean, over the folds (0 with one fold).
    std::vector<double> fold_event_segment_f1;  ///< Each fold's (the mean over its orders of joining).
    /// Set by the choice: the mean over the folds of this setting's F1 less the
    /// best setting's on the same fold, and that mean's standard error.
    double difference = 0, difference_error = 0;
    double detection_latency_s = 0;  ///< Mean over the folds (true start → `started` report).
    double frame_accuracy = 0;       ///< Mean over the folds of settled frame accuracy.
    bool kept = false;
};

/// One early settling tried (SegmenterConfig::settle_stable_us), with the
/// chosen segmenter settings, and what the held-out streams gave.
struct SettleStableStep : EventsScore {
    std::int64_t settle_stable_us = 0;
};

/// One shortest action of the events tried (AnnotatorConfig::min_action_us),
/// with the chosen segmenter settings and early settling, and what the
/// held-out streams gave.
struct MinActionStep : EventsScore {
    std::int64_t min_action_us = 0;
};

/// One label lead tried (AnnotatorConfig::label_lead_us), with the chosen
/// segmenter settings and shortest action, and what the held-out streams gave.
struct LabelLeadStep {
    std::int64_t label_lead_us = 0;
    double frame_accuracy = 0;  ///< Mean over the folds of settled frame accuracy.
    double segment_f1 = 0;      ///< Mean over the folds of the settled labels' segment F1 (IoU ≥ 0.5).
    bool kept = false;
};

/// One weight of the window's directions tried in the explanation
/// (SegmenterConfig::direction_weight), with the chosen grid settings.
struct DirectionWindowStep {
    float direction_weight = 0.0f;
    double frame_accuracy = 0;  ///< Mean over the folds of settled frame accuracy.
    double segment_f1 = 0;      ///< Mean over the folds of the settled labels' segment F1 (IoU ≥ 0.5).
    bool kept = false;
};

struct OnlineTuningResult {
    SegmenterConfig chosen;
    std::int64_t chosen_min_action_us = 250000;
    std::int64_t chosen_label_lead_us = 0;
    /// The window's length the model needs for chosen.direction_weight (the
    /// options' own, or online_tuning_window_s when they had none); 0 when
    /// the weight chosen is 0 and the options had no window.
    double chosen_direction_window_s = 0;
    double direction_window_s_tried = 0;  ///< The window the folds' models carried.
    std::vector<OnlineTuningStep> steps;
    std::vector<DirectionWindowStep> direction_window_steps;
    std::vector<SettleStableStep> settle_stable_steps;
    std::vector<MinActionStep> min_action_steps;
    std::vector<LabelLeadStep> label_lead_steps;
    /// With a latency budget (TrainingOptions::latency_budget_s): whether any
    /// setting met it. When none did, the fastest setting and the shortest
    /// action were kept.
    bool latency_budget_met = true;
    double seconds = 0;
};

/// Early settling tried, fastest first: a label final once every best
/// explanation has kept it this long, then the settle delay alone (0). On the
/// training subjects' folds of the configs in models/ (seeds 1-3, the delay 2
/// s), 1 s cut the mean detection latency from 2.56 to 1.79 s on HDM05 and
/// from 2.68 to 2.22 s on MSR Action3D, with the events' segment F1 within
/// 0.01 and the settled runs' segment F1 0.947 → 0.938 and 0.615 → 0.673;
/// models/README.md, "Early settling".
constexpr std::int64_t settle_stable_candidates_us[] = {500000, 750000, 1000000, 1250000, 1500000, 0};
/// The early settling a latency budget's grid tries beside shorter delays
/// (with the options' delay), before the step above refines it.
constexpr std::int64_t budget_stable_us = 1000000;

/// The events' shortest actions tried, shortest first. A longer one filters
/// more flicker but reports every action that much later.
constexpr std::int64_t min_action_candidates_us[] = {250000, 500000, 750000, 1000000, 1500000};

/// The one-standard-error rule over `steps` (fastest first, as
/// settle_stable_candidates_us and min_action_candidates_us): of those whose
/// events' segment F1 falls short of the best mean's by no more than one
/// standard error, the lowest mean detection latency on the folds (ties: the
/// earlier), so a device pays latency only for a gain the folds can tell from
/// noise. The shortfall is paired, fold by fold (the mean of the per-fold
/// differences and its standard error): folds differ in level far more than
/// settings do on them, and on HDM05's GMM folds (standard error 0.11 of a
/// mean) an unpaired bar let early settling lose 0.07 of every fold's events.
/// The candidates' order is a guess at their speed only: on UTKinect's folds
/// settling early reports no sooner than the delay alone. Returns its index
/// (0 when `steps` is empty).
std::size_t one_standard_error_choice(const std::vector<SettleStableStep>& steps);
std::size_t one_standard_error_choice(const std::vector<MinActionStep>& steps);

/// The label leads tried, shortest first. A character is made from the
/// feature at its tick, whose motion is a difference back over the model's
/// span, so the settled labels change a little after the actions do: on the
/// configs' training folds settled frames peaked with a lead of 0.1 s on
/// HDM05 and 0.15 to 0.2 s on MSR Action3D (velocity span 0.4 s), 0.25 to
/// 0.3 s on UTKinect (span 0.6 s), and at 0.05 s for the GMM feature, which
/// has no velocity; models/README.md, "The label lead".
constexpr std::int64_t label_lead_candidates_us[] = {0, 50000, 100000, 150000, 200000, 300000, 400000, 500000};

/// The window's directions (descriptor.hpp, window_direction_penalties()):
/// the window the folds' models get when the options have none, and the
/// weights tried in the explanation, smallest first. On the configs' training
/// folds (models/README.md, "The window's directions") settled frames peaked
/// at 1.5 s with 0.15 on MSR Action3D and 0.25 on HDM05, and at 1 s with 0.25
/// on UTKinect, where 1.5 s gave within 0.001 of it.
constexpr double online_tuning_window_s = 1.5;
constexpr float direction_window_candidates[] = {0.0f, 0.1f, 0.25f};
/// A heavier weight is kept only when its settled-frame mean gains more than
/// this over the weight kept before it (the configs' rule: on their folds,
/// differences under it were noise, as the label lead's were).
constexpr double direction_window_tie = 0.001;

/// The stay and skip penalties tried beside the options' own (both at once):
/// the explanation's time warping made cheaper.
constexpr float online_tuning_warp = 0.1f;

/// Orders in which a held-out subject's clips are joined (evaluate_online()'s
/// seeds 1, 2, …): which actions end up side by side moves a stream's segment
/// F1 by a few hundredths, as much as the settings compared do, so each
/// setting is judged on the mean over these orders.
constexpr int online_tuning_orders = 3;

/// For each subject of `clips`, trains a model with `options` on the other
/// subjects and streams the held-out subject: its clips concatenated
/// (evaluate_online(), in online_tuning_orders orders), or, when `recordings`
/// is given, its whole recordings (evaluate_recordings(); the training
/// subjects' unlabelled stretches then teach the model its "no action" votes
/// and centres, and "no action" needs no flat cost).
/// Tries the characters' votes in the explanation (segment-votes 0, 0.1, 0.25),
/// the segment penalty (1, 3), with exemplars in `options` their weight in the
/// explanation (segment-exemplars 0, 0.1, and 0.2 with recordings), the stay
/// and skip penalties (options.online's, and online_tuning_warp each) and, with
/// recordings, the flat unknown cost (0, 0.2; with exemplars 0, 0.05, 0.2), the
/// rest as in `options.online`; keeps the best mean segment F1 (ties: frame
/// accuracy, then the earlier, simpler settings). Then, with those settings on
/// the same folds and streams (whose models carry the window's directions over
/// options.direction_window_s, or online_tuning_window_s when that is 0), tries
/// each of direction_window_candidates (and options.online.direction_weight,
/// in its place, when it is not one of them) as the window's weight and keeps the
/// best mean settled frame accuracy (a heavier weight only when it gains more
/// than direction_window_tie over the one kept before it). Then tries each of
/// settle_stable_candidates_us and keeps one_standard_error_choice() (with the options' shortest action); then
/// each of min_action_candidates_us for the events and keeps
/// one_standard_error_choice(); then, with all, each of
/// label_lead_candidates_us, and keeps the best mean settled frame accuracy
/// (ties: the shorter lead). Deterministic.
/// With options.latency_budget_s, the grid also tries settle delays of 1 and
/// 1.5 s beside options.online's, and that delay with budget_stable_us of
/// early settling, and every choice considers only what meets the budget on
/// the folds (the fastest when nothing does). Early settling's candidates no
/// shorter than the chosen delay are not tried.
/// Needs two subjects or more (otherwise returns options.online,
/// options.min_action_us and options.label_lead_us, no steps).
OnlineTuningResult tune_online(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                               const std::vector<LabelledRecording>* recordings = nullptr,
                               const std::function<void(const OnlineTuningStep&)>& progress = {});

/// Sets what tune_online() chose in `options`: the segmenter's settings (early
/// settling and the window's weight among them), the window's length, the
/// events' shortest action and the label lead.
void adopt_online_tuning(const OnlineTuningResult& tuned, TrainingOptions& options);

}  // namespace host
}  // namespace actionstring
