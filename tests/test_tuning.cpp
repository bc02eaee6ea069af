// Training that tunes itself: deterministic, only strict improvements kept,
// every step a cross-validation over the list's subjects.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "eval/online.hpp"
#include "run/classify.hpp"
#include "toy/toy.hpp"
#include "train/cross_validation.hpp"
#include "train/online_tuning.hpp"
#include "train/pipeline.hpp"
#include "train/settings.hpp"
#include "train/tuning.hpp"

using namespace actionstring::host;

namespace {

// Toy performances noisy enough (15 cm) that settings make a difference.
std::vector<LabelledClip> noisy_clips(const ToyWorld& world, int performances) {
    std::vector<LabelledClip> clips;
    for (int p = 0; p < performances; ++p)
        for (std::size_t a = 0; a < world.actions.size(); ++a) {
            ToyStreamOptions options;
            options.seed = 500 + static_cast<std::uint32_t>(p * 31 + static_cast<int>(a));
            options.frame_rate_hz = 15.0;
            options.position_noise_m = 0.15;
            clips.push_back({toy_clip(toy_stream(world, {static_cast<int>(a)}, options), world.actions[a].name),
                             world.actions[a].name, "toy" + std::to_string(p)});
        }
    return clips;
}

}  // namespace

TEST_CASE("self-tuning is deterministic and keeps a setting only when its folds improve") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 2);  // subjects toy0, toy1: two folds
    const TuningResult a = tune_training(clips, tuning_start());
    const TuningResult b = tune_training(clips, tuning_start());
    CHECK(options_as_config(a.options) == options_as_config(b.options));
    REQUIRE(a.steps.size() == b.steps.size());
    REQUIRE(a.steps.size() > 10);
    double best = -1.0, best_margin = -2.0;
    int kept = 0, kept_on_margin = 0;
    for (std::size_t i = 0; i < a.steps.size(); ++i) {
        CAPTURE(a.steps[i].setting);
        CHECK(a.steps[i].mean_accuracy == b.steps[i].mean_accuracy);
        CHECK(a.steps[i].mean_margin == b.steps[i].mean_margin);
        CHECK(a.steps[i].kept == b.steps[i].kept);
        // A signed margin: within [−1, 1], and positive when every clip is right.
        CHECK(a.steps[i].mean_margin >= -1.0);
        CHECK(a.steps[i].mean_margin <= 1.0);
        if (a.steps[i].mean_accuracy == 1.0) CHECK(a.steps[i].mean_margin > 0.0);
        const bool ties = std::fabs(a.steps[i].mean_accuracy - best) <= 1e-9;
        if (a.steps[i].kept) {
            ++kept;
            // Better folds, or folds as good by a wider margin; the exemplars'
            // dimension only saves work, and a tie keeps it too.
            if (a.steps[i].setting.rfind("exemplar-dims", 0) == 0) CHECK((a.steps[i].mean_accuracy > best || ties));
            else CHECK((a.steps[i].mean_accuracy > best + 1e-9 || (ties && a.steps[i].mean_margin > best_margin)));
            if (ties && a.steps[i].setting.rfind("exemplar-dims", 0) != 0) ++kept_on_margin;
            best = a.steps[i].mean_accuracy;
            best_margin = a.steps[i].mean_margin;
        } else {
            CHECK((a.steps[i].mean_accuracy < best - 1e-9 || (ties && a.steps[i].mean_margin <= best_margin)));
        }
    }
    CHECK(kept >= 2);  // the search moved off its starting point
    // The toy's folds reach their ceiling, where only the margin can choose: it did.
    CHECK(kept_on_margin >= 1);
    REQUIRE(a.folds.size() == 2);
    CHECK(a.folds[0].subject == "toy0");
    const std::string config = options_as_config(a.options);
    for (const char* line : {"components 0\n", "keep-singletons true\n", "variant whole\n"})
        CHECK(config.find(line) != std::string::npos);
    // Exemplars of half the feature's coordinates are tried only where there are exemplars.
    bool exemplars_kept = false, dims_tried = false;
    for (const TuningStep& step : a.steps) {
        if (step.setting.rfind("exemplars 64", 0) == 0) exemplars_kept |= step.kept;
        dims_tried |= step.setting.rfind("exemplar-dims", 0) == 0;
    }
    CHECK(dims_tried == exemplars_kept);
    // The acceleration's weight is searched and echoed with the rest.
    bool tried_acceleration = false;
    for (const TuningStep& step : a.steps) tried_acceleration |= step.setting == "acceleration 0.5";
    CHECK(tried_acceleration);
    CHECK(config.find("\nacceleration ") != std::string::npos);
    // The clip descriptor is searched (three weights over three levels) and echoed when kept.
    int descriptor_steps = 0;
    for (const TuningStep& step : a.steps)
        descriptor_steps +=
            step.setting.rfind("descriptor-levels 3, descriptor-ridge 3000, descriptor-weight ", 0) == 0;
    CHECK(descriptor_steps == 3);
    CHECK((config.find("descriptor-levels 3\n") != std::string::npos) == (a.options.descriptor_levels == 3));
    // So are the motion directions (three weights over three levels).
    int direction_steps = 0;
    for (const TuningStep& step : a.steps)
        direction_steps += step.setting.rfind("direction-levels 3, direction-ridge 3000, direction-weight ", 0) == 0;
    CHECK(direction_steps == 3);
    CHECK((config.find("direction-levels 3\n") != std::string::npos) == (a.options.direction_levels == 3));
    // The toy skeleton has parents: size is normalised by the torso, never searched.
    CHECK(a.options.scale_mode == actionstring::ScaleMode::torso);
    CHECK(config.find("scale torso\n") != std::string::npos);
    for (const TuningStep& step : a.steps) CHECK(step.setting.rfind("scale", 0) == std::string::npos);
    // Without parents there is no torso to measure: size stays as it is.
    std::vector<LabelledClip> flat = clips;
    for (LabelledClip& c : flat) c.clip.parents.clear();
    CHECK(tune_training(flat, tuning_start()).options.scale_mode == actionstring::ScaleMode::none);
}

TEST_CASE("self-tuning tries exemplars of half the feature's coordinates, and keeps them on a tie") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 2);
    TrainingOptions start = tuning_start();
    start.exemplars = 64;
    start.exemplar_weight = 1.0;
    const TuningResult a = tune_training(clips, start);
    REQUIRE(a.options.exemplars > 0);
    const TuningStep* dims = nullptr;
    double best_before = -1.0;
    for (const TuningStep& step : a.steps) {
        if (step.setting.rfind("exemplar-dims", 0) == 0) {
            dims = &step;
            break;
        }
        if (step.kept) best_before = step.mean_accuracy;
    }
    REQUIRE(dims != nullptr);
    // Half the feature's coordinates, rounded to a multiple of four (the toy's PCA is its input's 15: 8).
    const long half = std::lround(a.options.pca_dim / 8.0) * 4;
    CHECK(dims->setting == "exemplar-dims " + std::to_string(half));
    // The toy's folds are at their ceiling, so the cheaper setting ties and is kept.
    CHECK(dims->mean_accuracy == best_before);
    CHECK(dims->kept);
    CHECK(a.options.exemplar_dims == half);
    CHECK(options_as_config(a.options).find("exemplar-dims " + std::to_string(a.options.exemplar_dims) + "\n") !=
          std::string::npos);
    // A model trained with the choice keeps that many coordinates per centre.
    const ModelData model = train_model(clips, a.options);
    CHECK(model.exemplar_dim == a.options.exemplar_dims);
}

TEST_CASE("a fold's margin: its held-out clips' confidence, signed by whether each is right") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 2);
    TrainingOptions options = tuning_start();
    options.pca_dim = 8;  // the toy's pose has 15 coordinates
    const std::vector<FoldResult> folds = cross_validate(clips, options);
    REQUIRE(folds.size() == 2);
    std::vector<LabelledClip> train, held;
    for (const LabelledClip& c : clips) (c.subject == "toy0" ? held : train).push_back(c);
    const ModelData model = train_model(train, options);
    const actionstring::ModelView view = model.view();
    double signed_sum = 0;
    std::size_t right = 0;
    for (const LabelledClip& c : held) {
        const actionstring::Classification k = classify_clip(view, c.clip);
        const bool correct = k.label != actionstring::unknown_label && view.label_names[k.label] == c.label;
        right += correct;
        signed_sum += correct ? k.confidence : -static_cast<double>(k.confidence);
    }
    const ClipScore score = clip_score(view, held);
    CHECK(score.accuracy == doctest::Approx(static_cast<double>(right) / static_cast<double>(held.size())));
    CHECK(score.accuracy == clip_accuracy(view, held));
    CHECK(score.margin == doctest::Approx(signed_sum / static_cast<double>(held.size())));
    CHECK(folds[0].subject == "toy0");
    CHECK(folds[0].margin == doctest::Approx(score.margin));
    CHECK(mean_margin(folds) == doctest::Approx((folds[0].margin + folds[1].margin) / 2));
    // Every clip given a label the model does not predict: nothing right, and
    // the margin is minus the mean confidence of the (wrong) winners.
    std::vector<LabelledClip> wrong = held;
    double confidence_sum = 0;
    for (LabelledClip& c : wrong) {
        const actionstring::Classification k = classify_clip(view, c.clip);
        c.label = "not an action of the model";
        confidence_sum += k.confidence;
    }
    const ClipScore none_right = clip_score(view, wrong);
    CHECK(none_right.accuracy == 0.0);
    CHECK(none_right.margin == doctest::Approx(-confidence_sum / static_cast<double>(wrong.size())));
    CHECK(none_right.margin < 0.0);
}

TEST_CASE("cross-validation needs two subjects") {
    ToyWorld world = make_toy_world();
    std::vector<LabelledClip> clips = toy_clips(world, 1, 3, 15.0);
    CHECK_THROWS_AS(cross_validate(clips, tuning_start()), std::invalid_argument);
}

TEST_CASE("folds: one per subject, or at most max_folds with the subjects dealt round-robin") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 7);  // subjects toy0 … toy6
    CHECK(subject_folds(clips).size() == 7);
    CHECK(subject_folds(clips, 10).size() == 7);
    const auto three = subject_folds(clips, 3);
    REQUIRE(three.size() == 3);
    CHECK(three[0] == std::vector<std::string>{"toy0", "toy3", "toy6"});
    CHECK(three[1] == std::vector<std::string>{"toy1", "toy4"});
    CHECK(three[2] == std::vector<std::string>{"toy2", "toy5"});
    TrainingOptions options = tuning_start();
    options.pca_dim = 8;
    const auto folds = cross_validate(clips, options, 3);
    REQUIRE(folds.size() == 3);
    CHECK(folds[0].subject == "toy0+toy3+toy6");
    CHECK(folds[0].clips == 3 * world.actions.size());
    CHECK(folds[1].clips + folds[2].clips == 4 * world.actions.size());
}

TEST_CASE("online settings: chosen by streaming held-out subjects, deterministic, the best segment F1") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 3);  // three subjects: three folds
    TrainingOptions options = tuning_start();
    options.pca_dim = 6;
    const OnlineTuningResult a = tune_online(clips, options);
    const OnlineTuningResult b = tune_online(clips, options);
    // Stay and skip penalties 0.3 (the options') / 0.1 × segment votes 0 / 0.1 / 0.25
    // × segment penalty 1 / 3; no recordings.
    REQUIRE(a.steps.size() == 12);
    REQUIRE(b.steps.size() == a.steps.size());
    for (std::size_t i = 0; i < a.steps.size(); ++i) {
        const float warp = i < 6 ? options.online.stay_penalty : online_tuning_warp;
        CHECK(a.steps[i].config.stay_penalty == warp);
        CHECK(a.steps[i].config.skip_penalty == (i < 6 ? options.online.skip_penalty : online_tuning_warp));
        CHECK((a.steps[i].settings.find("stay-penalty ") != std::string::npos));
    }
    // Options with a window of their own and a weight not among the candidates:
    // their window, and their weight tried in its place; the window stays.
    TrainingOptions own_window = options;
    own_window.direction_window_s = 1.0;
    own_window.online.direction_weight = 0.15f;
    const OnlineTuningResult own = tune_online(clips, own_window);
    CHECK(own.direction_window_s_tried == 1.0);
    REQUIRE(own.direction_window_steps.size() == std::size(direction_window_candidates) + 1);
    CHECK(own.direction_window_steps[1].direction_weight == 0.1f);
    CHECK(own.direction_window_steps[2].direction_weight == 0.15f);
    CHECK(own.chosen_direction_window_s == 1.0);
    // Options already at the second warp try it once.
    TrainingOptions warped = options;
    warped.online.stay_penalty = warped.online.skip_penalty = online_tuning_warp;
    CHECK(tune_online(clips, warped).steps.size() == 6);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < a.steps.size(); ++i) {
        CHECK(a.steps[i].segment_f1 == b.steps[i].segment_f1);
        CHECK(a.steps[i].frame_accuracy >= 0.0);
        CHECK(a.steps[i].frame_accuracy <= 1.0);
        if (!a.steps[i].kept) continue;
        ++kept;
        CHECK(a.chosen.vote_weight == a.steps[i].config.vote_weight);
        CHECK(a.chosen.segment_penalty == a.steps[i].config.segment_penalty);
        CHECK(a.chosen.stay_penalty == a.steps[i].config.stay_penalty);
        CHECK(a.chosen.skip_penalty == a.steps[i].config.skip_penalty);
        for (const OnlineTuningStep& other : a.steps) CHECK(other.segment_f1 <= a.steps[i].segment_f1);
    }
    CHECK(kept == 1);
    // Each setting's figure is the mean over the folds and over the orders the
    // held-out clips are joined in: the first setting, recomputed by hand.
    // The events' shortest action is tried with the chosen settings: the
    // longest candidate's figures, recomputed by hand the same way.
    const auto folds = subject_folds(clips, tuning_max_folds);
    REQUIRE(folds.size() == 3);
    REQUIRE(a.min_action_steps.size() == std::size(min_action_candidates_us));
    const MinActionStep& longest = a.min_action_steps.back();
    CHECK(longest.min_action_us == 1500000);
    // Early settling is tried with the chosen settings and the options' shortest
    // action: the fastest candidate's figures too.
    REQUIRE(a.settle_stable_steps.size() == std::size(settle_stable_candidates_us));
    const SettleStableStep& eager = a.settle_stable_steps.front();
    CHECK(eager.settle_stable_us == 500000);
    CHECK(a.settle_stable_steps.back().settle_stable_us == 0);  // the delay alone, last (the slowest)
    // The label lead is tried with both chosen: the longest lead's figures too.
    REQUIRE(a.label_lead_steps.size() == std::size(label_lead_candidates_us));
    const LabelLeadStep& longest_lead = a.label_lead_steps.back();
    CHECK(longest_lead.label_lead_us == 500000);
    // The window's weights are tried with the grid's choice, on models that
    // carry a window of online_tuning_window_s (the options have none): the
    // heaviest weight's figures too.
    REQUIRE(a.direction_window_steps.size() == std::size(direction_window_candidates));
    CHECK(a.direction_window_s_tried == online_tuning_window_s);
    const DirectionWindowStep& heaviest = a.direction_window_steps.back();
    CHECK(heaviest.direction_weight == 0.25f);
    TrainingOptions windowed = options;
    windowed.direction_window_s = online_tuning_window_s;
    double f1 = 0, frames = 0, latency = 0, led_frames = 0, led_f1 = 0, eager_latency = 0, eager_frames = 0;
    double window_frames = 0, window_f1 = 0;
    std::vector<double> event_f1, eager_f1;  // per fold
    for (const auto& held : folds) {
        REQUIRE(held.size() == 1);  // one subject per fold
        std::vector<LabelledClip> train, test;
        for (const LabelledClip& c : clips) (c.subject == held.front() ? test : train).push_back(c);
        const ModelData model = train_model(train, windowed);
        REQUIRE(model.view().has_window_directions());
        actionstring::AnnotatorConfig config = actionstring::annotator_config(model.view());
        config.segmenter = a.steps[0].config;
        actionstring::AnnotatorConfig window = actionstring::annotator_config(model.view());
        window.segmenter = a.steps[0].config;
        for (const OnlineTuningStep& step : a.steps)
            if (step.kept) window.segmenter = step.config;
        window.segmenter.direction_weight = heaviest.direction_weight;
        actionstring::AnnotatorConfig events = actionstring::annotator_config(model.view());
        events.segmenter = a.chosen;
        events.min_action_us = longest.min_action_us;
        actionstring::AnnotatorConfig led = actionstring::annotator_config(model.view());
        led.segmenter = a.chosen;
        led.min_action_us = a.chosen_min_action_us;
        led.label_lead_us = longest_lead.label_lead_us;
        actionstring::AnnotatorConfig early = actionstring::annotator_config(model.view());
        early.segmenter = a.chosen;
        early.segmenter.settle_stable_us = eager.settle_stable_us;
        early.min_action_us = options.min_action_us;
        event_f1.push_back(0.0);
        eager_f1.push_back(0.0);
        for (int order = 1; order <= online_tuning_orders; ++order) {
            const OnlineReport report = evaluate_online(model.view(), test, static_cast<std::uint32_t>(order), config);
            f1 += report.settled.segment_f1;
            frames += report.settled.frame_accuracy;
            const OnlineReport reported =
                evaluate_online(model.view(), test, static_cast<std::uint32_t>(order), events);
            event_f1.back() += reported.settled.event_segment_f1 / online_tuning_orders;
            latency += reported.settled.detection_latency_s;
            const OnlineReport windowing =
                evaluate_online(model.view(), test, static_cast<std::uint32_t>(order), window);
            window_frames += windowing.settled.frame_accuracy;
            window_f1 += windowing.settled.segment_f1;
            const OnlineReport leading = evaluate_online(model.view(), test, static_cast<std::uint32_t>(order), led);
            led_frames += leading.settled.frame_accuracy;
            led_f1 += leading.settled.segment_f1;
            const OnlineReport settling = evaluate_online(model.view(), test, static_cast<std::uint32_t>(order), early);
            eager_f1.back() += settling.settled.event_segment_f1 / online_tuning_orders;
            eager_latency += settling.settled.detection_latency_s;
            eager_frames += settling.settled.frame_accuracy;
        }
    }
    const double n = static_cast<double>(folds.size()) * online_tuning_orders;
    CHECK(a.steps[0].segment_f1 == doctest::Approx(f1 / n).epsilon(1e-12));
    CHECK(a.steps[0].frame_accuracy == doctest::Approx(frames / n).epsilon(1e-12));
    // The mean over the three folds and its standard error.
    auto check_folds = [](const EventsScore& score, const std::vector<double>& per_fold) {
        const double mean = (per_fold[0] + per_fold[1] + per_fold[2]) / 3.0;
        double squares = 0;
        for (const double v : per_fold) squares += (v - mean) * (v - mean);
        CHECK(score.event_segment_f1 == doctest::Approx(mean).epsilon(1e-12));
        CHECK(score.standard_error == doctest::Approx(std::sqrt(squares / 2.0 / 3.0)).epsilon(1e-12));
        CHECK(score.fold_event_segment_f1.size() == per_fold.size());
    };
    check_folds(longest, event_f1);
    CHECK(longest.detection_latency_s == doctest::Approx(latency / n).epsilon(1e-12));
    check_folds(eager, eager_f1);
    CHECK(eager.detection_latency_s == doctest::Approx(eager_latency / n).epsilon(1e-12));
    CHECK(eager.frame_accuracy == doctest::Approx(eager_frames / n).epsilon(1e-12));
    // One early settling kept, by the one-standard-error rule, and it is the model's.
    std::size_t kept_stable = 0;
    for (std::size_t i = 0; i < a.settle_stable_steps.size(); ++i) {
        CHECK(a.settle_stable_steps[i].event_segment_f1 == b.settle_stable_steps[i].event_segment_f1);
        kept_stable += a.settle_stable_steps[i].kept;
    }
    CHECK(kept_stable == 1);
    const std::size_t stable = one_standard_error_choice(a.settle_stable_steps);
    CHECK(a.settle_stable_steps[stable].kept);
    CHECK(a.chosen.settle_stable_us == a.settle_stable_steps[stable].settle_stable_us);
    CHECK(heaviest.frame_accuracy == doctest::Approx(window_frames / n).epsilon(1e-12));
    CHECK(heaviest.segment_f1 == doctest::Approx(window_f1 / n).epsilon(1e-12));
    // One weight kept: the best settled frames, a heavier one only when it gains more
    // than the tie over the one kept before it; deterministic.
    std::size_t kept_windows = 0, expected_window = 0;
    for (std::size_t i = 0; i < a.direction_window_steps.size(); ++i) {
        const DirectionWindowStep& step = a.direction_window_steps[i];
        CHECK(step.direction_weight == direction_window_candidates[i]);
        CHECK(step.frame_accuracy == b.direction_window_steps[i].frame_accuracy);
        if (step.frame_accuracy > a.direction_window_steps[expected_window].frame_accuracy + direction_window_tie)
            expected_window = i;
        kept_windows += step.kept;
    }
    CHECK(kept_windows == 1);
    CHECK(a.direction_window_steps[expected_window].kept);
    CHECK(a.chosen.direction_weight == a.direction_window_steps[expected_window].direction_weight);
    for (const DirectionWindowStep& step : a.direction_window_steps)
        CHECK(step.frame_accuracy <= a.direction_window_steps[expected_window].frame_accuracy + direction_window_tie);
    // The model keeps the window only when it is weighed.
    CHECK(a.chosen_direction_window_s == (a.chosen.direction_weight > 0 ? online_tuning_window_s : 0.0));
    CHECK(longest_lead.frame_accuracy == doctest::Approx(led_frames / n).epsilon(1e-12));
    CHECK(longest_lead.segment_f1 == doctest::Approx(led_f1 / n).epsilon(1e-12));
    // One lead kept: the best settled frames, the shorter on a tie; deterministic.
    std::size_t kept_leads = 0;
    for (std::size_t i = 0; i < a.label_lead_steps.size(); ++i) {
        CHECK(a.label_lead_steps[i].frame_accuracy == b.label_lead_steps[i].frame_accuracy);
        if (!a.label_lead_steps[i].kept) continue;
        ++kept_leads;
        CHECK(a.chosen_label_lead_us == a.label_lead_steps[i].label_lead_us);
        for (std::size_t j = 0; j < a.label_lead_steps.size(); ++j) {
            CHECK(a.label_lead_steps[j].frame_accuracy <= a.label_lead_steps[i].frame_accuracy + 1e-9);
            if (j < i) CHECK(a.label_lead_steps[j].frame_accuracy < a.label_lead_steps[i].frame_accuracy - 1e-9);
        }
    }
    CHECK(kept_leads == 1);
    TrainingOptions adopted = options;
    adopt_online_tuning(a, adopted);
    CHECK(adopted.label_lead_us == a.chosen_label_lead_us);
    CHECK(adopted.min_action_us == a.chosen_min_action_us);
    CHECK(adopted.online.segment_penalty == a.chosen.segment_penalty);
    CHECK(adopted.online.settle_stable_us == a.chosen.settle_stable_us);
    CHECK(adopted.online.direction_weight == a.chosen.direction_weight);
    CHECK(adopted.direction_window_s == a.chosen_direction_window_s);
    // One kept, by the one-standard-error rule, and it is the model's.
    std::size_t kept_actions = 0;
    for (std::size_t i = 0; i < a.min_action_steps.size(); ++i) {
        CHECK(a.min_action_steps[i].event_segment_f1 == b.min_action_steps[i].event_segment_f1);
        if (a.min_action_steps[i].kept) ++kept_actions;
    }
    CHECK(kept_actions == 1);
    CHECK(a.min_action_steps[one_standard_error_choice(a.min_action_steps)].kept);
    CHECK(a.chosen_min_action_us == a.min_action_steps[one_standard_error_choice(a.min_action_steps)].min_action_us);
    // One subject: nothing to hold out, the given settings come back.
    std::vector<LabelledClip> one = clips;
    for (LabelledClip& c : one) c.subject = "s";
    options.min_action_us = 400000;
    options.label_lead_us = 70000;
    const OnlineTuningResult single = tune_online(one, options);
    CHECK(single.steps.empty());
    CHECK(single.min_action_steps.empty());
    CHECK(single.settle_stable_steps.empty());
    CHECK(single.chosen.segment_penalty == options.online.segment_penalty);
    CHECK(single.chosen_min_action_us == 400000);
    CHECK(single.label_lead_steps.empty());
    CHECK(single.chosen_label_lead_us == 70000);
}

TEST_CASE(
    "a latency budget: shorter settle delays and early settling tried, only what meets it kept, the fastest when "
    "nothing does") {
    ToyWorld world = make_toy_world();
    const std::vector<LabelledClip> clips = noisy_clips(world, 3);
    TrainingOptions options = tuning_start();
    options.pca_dim = 6;
    const OnlineTuningResult free = tune_online(clips, options);
    // A budget every setting meets: three settle delays and early settling at 2 s, the same choice of
    // those at 2 s.
    options.latency_budget_s = 60;
    const OnlineTuningResult loose = tune_online(clips, options);
    REQUIRE(loose.steps.size() == 4 * free.steps.size());  // settle 2, 1.5 and 1 s, and 2 s with 1 s early
    CHECK(loose.latency_budget_met);
    for (std::size_t i = 0; i < loose.steps.size(); ++i) {
        const actionstring::SegmenterConfig& c = loose.steps[i].config;
        const std::size_t block = i / free.steps.size();
        CHECK(c.settle_delay_us == (block == 0 || block == 3 ? 2000000 : block == 1 ? 1500000 : 1000000));
        CHECK(c.settle_stable_us == (block == 3 ? budget_stable_us : 0));
    }
    // Early settling's candidates stop below the chosen delay (the delay alone last).
    for (const SettleStableStep& step : loose.settle_stable_steps)
        CHECK((step.settle_stable_us == 0 || step.settle_stable_us < loose.chosen.settle_delay_us));
    CHECK(loose.settle_stable_steps.back().settle_stable_us == 0);
    for (std::size_t i = 0; i < free.steps.size(); ++i) {
        CHECK(loose.steps[i].segment_f1 == free.steps[i].segment_f1);
        CHECK(loose.steps[i].detection_latency_s == free.steps[i].detection_latency_s);
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < loose.steps.size(); ++i)
        if (loose.steps[i].segment_f1 > loose.steps[best].segment_f1) best = i;
    CHECK(loose.steps[best].kept);
    // A budget between the fastest and the slowest settings: what is kept meets
    // it, and is the best segment F1 of what does.
    double fastest = loose.steps[0].detection_latency_s, slowest = fastest;
    for (const OnlineTuningStep& step : loose.steps) {
        fastest = std::min(fastest, step.detection_latency_s);
        slowest = std::max(slowest, step.detection_latency_s);
    }
    REQUIRE(fastest < slowest);  // the settle delay moves the latency
    options.latency_budget_s = 0.5 * (fastest + slowest);
    const OnlineTuningResult tight = tune_online(clips, options);
    CHECK(tight.latency_budget_met);
    for (const OnlineTuningStep& step : tight.steps) {
        if (!step.kept) continue;
        CHECK(step.detection_latency_s <= options.latency_budget_s);
        CHECK(tight.chosen.settle_delay_us == step.config.settle_delay_us);
        for (const OnlineTuningStep& other : tight.steps)
            if (other.detection_latency_s <= options.latency_budget_s) CHECK(other.segment_f1 <= step.segment_f1);
    }
    for (const MinActionStep& step : tight.min_action_steps)
        if (step.kept) CHECK(step.detection_latency_s <= options.latency_budget_s);
    for (const SettleStableStep& step : tight.settle_stable_steps)
        if (step.kept) CHECK(step.detection_latency_s <= options.latency_budget_s);
    // A budget nothing meets: the fastest setting and the shortest action, and it says so.
    options.latency_budget_s = 0.01;
    const OnlineTuningResult impossible = tune_online(clips, options);
    CHECK_FALSE(impossible.latency_budget_met);
    for (const OnlineTuningStep& step : impossible.steps)
        if (step.kept) CHECK(step.detection_latency_s == doctest::Approx(fastest));
    CHECK(impossible.min_action_steps.front().kept);
    CHECK(impossible.settle_stable_steps.front().kept);  // the fastest early settling too
    CHECK(impossible.chosen_min_action_us == min_action_candidates_us[0]);
}

TEST_CASE("the one-standard-error rule: the fastest on the folds within one standard error of the best") {
    // A step by its per-fold F1 (three folds) and its mean latency.
    auto step = [](std::int64_t us, std::vector<double> folds, double latency = 0.0) {
        MinActionStep s;
        s.min_action_us = us;
        s.fold_event_segment_f1 = folds;
        s.event_segment_f1 = (folds[0] + folds[1] + folds[2]) / 3.0;
        s.detection_latency_s = latency;
        return s;
    };
    CHECK(one_standard_error_choice(std::vector<MinActionStep>{}) == 0);
    // Differences from the best (0.8, 0.6, 0.7): 0.25 s falls short by 0.1 on every fold (no spread: not
    // within); 0.5 s by 0.03, -0.01 and 0.01, 0.01 on average with a standard error of 0.012: within, and the
    // shortest within wins.
    const std::vector<MinActionStep> steps{step(250000, {0.7, 0.5, 0.6}), step(500000, {0.77, 0.61, 0.69}),
                                           step(750000, {0.8, 0.6, 0.7})};
    CHECK(one_standard_error_choice(steps) == 1);
    // The same differences at other levels per fold: paired, the levels do not matter. Unpaired, the best
    // mean's standard error (0.17 over these folds) would have let 0.25 s within.
    const std::vector<MinActionStep> levelled{step(250000, {0.9, 0.3, 0.6}), step(500000, {0.97, 0.41, 0.69}),
                                              step(750000, {1.0, 0.4, 0.7})};
    CHECK(one_standard_error_choice(levelled) == 1);
    // A clear gain buys latency; with no gain, the shortest.
    CHECK(one_standard_error_choice({step(250000, {0.6, 0.6, 0.6}), step(500000, {0.8, 0.8, 0.81})}) == 1);
    CHECK(one_standard_error_choice({step(250000, {0.8, 0.8, 0.8}), step(500000, {0.8, 0.8, 0.8})}) == 0);
    CHECK(one_standard_error_choice({step(250000, {0.9, 0.8, 0.7}), step(500000, {0.8, 0.7, 0.6})}) == 0);
    // The fastest on the folds among those within: a later candidate that reported sooner.
    std::vector<MinActionStep> timed{step(250000, {0.78, 0.77, 0.79}, 2.3), step(500000, {0.8, 0.79, 0.81}, 2.5),
                                     step(750000, {0.79, 0.8, 0.8}, 2.2), step(1000000, {0.7, 0.7, 0.7}, 1.0)};
    CHECK(one_standard_error_choice(timed) == 2);  // 1.0 s is faster but not within; 0.25 s is not within
    timed[2].detection_latency_s = 2.5;
    CHECK(one_standard_error_choice(timed) == 1);  // a tie in latency: the earlier
}

TEST_CASE("counts and indices refuse a fraction rather than truncate it") {
    TrainingOptions options;
    ReadOptions read;
    for (const char* name : {"components", "pca", "em-iterations", "em-restarts", "max-characters",
                             "max-representative-chars", "neighbours", "exemplars", "exemplar-dims",
                             "descriptor-levels", "descriptor-dims", "direction-levels", "seed", "body"}) {
        CAPTURE(name);
        CHECK_THROWS_WITH_AS(apply_training_setting(name, "2.5", options, read),
                             doctest::Contains("expects a whole number"), std::invalid_argument);
        CHECK(apply_training_setting(name, "3", options, read));
    }
    CHECK(options.pca_dim == 3);
    CHECK(options.exemplar_dims == 3);
    CHECK(read.body == 3);
    CHECK(apply_training_setting("pca", "16.0", options, read));  // a whole number written with a point
    CHECK(options.pca_dim == 16);
    CHECK_THROWS_WITH_AS(apply_training_setting("pca", "1e9", options, read), doctest::Contains("[0, 65535]"),
                         std::invalid_argument);
    // Real-valued settings keep their fractions.
    CHECK(apply_training_setting("sigma", "0.75", options, read));
    CHECK(options.sigma == 0.75);
    CHECK(apply_training_setting("max-representative-share", "0.7", options, read));
    CHECK(options.max_representative_share == 0.7);
    CHECK(options_as_config(options).find("max-representative-share 0.7\n") != std::string::npos);
    // The clip descriptor's settings go into the config a user keeps, and come back from it.
    CHECK(apply_training_setting("descriptor-ridge", "3000", options, read));
    CHECK(apply_training_setting("descriptor-weight", "24", options, read));
    const std::string config = options_as_config(options);
    for (const char* line :
         {"descriptor-levels 3\n", "descriptor-dims 3\n", "descriptor-ridge 3000\n", "descriptor-weight 24\n"})
        CHECK(config.find(line) != std::string::npos);
    TrainingOptions back;
    std::istringstream lines(config);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t space = line.find(' ');
        if (space != std::string::npos)
            apply_training_setting(line.substr(0, space), line.substr(space + 1), back, read);
    }
    CHECK(back.descriptor_levels == 3);
    CHECK(back.descriptor_dims == 3);
    CHECK(back.descriptor_ridge == 3000.0);
    CHECK(back.descriptor_weight == 24.0);
    CHECK_THROWS_AS(apply_training_setting("descriptor-dims", "65", options, read), std::invalid_argument);
    CHECK_THROWS_AS(apply_training_setting("descriptor-levels", "9", options, read), std::invalid_argument);
    // And the motion directions'.
    CHECK(apply_training_setting("direction-ridge", "3000", options, read));
    CHECK(apply_training_setting("direction-weight", "8", options, read));
    const std::string with_directions = options_as_config(options);
    for (const char* line : {"direction-levels 3\n", "direction-ridge 3000\n", "direction-weight 8\n"})
        CHECK(with_directions.find(line) != std::string::npos);
    TrainingOptions again;
    std::istringstream directed(with_directions);
    for (std::string line; std::getline(directed, line);) {
        const std::size_t space = line.find(' ');
        if (space != std::string::npos)
            apply_training_setting(line.substr(0, space), line.substr(space + 1), again, read);
    }
    CHECK(again.direction_levels == 3);
    CHECK(again.direction_ridge == 3000.0);
    CHECK(again.direction_weight == 8.0);
    CHECK_THROWS_AS(apply_training_setting("direction-levels", "9", options, read), std::invalid_argument);
    CHECK_THROWS_AS(apply_training_setting("direction-weight", "-1", options, read), std::invalid_argument);
}

TEST_CASE("yes/no settings take true/false (or on/off, yes/no, 1/0) and refuse anything else") {
    TrainingOptions options;
    ReadOptions read;
    CHECK(options.no_action_exemplars);
    for (const char* no : {"false", "0", "off", "no"}) {
        options.no_action_exemplars = true;
        CHECK(apply_training_setting("no-action-exemplars", no, options, read));
        CHECK_FALSE(options.no_action_exemplars);
    }
    for (const char* yes : {"", "true", "1", "on", "yes"}) {
        options.mirror = false;
        CHECK(apply_training_setting("mirror", yes, options, read));
        CHECK(options.mirror);
    }
    CHECK_THROWS_WITH_AS(apply_training_setting("keep-singletons", "maybe", options, read),
                         doctest::Contains("expected true or false, not 'maybe'"), std::invalid_argument);
    // What self-tuning echoes as a config reads back to the same options.
    options.exemplars = 8;
    options.exemplar_weight = 2.0;
    options.no_action_exemplars = false;
    const std::string config = options_as_config(options);
    CHECK(config.find("no-action-exemplars false") != std::string::npos);
    TrainingOptions again;
    std::size_t start = 0;
    while (start < config.size()) {
        const std::size_t end = config.find('\n', start);
        const std::string line = config.substr(start, end - start);
        start = end == std::string::npos ? config.size() : end + 1;
        if (line.empty() || line[0] == '#') continue;
        const std::size_t space = line.find(' ');
        apply_training_setting(line.substr(0, space), space == std::string::npos ? "" : line.substr(space + 1), again,
                               read);
    }
    CHECK_FALSE(again.no_action_exemplars);
    CHECK(again.exemplars == 8);
}
