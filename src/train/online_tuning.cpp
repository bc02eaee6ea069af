// The segmenter's online settings chosen by leave-one-subject-out cross-validation.
#include "train/online_tuning.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <utility>

#include "common/time.hpp"
#include "eval/online.hpp"
#include "model/model_data.hpp"
#include "train/cross_validation.hpp"
#include "train/pipeline.hpp"
#include "train/settings.hpp"

namespace actionstring {
namespace host {
namespace {

std::string number(double v) { return setting_value_text(v); }

// Stretches of no action shorter than this are not learned from (as `train` does).
constexpr double min_no_action_seconds = 1.0;

// A held-out subject: the model trained without it, and its streams.
struct Fold {
    ModelData model;
    std::vector<LabelledClip> test;
    std::vector<LabelledRecording> test_recordings;
};

}  // namespace

namespace {

// The mean and the standard error over the folds of the per-fold differences
// a − b (0 and 0 with fewer than two folds or different fold counts).
std::pair<double, double> paired_difference(const EventsScore& a, const EventsScore& b) {
    const std::vector<double>& x = a.fold_event_segment_f1;
    const std::vector<double>& y = b.fold_event_segment_f1;
    if (x.size() != y.size() || x.empty()) return {a.event_segment_f1 - b.event_segment_f1, 0.0};
    const double n = static_cast<double>(x.size());
    double mean = 0;
    for (std::size_t f = 0; f < x.size(); ++f) mean += (x[f] - y[f]) / n;
    double squares = 0;
    for (std::size_t f = 0; f < x.size(); ++f) squares += (x[f] - y[f] - mean) * (x[f] - y[f] - mean);
    return {mean, x.size() > 1 ? std::sqrt(squares / (n - 1.0) / n) : 0.0};
}

// The rule among the steps `allowed` marks (one_standard_error_choice()): the
// best mean, then, of those whose difference from it is within one standard
// error, the fastest on the folds (ties: the earlier). Each step's difference
// from the best is written to it. Returns steps.size() when none is allowed.
template <class Step>
std::size_t one_standard_error_rule(std::vector<Step>& steps, const std::vector<bool>& allowed) {
    std::size_t best = steps.size();
    for (std::size_t i = 0; i < steps.size(); ++i)
        if (allowed[i] && (best == steps.size() || steps[i].event_segment_f1 > steps[best].event_segment_f1)) best = i;
    if (best == steps.size()) return best;
    std::size_t chosen = best;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const std::pair<double, double> d = paired_difference(steps[i], steps[best]);
        steps[i].difference = d.first;
        steps[i].difference_error = d.second;
        const bool within = allowed[i] && d.first >= -d.second;
        const double latency = steps[i].detection_latency_s, fastest = steps[chosen].detection_latency_s;
        if (within && (latency < fastest || (latency == fastest && i < chosen))) chosen = i;
    }
    return chosen;
}

// The rule among the steps within a latency budget (all without one); none
// within: the first (the fastest). Marks the chosen step kept and returns it;
// `met` becomes false when nothing was within the budget.
template <class Step, class Within>
std::size_t choose_within_budget(std::vector<Step>& steps, const Within& within, bool& met) {
    std::vector<bool> allowed;
    for (const Step& step : steps) allowed.push_back(within(step.detection_latency_s));
    std::size_t kept = one_standard_error_rule(steps, allowed);
    if (kept == steps.size()) kept = 0, met = false;
    steps[kept].kept = true;
    return kept;
}

template <class Step>
std::size_t choice_of(std::vector<Step> steps) {
    if (steps.empty()) return 0;
    return one_standard_error_rule(steps, std::vector<bool>(steps.size(), true));
}

}  // namespace

std::size_t one_standard_error_choice(const std::vector<SettleStableStep>& steps) { return choice_of(steps); }
std::size_t one_standard_error_choice(const std::vector<MinActionStep>& steps) { return choice_of(steps); }

OnlineTuningResult tune_online(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                               const std::vector<LabelledRecording>* recordings,
                               const std::function<void(const OnlineTuningStep&)>& progress) {
    const auto began = std::chrono::steady_clock::now();
    OnlineTuningResult result;
    result.chosen = options.online;
    result.chosen_min_action_us = options.min_action_us;
    result.chosen_label_lead_us = options.label_lead_us;
    result.chosen_direction_window_s = options.direction_window_s;
    // The folds of self-tuning (at most tuning_max_folds, subjects dealt round-robin).
    const std::vector<std::vector<std::string>> folds = subject_folds(clips, tuning_max_folds);
    if (folds.size() < 2) return result;

    // The grid, in order of preference on ties (simpler first).
    const float infinity = std::numeric_limits<float>::infinity();
    std::vector<OnlineTuningStep> steps;
    // The exemplars in the explanation only when the model has them
    // (models/README.md); with recordings the model also has centres of no
    // action, which favour a heavier weight and a lower unknown cost.
    const bool exemplars = options.exemplars > 0 && options.exemplar_weight > 0;
    const std::vector<float> unknowns =
        recordings == nullptr ? std::vector<float>{infinity}
                              : (exemplars ? std::vector<float>{0.0f, 0.05f, 0.2f} : std::vector<float>{0.0f, 0.2f});
    const std::vector<float> exemplar_weights =
        !exemplars ? std::vector<float>{0.0f}
                   : (recordings != nullptr ? std::vector<float>{0.0f, 0.1f, 0.2f} : std::vector<float>{0.0f, 0.1f});
    // A latency budget also tries shorter settle delays and early settling
    // within the options' delay (1 s; the step after the grid tries others):
    // an event waits for its characters to settle, so settling is most of its
    // latency. Each entry: the delay, early settling.
    const double budget = options.latency_budget_s;
    const std::int64_t delay = options.online.settle_delay_us;
    std::vector<std::pair<std::int64_t, std::int64_t>> settles{{delay, options.online.settle_stable_us}};
    if (budget > 0) {
        for (const std::int64_t shorter : {1500000, 1000000})
            if (shorter < delay) settles.emplace_back(shorter, 0);
        if (budget_stable_us < delay && options.online.settle_stable_us != budget_stable_us)
            settles.emplace_back(delay, budget_stable_us);
    }
    // The explanation's time warping: the options' stay and skip penalties,
    // then both at 0.1, where MSR Action3D's online folds peaked (settled
    // frames 0.708 → 0.720, segment F1 0.555 → 0.614 from 0.3 each;
    // models/README.md, "The segmenter's time warping on MSR"). Cheaper warps
    // let a representative stretch over a slower or faster performer.
    std::vector<std::pair<float, float>> warps{{options.online.stay_penalty, options.online.skip_penalty}};
    if (options.online.stay_penalty != online_tuning_warp || options.online.skip_penalty != online_tuning_warp)
        warps.emplace_back(online_tuning_warp, online_tuning_warp);
    for (const std::pair<std::int64_t, std::int64_t>& settle : settles)
        for (const std::pair<float, float>& warp : warps)
            for (const float unknown : unknowns)
                for (const float votes : {0.0f, 0.1f, 0.25f})
                    for (const float penalty : {1.0f, 3.0f})
                        for (const float exemplar : exemplar_weights) {
                            OnlineTuningStep step;
                            step.config = options.online;
                            step.config.settle_delay_us = settle.first;
                            step.config.settle_stable_us = settle.second;
                            step.config.stay_penalty = warp.first;
                            step.config.skip_penalty = warp.second;
                            step.config.vote_weight = votes;
                            step.config.segment_penalty = penalty;
                            step.config.unknown_cost = unknown;
                            step.config.exemplar_weight = exemplar;
                            step.settings = "segment-votes " + number(votes) + ", segment-penalty " + number(penalty) +
                                            ", unknown-cost " + number(static_cast<double>(unknown));
                            if (exemplars)
                                step.settings += ", segment-exemplars " + number(static_cast<double>(exemplar));
                            if (warps.size() > 1)
                                step.settings += ", stay-penalty " + number(static_cast<double>(warp.first)) +
                                                 ", skip-penalty " + number(static_cast<double>(warp.second));
                            if (settles.size() > 1) {
                                step.settings += ", settle " + number(us_to_seconds(settle.first));
                                if (settle.second > 0)
                                    step.settings += ", settle-stable " + number(us_to_seconds(settle.second));
                            }
                            steps.push_back(step);
                        }

    // One model per fold, every setting streamed through it: recordings as they
    // are, joined clips in several orders; every fold and order weighs the same.
    // The models carry the window's directions, which only the window's step
    // weighs (the grid's settings keep the options' weight).
    TrainingOptions fold_options = options;
    if (fold_options.direction_window_s <= 0) fold_options.direction_window_s = online_tuning_window_s;
    result.direction_window_s_tried = fold_options.direction_window_s;
    const int orders = recordings != nullptr ? 1 : online_tuning_orders;
    const double share = 1.0 / static_cast<double>(folds.size() * static_cast<std::size_t>(orders));
    std::vector<Fold> trained;
    for (const std::vector<std::string>& held : folds) {
        auto held_out = [&held](const std::string& subject) {
            return std::find(held.begin(), held.end(), subject) != held.end();
        };
        Fold fold;
        std::vector<LabelledClip> train;
        for (const LabelledClip& c : clips) (held_out(c.subject) ? fold.test : train).push_back(c);
        std::vector<LabelledRecording> train_recordings;
        if (recordings != nullptr)
            for (const LabelledRecording& r : *recordings)
                (held_out(r.subject) ? fold.test_recordings : train_recordings).push_back(r);
        const std::vector<LabelledClip> no_action = unlabelled_stretches(train_recordings, min_no_action_seconds);
        fold.model = train_model(train, fold_options, nullptr, &no_action);
        trained.push_back(std::move(fold));
    }
    // One held-out stream set's report under `config`, in order `order`:
    // the segmenter's figures only (the paper's window rule is not run).
    auto stream = [&](const Fold& fold, const AnnotatorConfig& config, int order) {
        return recordings != nullptr
                   ? evaluate_recordings(fold.model.view(), fold.test_recordings, config, false)
                   : evaluate_online(fold.model.view(), fold.test, static_cast<std::uint32_t>(order), config, false);
    };
    for (const Fold& fold : trained)
        for (OnlineTuningStep& step : steps) {
            AnnotatorConfig config = annotator_config(fold.model.view());
            config.segmenter = step.config;
            for (int order = 1; order <= orders; ++order) {
                const OnlineReport report = stream(fold, config, order);
                step.segment_f1 += report.settled.segment_f1 * share;
                step.frame_accuracy += report.settled.frame_accuracy * share;
                step.detection_latency_s += report.settled.detection_latency_s * share;
            }
        }
    // Within the budget (all, without one); when nothing meets it, the fastest.
    auto within = [budget](double latency_s) { return budget <= 0 || latency_s <= budget; };
    result.latency_budget_met = std::any_of(
        steps.begin(), steps.end(), [&](const OnlineTuningStep& step) { return within(step.detection_latency_s); });
    std::size_t best = steps.size();
    for (std::size_t i = 0; i < steps.size(); ++i) {
        if (!result.latency_budget_met) {
            if (best == steps.size() || steps[i].detection_latency_s < steps[best].detection_latency_s) best = i;
            continue;
        }
        if (!within(steps[i].detection_latency_s)) continue;
        if (best == steps.size() || steps[i].segment_f1 > steps[best].segment_f1 ||
            (steps[i].segment_f1 == steps[best].segment_f1 && steps[i].frame_accuracy > steps[best].frame_accuracy))
            best = i;
    }
    steps[best].kept = true;
    result.chosen = steps[best].config;
    for (const OnlineTuningStep& step : steps)
        if (progress) progress(step);
    result.steps = std::move(steps);

    // A step judged by the settled labels: their frame accuracy and their runs'
    // segment F1 over every fold and order, with the settings chosen so far and
    // `adjust` applied to each fold's configuration.
    auto settled_on_folds = [&](const auto& adjust, auto& step) {
        for (const Fold& fold : trained) {
            AnnotatorConfig config = annotator_config(fold.model.view());
            config.segmenter = result.chosen;
            adjust(config);
            for (int order = 1; order <= orders; ++order) {
                const OnlineReport report = stream(fold, config, order);
                step.frame_accuracy += report.settled.frame_accuracy * share;
                step.segment_f1 += report.settled.segment_f1 * share;
            }
        }
    };
    // Of steps so judged, the first with the best settled frames, a later one
    // only when it gains more than `tie`; marked kept.
    auto keep_best_settled = [](auto& tried, double tie) {
        std::size_t kept = 0;
        for (std::size_t i = 1; i < tried.size(); ++i)
            if (tried[i].frame_accuracy > tried[kept].frame_accuracy + tie) kept = i;
        tried[kept].kept = true;
        return kept;
    };

    // The window's directions in the explanation, with the settings chosen:
    // judged by the settled frames, as the configs' windows were. The options'
    // own weight is tried too, in its place.
    std::vector<float> window_weights(std::begin(direction_window_candidates), std::end(direction_window_candidates));
    if (std::find(window_weights.begin(), window_weights.end(), options.online.direction_weight) ==
        window_weights.end())
        window_weights.insert(
            std::upper_bound(window_weights.begin(), window_weights.end(), options.online.direction_weight),
            options.online.direction_weight);
    for (const float weight : window_weights) {
        DirectionWindowStep step;
        step.direction_weight = weight;
        settled_on_folds([weight](AnnotatorConfig& config) { config.segmenter.direction_weight = weight; }, step);
        result.direction_window_steps.push_back(step);
    }
    const std::size_t window = keep_best_settled(result.direction_window_steps, direction_window_tie);
    result.chosen.direction_weight = result.direction_window_steps[window].direction_weight;
    result.chosen_direction_window_s =
        result.chosen.direction_weight > 0 ? fold_options.direction_window_s : options.direction_window_s;

    // The events of every fold's streams under `segmenter` and a shortest
    // action: their segment F1 (per fold, and its mean and standard error over
    // the folds), detection latency and settled frames.
    auto events_on_folds = [&](const SegmenterConfig& segmenter, std::int64_t min_action_us, EventsScore& score) {
        std::vector<double> per_fold;
        for (const Fold& fold : trained) {
            AnnotatorConfig config = annotator_config(fold.model.view());
            config.segmenter = segmenter;
            config.min_action_us = min_action_us;
            double f1 = 0;
            for (int order = 1; order <= orders; ++order) {
                const OnlineReport report = stream(fold, config, order);
                f1 += report.settled.event_segment_f1 / orders;
                score.detection_latency_s += report.settled.detection_latency_s * share;
                score.frame_accuracy += report.settled.frame_accuracy * share;
            }
            per_fold.push_back(f1);
        }
        const double n = static_cast<double>(per_fold.size());
        for (const double f1 : per_fold) score.event_segment_f1 += f1 / n;
        double squares = 0;
        for (const double f1 : per_fold) squares += (f1 - score.event_segment_f1) * (f1 - score.event_segment_f1);
        score.standard_error = per_fold.size() > 1 ? std::sqrt(squares / (n - 1.0) / n) : 0.0;
        score.fold_event_segment_f1 = per_fold;
    };

    // Early settling, with the settings chosen and the options' shortest
    // action: it changes what is settled, and when, not the explanation. A
    // candidate no shorter than the chosen delay would be the delay alone.
    for (const std::int64_t stable_us : settle_stable_candidates_us) {
        if (stable_us != 0 && stable_us >= result.chosen.settle_delay_us) continue;
        SettleStableStep step;
        step.settle_stable_us = stable_us;
        SegmenterConfig segmenter = result.chosen;
        segmenter.settle_stable_us = stable_us;
        events_on_folds(segmenter, options.min_action_us, step);
        result.settle_stable_steps.push_back(step);
    }
    const std::size_t stable = choose_within_budget(result.settle_stable_steps, within, result.latency_budget_met);
    result.chosen.settle_stable_us = result.settle_stable_steps[stable].settle_stable_us;

    // The events' shortest action, with the settings chosen: the settled
    // labels do not depend on it, only which of their runs are reported.
    for (const std::int64_t min_action_us : min_action_candidates_us) {
        MinActionStep step;
        step.min_action_us = min_action_us;
        events_on_folds(result.chosen, min_action_us, step);
        result.min_action_steps.push_back(step);
    }
    const std::size_t kept = choose_within_budget(result.min_action_steps, within, result.latency_budget_met);
    result.chosen_min_action_us = result.min_action_steps[kept].min_action_us;

    // The label lead, with both: it moves where each settled label lies in
    // time, not what is settled, so it is judged by the settled frames.
    for (const std::int64_t lead_us : label_lead_candidates_us) {
        LabelLeadStep step;
        step.label_lead_us = lead_us;
        const std::int64_t min_action_us = result.chosen_min_action_us;
        settled_on_folds(
            [&](AnnotatorConfig& config) {
                config.min_action_us = min_action_us;
                config.label_lead_us = lead_us;
            },
            step);
        result.label_lead_steps.push_back(step);
    }
    const std::size_t lead = keep_best_settled(result.label_lead_steps, 1e-9);
    result.chosen_label_lead_us = result.label_lead_steps[lead].label_lead_us;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    return result;
}

void adopt_online_tuning(const OnlineTuningResult& tuned, TrainingOptions& options) {
    options.online = tuned.chosen;
    options.direction_window_s = tuned.chosen_direction_window_s;
    options.min_action_us = tuned.chosen_min_action_us;
    options.label_lead_us = tuned.chosen_label_lead_us;
}

}  // namespace host
}  // namespace actionstring
