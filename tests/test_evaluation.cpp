// Evaluation: metrics on hand-made predictions, JSON, and the baselines on the toy world.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "eval/baselines.hpp"
#include "eval/clip_eval.hpp"
#include "eval/json.hpp"
#include "eval/online.hpp"
#include "eval/report.hpp"
#include "eval/significance.hpp"
#include "run/classify.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

TEST_CASE("accuracy, unknown rate, confusion, precision and recall") {
    std::vector<LabelledClip> clips(4);
    clips[0].label = clips[1].label = "a";
    clips[2].label = clips[3].label = "b";
    ClipResults r;
    r.labels = {"a", "b"};
    r.predictions = {0, 1, 1, -1};
    summarise(r, clips);
    CHECK(r.clip_accuracy == doctest::Approx(0.5));
    CHECK(r.unknown_rate == doctest::Approx(0.25));
    CHECK(r.confusion == std::vector<std::vector<int>>{{1, 1, 0}, {0, 1, 1}});
    CHECK(r.precision == std::vector<double>{1.0, 0.5});
    CHECK(r.recall == std::vector<double>{0.5, 0.5});
    JsonWriter writer;
    write_json(writer, r, clips);
    const std::string json = writer.str();
    CHECK(json.find("\"clip_accuracy\": 0.5") != std::string::npos);
    CHECK(json.find("\"confusion\": [[1, 1, 0], [0, 1, 1]]") != std::string::npos);
    CHECK(json.find("\"b\": {\"precision\": 0.5, \"recall\": 0.5, \"support\": 2}") != std::string::npos);
    CHECK(std::count(json.begin(), json.end(), '{') == std::count(json.begin(), json.end(), '}'));
    CHECK(std::count(json.begin(), json.end(), '[') == std::count(json.begin(), json.end(), ']'));
    // No clip names a subject: no per-subject scores.
    CHECK(r.per_subject.empty());
    CHECK(json.find("\"per_subject\": []") != std::string::npos);
}

TEST_CASE("per-subject clip accuracy, in the order of the subjects' names") {
    std::vector<LabelledClip> clips(5);
    const char* labels[] = {"a", "b", "a", "b", "a"};
    const char* subjects[] = {"s2", "s1", "s2", "s1", "s1"};
    for (std::size_t c = 0; c < clips.size(); ++c) clips[c].label = labels[c], clips[c].subject = subjects[c];
    ClipResults r;
    r.labels = {"a", "b"};
    r.predictions = {0, 1, 1, -1, 0};  // s2: right, wrong; s1: right, unknown, right
    summarise(r, clips);
    REQUIRE(r.per_subject.size() == 2);
    CHECK(r.per_subject[0].subject == "s1");
    CHECK(r.per_subject[0].clips == 3);
    CHECK(r.per_subject[0].correct == 2);
    CHECK(r.per_subject[0].accuracy == doctest::Approx(2.0 / 3.0));
    CHECK(r.per_subject[1].subject == "s2");
    CHECK(r.per_subject[1].clips == 2);
    CHECK(r.per_subject[1].correct == 1);
    CHECK(r.per_subject[1].accuracy == doctest::Approx(0.5));
    JsonWriter writer;
    write_json(writer, r, clips);
    CHECK(writer.str().find("\"per_subject\": [{\"subject\": \"s1\", \"clips\": 3, \"correct\": 2, "
                            "\"clip_accuracy\": 0.666") != std::string::npos);
    // Summarised again (another method on the same clips), nothing accumulates.
    summarise(r, clips);
    CHECK(r.per_subject.size() == 2);
    CHECK(r.per_subject[0].clips == 3);
}

TEST_CASE("the 95% Wilson interval of an accuracy, against values worked by hand") {
    // 0 of 10: the upper end is z² / (n + z²); 5 of 10 and 42 of 44 (HDM05 val's size)
    // from the score formula, centre (p + z²/2n) / (1 + z²/n) ± its half-width.
    const Interval none = wilson_interval(0, 10);
    CHECK(none.low == 0.0);
    CHECK(none.high == doctest::Approx(0.27753).epsilon(1e-4));
    const Interval all = wilson_interval(10, 10);
    CHECK(all.low == doctest::Approx(0.72247).epsilon(1e-4));
    CHECK(all.high == 1.0);
    const Interval half = wilson_interval(5, 10);
    CHECK(half.low == doctest::Approx(0.23659).epsilon(1e-4));
    CHECK(half.high == doctest::Approx(0.76341).epsilon(1e-4));
    const Interval hdm05 = wilson_interval(42, 44);
    CHECK(hdm05.low == doctest::Approx(0.8487).epsilon(1e-3));
    CHECK(hdm05.high == doctest::Approx(0.9874).epsilon(1e-3));
    // No trials: nothing is known. More trials: a narrower interval around the same rate.
    CHECK(wilson_interval(0, 0).low == 0.0);
    CHECK(wilson_interval(0, 0).high == 1.0);
    const Interval many = wilson_interval(500, 1000);
    CHECK(many.high - many.low < half.high - half.low);
    CHECK(many.low < 0.5);
    CHECK(many.high > 0.5);
}

TEST_CASE("the exact McNemar test: binomial tails by hand, symmetric, sane at scale") {
    // 5 against 1: 2 · (C(6,0) + C(6,1)) / 2⁶ = 14 / 64; 6 against 0: 2 / 64.
    CHECK(mcnemar_exact_p(5, 1) == doctest::Approx(14.0 / 64.0));
    CHECK(mcnemar_exact_p(1, 5) == doctest::Approx(14.0 / 64.0));
    CHECK(mcnemar_exact_p(6, 0) == doctest::Approx(2.0 / 64.0));
    CHECK(mcnemar_exact_p(0, 0) == 1.0);
    CHECK(mcnemar_exact_p(3, 3) == 1.0);
    CHECK(mcnemar_exact_p(1, 0) == 1.0);
    CHECK(mcnemar_exact_p(3, 2) == 1.0);  // exactly, not 1 less rounding
    CHECK(mcnemar_exact_p(4, 2) == doctest::Approx(2.0 * 22.0 / 64.0));  // 2 · (1 + 6 + 15) / 2⁶
    // 100 against 50: the normal approximation with continuity, (|b − c| − 1)² / (b + c) = 16.0,
    // gives about 6e-5; the exact tail is of that order and neither overflows nor vanishes.
    const double p = mcnemar_exact_p(100, 50);
    CHECK(p > 1e-5);
    CHECK(p < 2e-4);
    const double huge = mcnemar_exact_p(60000, 40000);
    CHECK(huge >= 0.0);
    CHECK(huge < 1e-100);
    CHECK(mcnemar_exact_p(50000, 50000) == 1.0);
}

TEST_CASE("a baseline is paired with the model clip by clip") {
    std::vector<LabelledClip> clips(6);
    for (std::size_t c = 0; c < clips.size(); ++c) clips[c].label = c < 3 ? "a" : "b";
    ClipResults model, baseline;
    model.labels = baseline.labels = {"a", "b"};
    model.predictions = {0, 0, 1, 1, 1, -1};    // right on 0, 1, 3, 4
    baseline.predictions = {0, 1, 1, 1, 0, 1};  // right on 0, 3, 5
    summarise(model, clips);
    summarise(baseline, clips);
    CHECK(model.correct == 4);
    CHECK(model.accuracy_interval.low < model.clip_accuracy);
    CHECK(model.accuracy_interval.high > model.clip_accuracy);
    compare_with_model(model, baseline, clips);
    CHECK(baseline.paired);
    CHECK(baseline.model_only == 2);   // clips 1 and 4
    CHECK(baseline.method_only == 1);  // clip 5
    CHECK(baseline.mcnemar_p == doctest::Approx(mcnemar_exact_p(2, 1)));
    JsonWriter writer;
    write_json(writer, baseline, clips);
    const std::string json = writer.str();
    CHECK(json.find("\"paired_with_model\": {\"model_only\": 2, \"baseline_only\": 1, \"mcnemar_p\": 1}") !=
          std::string::npos);
    CHECK(json.find("\"clip_accuracy_ci95\": [") != std::string::npos);
}

TEST_CASE("the model and every baseline recognise held-out toy performances") {
    ToyWorld world = make_toy_world();
    const TrainingOptions options = test::toy_options();
    const auto train = toy_clips(world, 5, 300);
    const auto test = toy_clips(world, 4, 7000, 30.0);
    ModelData model = train_model(train, options);
    const ModelView view = model.view();
    CHECK(evaluate_model(view, test).clip_accuracy >= 0.9);
    CHECK(evaluate_all_strings(view, train, test).clip_accuracy >= 0.9);
    const ClipResults dtw = evaluate_pose_dtw(view, train, test);
    CHECK(dtw.clip_accuracy >= 0.9);
    const ClipResults pca = evaluate_pca_characters(view, train, test);
    CHECK(pca.clip_accuracy >= 0.9);
    CHECK(pca.predictions == evaluate_pca_characters(view, train, test).predictions);
    // A single character says nothing: every string is the same, so 1-NN
    // cannot tell the four actions apart.
    ModelView one_character = view;
    one_character.character_count = 1;
    CHECK(evaluate_pca_characters(one_character, train, test).clip_accuracy <= 0.5);
    CHECK(dtw.confusion.size() == 4);
    const auto times = annotator_frame_times(view, test, annotator_config(view));
    CHECK(times.size() > 1000);
    CHECK(std::is_sorted(times.begin(), times.end()));
    // Timed with eval's settings (here the work spread): one time per frame too.
    AnnotatorConfig spread = annotator_config(view);
    spread.spread_work = true;
    CHECK(annotator_frame_times(view, test, spread).size() == times.size());
}

TEST_CASE("top-k: the true label's rank among the labels' scores, ties against it") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 5, 300);
    auto test = toy_clips(world, 3, 7100, 30.0);
    ModelData model = train_model(train, test::toy_options());
    const ModelView view = model.view();
    REQUIRE(view.label_count == 4);
    // A clip of an action the model does not know is never within the top k.
    LabelledClip stranger = test.front();
    stranger.label = "unseen";
    test.push_back(stranger);
    const ClipResults r = evaluate_model(view, test);
    REQUIRE(r.top_k.size() == 3);
    std::vector<std::size_t> within(3, 0);
    for (const LabelledClip& c : test) {
        const std::vector<float> scores = host::label_distances(view, c.clip);
        const auto truth = static_cast<std::size_t>(label_index(r.labels, c.label));
        if (truth >= view.label_count) continue;
        std::size_t ahead = 0;
        for (std::size_t l = 0; l < scores.size(); ++l) ahead += l != truth && scores[l] <= scores[truth];
        for (std::size_t k = ahead; k < 3; ++k) ++within[k];
    }
    for (std::size_t k = 0; k < 3; ++k)
        CHECK(r.top_k[k] == doctest::Approx(static_cast<double>(within[k]) / static_cast<double>(test.size())));
    CHECK(std::is_sorted(r.top_k.begin(), r.top_k.end()));
    CHECK(r.top_k[2] < 1.0);  // the stranger
    // One neighbour and no rejection: top-1 is the clip accuracy.
    REQUIRE(view.neighbours == 1);
    CHECK(r.top_k[0] == doctest::Approx(r.clip_accuracy));
    // The baselines carry no ranking; the JSON carries the model's.
    CHECK(evaluate_pose_dtw(view, train, test).top_k.empty());
}

TEST_CASE("report.md: the clip table, the model's top-k and the confusion picture") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 5, 300);
    const auto test = toy_clips(world, 2, 7200, 30.0);
    ModelData model = train_model(train, test::toy_options());
    const ModelView view = model.view();
    const ClipResults mine = evaluate_model(view, test);
    const ClipResults dtw = evaluate_pose_dtw(view, train, test);
    // Its own folder: builds of the tests may run side by side.
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() /
        ("actionstring_report_test_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::remove_all(folder);
    write_report(folder.string(), "toy", {mine, dtw}, nullptr, mine.labels);
    std::ifstream in(folder / "report.md");
    REQUIRE(in.good());
    const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(md.find("| " + mine.method + " | ") != std::string::npos);
    CHECK(md.find("| " + dtw.method + " | ") != std::string::npos);
    std::ostringstream top;
    top.precision(3);
    top << std::fixed << "top-1 " << mine.top_k[0] << ", top-2 " << mine.top_k[1] << ", top-3 " << mine.top_k[2] << ".";
    CHECK(md.find(top.str()) != std::string::npos);
    CHECK(md.find("confusion.svg") != std::string::npos);
    CHECK(std::filesystem::exists(folder / "confusion.svg"));
    in.close();
    // With the online streams: their table and when the settled labels became final.
    const OnlineReport online = evaluate_online(view, test, 1);
    write_report(folder.string(), "toy", {mine, dtw}, &online, mine.labels);
    std::ifstream again(folder / "report.md");
    const std::string with_online((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
    CHECK(with_online.find("| segmenter, settled labels | ") != std::string::npos);
    std::ostringstream final_after;
    final_after.precision(3);
    final_after << std::fixed << "became final a median " << online.settled.final_after_median_s
                << " s after their frames (95th percentile " << online.settled.final_after_p95_s << " s)";
    CHECK(with_online.find(final_after.str()) != std::string::npos);
    again.close();
    std::filesystem::remove_all(folder);
}

TEST_CASE("online metrics on a timeline scored by hand") {
    // One stream, 1 s per frame: truth 0 0 0 0 1 1 1 1, prediction ? ? 0 0 0 1 1 1.
    const std::vector<int> truth{0, 0, 0, 0, 1, 1, 1, 1}, predicted{-1, -1, 0, 0, 0, 1, 1, 1};
    const std::vector<double> times{0, 1, 2, 3, 4, 5, 6, 7};
    const OnlineResults r = score_timeline(truth, predicted, times, {0, 8});
    CHECK(r.frame_accuracy == doctest::Approx(5.0 / 8));
    // Segment 0: IoU 2/5 < 0.5, not matched; segment 1: IoU 3/4, matched. 2 predicted, 2 true.
    CHECK(r.segment_precision == doctest::Approx(0.5));
    CHECK(r.segment_recall == doctest::Approx(0.5));
    CHECK(r.segment_f1 == doctest::Approx(0.5));
    CHECK(r.mean_delay_s == doctest::Approx(1.5));  // 2 s and 1 s
    CHECK(r.missed_segments == 0);
    CHECK(r.true_changes_per_min == doctest::Approx(60.0 / 7));
    CHECK(r.label_changes_per_min == doctest::Approx(120.0 / 7));
    CHECK(r.flicker_per_min == doctest::Approx(60.0 / 7));
    CHECK(r.final_after_median_s == 0.0);  // no final times given: labels with their frames
    // With the time each frame's label became final: 2, 2, 2, 2, 1, 1, 1 and 3 s after it; by nearest rank.
    const std::vector<double> final_at{2, 3, 4, 5, 5, 6, 7, 10};
    const OnlineResults timed = score_timeline(truth, predicted, times, {0, 8}, &final_at);
    CHECK(timed.final_after_median_s == doctest::Approx(2.0));  // sorted 1 1 1 2 2 2 2 3: the 4th
    CHECK(timed.final_after_p95_s == doctest::Approx(3.0));     // the 8th
    // Two streams: the boundary between them is not a label change, and a never-found segment is missed.
    const OnlineResults split = score_timeline({0, 0, 1, 1}, {0, 0, 0, 0}, {0, 1, 0, 1}, {0, 2, 4});
    CHECK(split.true_changes_per_min == 0.0);
    CHECK(split.missed_segments == 1);
}

TEST_CASE("frames by class: the confusion, each class's recall and precision, what it was taken for") {
    // Truth:      -  -  -  0  0  0  0  1  1  2  x      (- no action, x a label the model does not know)
    // Prediction: -  0  -  0  0  -  1  1  1  -  0
    const std::vector<int> truth{-1, -1, -1, 0, 0, 0, 0, 1, 1, 2, -2}, predicted{-1, 0, -1, 0, 0, -1, 1, 1, 1, -1, 0};
    std::vector<double> times(truth.size());
    for (std::size_t i = 0; i < times.size(); ++i) times[i] = static_cast<double>(i);
    const OnlineResults r = score_timeline(truth, predicted, times, {0, truth.size()});
    REQUIRE(r.confusion_labels == 3);
    REQUIRE(r.frame_confusion.size() == 20);  // 5 rows (no action, 0, 1, 2, labels not in the model) of 4
    CHECK(r.confused(-1, -1) == 2);
    CHECK(r.confused(-1, 0) == 1);
    CHECK(r.confused(0, 0) == 2);
    CHECK(r.confused(0, -1) == 1);
    CHECK(r.confused(0, 1) == 1);
    CHECK(r.confused(1, 1) == 2);
    CHECK(r.confused(2, -1) == 1);
    CHECK(r.confused(2, 2) == 0);
    CHECK(r.confused(3, 0) == 0);   // outside the table
    CHECK(r.confused(-2, 0) == 1);  // the last row: the frame of a label the model does not know
    CHECK(r.confused(-2, -1) == 0);
    CHECK(r.confused(-3, 0) == 0);
    std::size_t counted = 0;
    for (std::size_t n : r.frame_confusion) counted += n;
    CHECK(counted == truth.size());

    const std::vector<FrameClassScore> classes = frame_class_scores(r);
    REQUIRE(classes.size() == 4);  // no action, then labels 0, 1, 2
    CHECK(classes[0].label == -1);
    CHECK(classes[0].frames == 3);
    CHECK(classes[0].recall == doctest::Approx(2.0 / 3));
    CHECK(classes[0].precision == doctest::Approx(2.0 / 4));  // unknown said 4 times, twice rightly
    CHECK(classes[0].most_taken_for == 0);
    CHECK(classes[0].most_taken_for_frames == 1);
    CHECK(classes[1].label == 0);
    CHECK(classes[1].frames == 4);
    CHECK(classes[1].right == 2);
    CHECK(classes[1].labelled == 4);  // the frame of a label the model does not know, called 0, too
    CHECK(classes[1].recall == doctest::Approx(0.5));
    CHECK(classes[1].precision == doctest::Approx(0.5));
    CHECK(classes[1].f1 == doctest::Approx(2.0 * 2 / (4 + 4)));
    CHECK(classes[1].most_taken_for == -1);  // a tie of one frame each: unknown (−1) before label 1
    CHECK(classes[1].most_taken_for_frames == 1);
    CHECK(classes[2].recall == doctest::Approx(1.0));
    CHECK(classes[2].precision == doctest::Approx(2.0 / 3));
    CHECK(classes[2].most_taken_for_frames == 0);
    // An action missed whole: recall, precision and F1 0, taken for no action.
    CHECK(classes[3].label == 2);
    CHECK(classes[3].recall == 0.0);
    CHECK(classes[3].precision == 0.0);
    CHECK(classes[3].f1 == 0.0);
    CHECK(classes[3].most_taken_for == -1);
    // The per-class F1 of the actions is what frame F1 averages.
    CHECK(r.frame_f1 == doctest::Approx((classes[1].f1 + classes[2].f1 + classes[3].f1) / 3));
    CHECK(frame_class_name(-1, {"a", "b"}) == "no action");
    CHECK(frame_class_name(1, {"a", "b"}) == "b");
    CHECK(frame_class_name(5, {"a", "b"}) == "5");

    // In JSON, with names: the whole table, and the classes named.
    JsonWriter out;
    const std::vector<std::string> names{"kick", "punch", "wave"};
    write_json(out, r, &names);
    const std::string json = out.str();
    CAPTURE(json);
    CHECK(json.find("\"frame_confusion\": [[2, 1, 0, 0], [1, 2, 1, 0], [0, 0, 2, 0], [1, 0, 0, 0]]") !=
          std::string::npos);
    CHECK(json.find("{\"label\": \"wave\", \"frames\": 1, \"right\": 0, \"labelled\": 0, \"recall\": 0") !=
          std::string::npos);
    CHECK(json.find("\"most_taken_for\": \"kick\"") != std::string::npos);
    CHECK(json.find("\"frame_confusion_unmodelled\": [0, 1, 0, 0]") != std::string::npos);
    // Without names, neither.
    JsonWriter plain;
    write_json(plain, r);
    CHECK(plain.str().find("frame_confusion") == std::string::npos);
}

TEST_CASE("online evaluation streams concatenated toy clips deterministically") {
    ToyWorld world = make_toy_world();
    const TrainingOptions options = test::toy_options();
    ModelData model = train_model(toy_clips(world, 5, 300), options);
    const ModelView view = model.view();
    const auto test = toy_clips(world, 4, 7000, 30.0);
    const OnlineReport a = evaluate_online(view, test, 3), b = evaluate_online(view, test, 3);
    CHECK(a.settled.frames > 1000);
    CHECK(a.settled.frame_accuracy == b.settled.frame_accuracy);
    CHECK(a.window.frame_accuracy == b.window.frame_accuracy);
    CHECK(a.window.frame_accuracy > 0.3);  // the latest-window rule lags by about a window
    // The segmenter explains the stream as actions end to end and settles 2 s later.
    CHECK(a.settled.frame_accuracy > a.window.frame_accuracy);
    CHECK(a.settled.frame_accuracy > 0.8);
    CHECK(a.settled.mean_delay_s >= 1.9);  // never before the settle delay
    // Each frame's label is final the settle delay after it (to within a frame and a string
    // period); the other rules' labels come with their frames.
    CHECK(a.settled.final_after_median_s >= 1.9);
    CHECK(a.settled.final_after_median_s <= a.settled.final_after_p95_s);
    CHECK(a.settled.final_after_p95_s <= 2.2);
    CHECK(a.live.final_after_median_s == 0.0);
    // With early settling most labels are final sooner, none later; the same explanation.
    AnnotatorConfig early = annotator_config(view);
    early.segmenter.settle_stable_us = 500000;
    const OnlineReport e = evaluate_online(view, test, 3, early);
    CHECK(e.settled.final_after_median_s < a.settled.final_after_median_s - 0.5);
    CHECK(e.settled.final_after_p95_s <= 2.2);
    CHECK(e.live.frame_accuracy == a.live.frame_accuracy);
    CHECK(e.settled.detection_latency_s < a.settled.detection_latency_s);  // the events come sooner
    CHECK(a.live.frame_accuracy > 0.3);
    CHECK(a.settled.segment_f1 >= 0.0);
    CHECK(a.settled.segment_f1 <= 1.0);
    // The intervals' units add up to the figures, and the intervals hold them.
    std::size_t frames = 0, right = 0, matched = 0, segments = 0, events_matched = 0, events = 0;
    for (const OnlineResults::Unit& unit : a.settled.units) {
        frames += unit.frames, right += unit.right, matched += unit.matched;
        segments += unit.predicted + unit.true_segments;
        events_matched += unit.iou_matched_events, events += unit.reported + unit.true_actions;
    }
    CHECK(frames == a.settled.frames);
    CHECK(static_cast<double>(right) / static_cast<double>(frames) == doctest::Approx(a.settled.frame_accuracy));
    CHECK(2.0 * static_cast<double>(matched) / static_cast<double>(segments) == doctest::Approx(a.settled.segment_f1));
    CHECK(events_matched == a.settled.iou_matched_events);
    CHECK(2.0 * static_cast<double>(events_matched) / static_cast<double>(events) ==
          doctest::Approx(a.settled.event_segment_f1));
    // Each stream alone: one per stream, its frames and right frames adding up to the pooled ones;
    // scored alone, a stream gets what the pooled scoring gives it (its units' right frames).
    REQUIRE(a.per_stream.size() == a.streams.size());
    REQUIRE(a.streams.size() >= 2);
    std::size_t stream_frames = 0;
    double stream_right = 0;
    for (std::size_t s = 0; s < a.per_stream.size(); ++s) {
        CHECK(a.per_stream[s].frames == a.streams[s].times_s.size());
        stream_frames += a.per_stream[s].frames;
        stream_right += a.per_stream[s].frame_accuracy * static_cast<double>(a.per_stream[s].frames);
        CHECK(a.per_stream[s].has_events);
        CHECK(a.per_stream[s].frame_accuracy == b.per_stream[s].frame_accuracy);
    }
    CHECK(stream_frames == a.settled.frames);
    CHECK(stream_right == doctest::Approx(a.settled.frame_accuracy * static_cast<double>(a.settled.frames)));
    // The frames by class hold every frame, the right ones on the diagonal.
    std::size_t tabled = 0, diagonal = 0;
    for (std::size_t n : a.settled.frame_confusion) tabled += n;
    for (const FrameClassScore& c : frame_class_scores(a.settled)) diagonal += c.right;
    CHECK(tabled == a.settled.frames);
    CHECK(static_cast<double>(diagonal) / static_cast<double>(tabled) == doctest::Approx(a.settled.frame_accuracy));
    CHECK(a.settled.frame_accuracy_interval.low <= a.settled.frame_accuracy);
    CHECK(a.settled.frame_accuracy_interval.high >= a.settled.frame_accuracy);
    CHECK(a.settled.segment_f1_interval.low <= a.settled.segment_f1);
    CHECK(a.settled.segment_f1_interval.high >= a.settled.segment_f1);
    CHECK(a.settled.frame_accuracy_interval.high - a.settled.frame_accuracy_interval.low < 0.5);
    CHECK(a.settled.frame_accuracy_interval.low == b.settled.frame_accuracy_interval.low);
    REQUIRE(a.streams.size() == 4);  // one per subject
    for (const StreamTimeline& s : a.streams) {
        CHECK(s.truth.size() == s.times_s.size());
        CHECK(s.labels.settled.size() == s.times_s.size());
    }
}

TEST_CASE("continuous recordings: frames outside every interval are no action, and unknown is right there") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    std::vector<ToyFrame> frames = toy_stream(world, {0, 1, 2, 3, 1}, {});
    // The toy repeats the boundary instant in the next action; a recording has one frame per instant.
    frames.erase(std::unique(frames.begin(), frames.end(),
                             [](const ToyFrame& a, const ToyFrame& b) { return a.time_us == b.time_us; }),
                 frames.end());
    LabelledRecording recording{"s1", toy_clip(frames, "rec.txt"), {}, {}};
    // Intervals from the toy's truth, except the third action, which stays unlabelled.
    std::size_t begin = 0, omitted_frames = 0;
    for (std::size_t f = 1; f <= frames.size(); ++f) {
        if (f < frames.size() && frames[f].action == frames[begin].action) continue;
        if (recording.intervals.size() == 2 && omitted_frames == 0) omitted_frames = f - begin;
        else
            recording.intervals.push_back({world.model.label_names[static_cast<std::size_t>(frames[begin].action)],
                                           recording.clip.times[begin], recording.clip.times[f - 1]});
        begin = f;
    }
    REQUIRE(recording.intervals.size() == 4);
    REQUIRE(omitted_frames > 0);
    const OnlineReport report = evaluate_recordings(view, {recording});
    REQUIRE(report.streams.size() == 1);
    const StreamTimeline& timeline = report.streams[0];
    CHECK(timeline.name == "rec.txt");
    CHECK(std::count(timeline.truth.begin(), timeline.truth.end(), -1) == static_cast<long>(omitted_frames));
    for (std::size_t f = 0; f < frames.size(); ++f)
        if (timeline.truth[f] != -1) CHECK(timeline.truth[f] == frames[f].action);
    CHECK(report.settled.no_action_frames == omitted_frames);
    // Without "no action" the segmenter labels every frame, so the parts are 0 and high.
    CHECK(report.settled.no_action_accuracy < 0.1);
    CHECK(report.settled.action_frame_accuracy > 0.8);
    const double share = static_cast<double>(omitted_frames) / static_cast<double>(frames.size());
    CHECK(report.settled.frame_accuracy == doctest::Approx(report.settled.action_frame_accuracy * (1 - share) +
                                                           report.settled.no_action_accuracy * share));

    // Each recording alone carries its own "unknown everywhere": the share of its no-action
    // frames. A second recording with every action labelled has none, so saying unknown
    // everywhere scores 0 there, while the pooled share lies between the two.
    LabelledRecording labelled = recording;
    labelled.clip.source = "labelled.txt";
    labelled.intervals.clear();
    begin = 0;
    for (std::size_t f = 1; f <= frames.size(); ++f) {
        if (f < frames.size() && frames[f].action == frames[begin].action) continue;
        labelled.intervals.push_back({world.model.label_names[static_cast<std::size_t>(frames[begin].action)],
                                      labelled.clip.times[begin], labelled.clip.times[f - 1]});
        begin = f;
    }
    const OnlineReport both = evaluate_recordings(view, {recording, labelled});
    REQUIRE(both.per_stream.size() == 2);
    CHECK(both.per_stream[0].unknown_everywhere_accuracy == doctest::Approx(share));
    CHECK(both.per_stream[1].no_action_frames == 0);
    CHECK(both.per_stream[1].unknown_everywhere_accuracy == 0.0);
    CHECK(both.settled.unknown_everywhere_accuracy == doctest::Approx(share / 2));
    JsonWriter stream_json;
    write_stream_json(stream_json, both.streams[0].name, both.per_stream[0]);
    CAPTURE(stream_json.str());
    CHECK(stream_json.str().find("\"unknown_everywhere_accuracy\": ") != std::string::npos);

    // Entries of a list: grouped by file, and a whole clip cannot be a recording.
    ClipListEntry whole;
    whole.path = "a.txt";
    CHECK_THROWS_AS(read_recordings({whole}), ReadError);
}

TEST_CASE("overlapping intervals: noted with both lines, and shared frames go to the one that starts later") {
    using Interval = LabelledRecording::Interval;
    // Back to back (one ends where the next starts) is how annotators mark
    // actions in a row: no overlap, and the shared instant is the later one's.
    const std::vector<Interval> touching{{"pull", 1.0, 2.0, 3}, {"push", 2.0, 3.0, 4}};
    CHECK(interval_overlaps(touching).empty());
    CHECK(interval_at(touching, 1.5) == 0);
    CHECK(interval_at(touching, 2.0) == 1);
    CHECK(interval_at(touching, 3.5) == -1);
    // Listed the other way round, the same instant still goes to the action that starts there.
    const std::vector<Interval> reversed{{"push", 2.0, 3.0, 3}, {"pull", 1.0, 2.0, 4}};
    CHECK(interval_at(reversed, 2.0) == 0);

    // UTKinect's s03_e01 slip, in seconds: push over 85.2-120.733 s around its throw.
    const std::vector<Interval> nested{
        {"throw", 107.533, 109.4, 30}, {"push", 85.2, 120.733, 31}, {"pull", 122.0, 124.333, 32}};
    const std::vector<IntervalOverlap> overlaps = interval_overlaps(nested);
    REQUIRE(overlaps.size() == 1);
    CHECK(overlaps[0].first == 0);
    CHECK(overlaps[0].second == 1);
    CHECK(overlaps[0].seconds == doctest::Approx(109.4 - 107.533));
    CHECK(overlaps[0].later == 0);  // the throw, listed first, starts later
    CHECK(interval_at(nested, 100.0) == 1);  // push's own frames
    CHECK(interval_at(nested, 108.0) == 0);  // the nested throw keeps its frames
    CHECK(interval_at(nested, 115.0) == 1);
    // Two that start together: the one listed last.
    CHECK(interval_at({{"a", 1.0, 4.0, 1}, {"b", 1.0, 2.0, 2}}, 1.5) == 1);
    // A partial overlap counts by its shared time.
    const std::vector<IntervalOverlap> partial = interval_overlaps({{"a", 0.0, 2.0, 1}, {"b", 1.5, 3.0, 2}});
    REQUIRE(partial.size() == 1);
    CHECK(partial[0].seconds == doctest::Approx(0.5));
    CHECK(partial[0].later == 1);

    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    const std::vector<ToyFrame> frames = toy_stream(world, {0, 1, 2}, {});
    LabelledRecording recording{"s1", toy_clip(frames, "dir/rec.txt"), {}, {}};
    const std::vector<double>& t = recording.clip.times;
    const double middle = t[t.size() / 2];
    const std::string outer = world.model.label_names[0], inner = world.model.label_names[1];
    recording.intervals = {{outer, t.front(), t.back(), 7}, {inner, middle - 0.2, middle + 0.2, 8}};
    note_interval_overlaps(recording);
    REQUIRE(recording.notes.size() == 1);
    const std::string& note = recording.notes[0];
    CAPTURE(note);
    CHECK(note.rfind("rec.txt: intervals " + outer + " ", 0) == 0);
    CHECK(note.find("(list line 7)") != std::string::npos);
    CHECK(note.find("(list line 8)") != std::string::npos);
    CHECK(note.find("overlap by 0.400 s") != std::string::npos);
    CHECK(note.find("count as " + inner + ", the one that starts later") != std::string::npos);
    // Intervals that do not overlap give no note.
    LabelledRecording apart = recording;
    apart.notes.clear();
    apart.intervals = {{outer, t.front(), middle, 1}, {inner, middle, t.back(), 2}};
    note_interval_overlaps(apart);
    CHECK(apart.notes.empty());

    // The evaluation's truth takes the same rule: the nested interval keeps its frames.
    const OnlineReport report = evaluate_recordings(view, {recording});
    REQUIRE(report.streams.size() == 1);
    const StreamTimeline& timeline = report.streams[0];
    std::size_t inner_frames = 0;
    for (std::size_t f = 0; f < t.size(); ++f) {
        const bool in_inner = t[f] >= middle - 0.2 && t[f] <= middle + 0.2;
        CHECK(timeline.truth[f] == (in_inner ? 1 : 0));
        inner_frames += in_inner ? 1u : 0u;
    }
    CHECK(inner_frames > 0);
}

TEST_CASE("annotate_clip returns a contiguous label timeline covering the clip") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    const auto frames = toy_stream(world, {0, 1, 2, 3}, {});
    const Clip clip = toy_clip(frames, "stream");
    const auto spans = annotate_clip(view, clip);
    REQUIRE(!spans.empty());
    CHECK(spans.front().start_s == clip.times.front());
    CHECK(spans.back().end_s == clip.times.back());
    // The settled timeline follows the performance: spans, frame by frame, against the toy's truth.
    std::size_t frame = 0, right = 0;
    for (const LabelSpan& span : spans)
        for (std::size_t k = 0; k < span.frames && frame < frames.size(); ++k, ++frame)
            right += span.label == frames[frame].action;
    CHECK(frame == frames.size());
    CHECK(static_cast<double>(right) / static_cast<double>(frames.size()) > 0.8);
    std::size_t frames_covered = 0;
    for (std::size_t i = 0; i < spans.size(); ++i) {
        frames_covered += spans[i].frames;
        CHECK(spans[i].label < static_cast<int>(view.label_count));
        CHECK(spans[i].agreement >= 0.0);
        CHECK(spans[i].agreement <= 1.0);
        if (i > 0) {
            CHECK(spans[i].start_s == spans[i - 1].end_s);
            CHECK(spans[i].label != spans[i - 1].label);
        }
    }
    CHECK(frames_covered == clip.frame_count());
    CHECK(spans.size() >= 4);  // the four actions show up
}

TEST_CASE("frame F1, the trivial baseline and the event metrics on a timeline scored by hand") {
    // 20 frames at 1 s: no action, action 0 (frames 4-9), no action, action 1 (14-17), no action.
    std::vector<int> truth(20, unknown_frame);
    for (int f = 4; f < 10; ++f) truth[static_cast<std::size_t>(f)] = 0;
    for (int f = 14; f < 18; ++f) truth[static_cast<std::size_t>(f)] = 1;
    std::vector<int> predicted(20, unknown_frame);
    for (int f = 5; f < 10; ++f) predicted[static_cast<std::size_t>(f)] = 0;  // 5 of 6 frames of action 0
    predicted[12] = 1;                                                        // a false alarm
    std::vector<double> times;
    for (int f = 0; f < 20; ++f) times.push_back(f);
    const std::vector<std::size_t> starts{0, 20};
    host::OnlineResults r = host::score_timeline(truth, predicted, times, starts);
    CHECK(r.unknown_everywhere_accuracy == doctest::Approx(10.0 / 20.0));
    // Class 0: TP 5, FN 1, FP 0 → F1 10/11. Class 1: TP 0, FP 1, FN 4 → 0.
    CHECK(r.frame_f1 == doctest::Approx((10.0 / 11.0 + 0.0) / 2.0));

    // Events: action 0 reported at 5-9 (reported at 7 s), a false action 1 at 11-12, action 1 missed.
    auto event = [](ActionEvent::Kind kind, LabelId label, double start, double end, double reported) {
        ActionEvent e;
        e.kind = kind;
        e.label = label;
        e.start_time_us = static_cast<std::int64_t>(start * 1e6);
        e.end_time_us = static_cast<std::int64_t>(end * 1e6);
        return host::ReportedEvent{e, reported};
    };
    const std::vector<std::vector<host::ReportedEvent>> events{{
        event(ActionEvent::Kind::started, 0, 5, 6, 7),
        event(ActionEvent::Kind::ended, 0, 5, 9, 11),
        event(ActionEvent::Kind::started, 1, 11, 12, 13),
        event(ActionEvent::Kind::ended, 1, 11, 12, 14),
    }};
    host::score_events(r, truth, times, starts, events);
    CHECK(r.events == 2);
    CHECK(r.matched_events == 1);
    CHECK(r.event_precision == doctest::Approx(0.5));
    CHECK(r.event_recall == doctest::Approx(0.5));
    CHECK(r.detection_latency_s == doctest::Approx(3.0));  // true start 4 s, reported at 7 s
    CHECK(r.start_error_s == doctest::Approx(1.0));
    CHECK(r.end_error_s == doctest::Approx(0.0));
    CHECK(r.start_bias_s == doctest::Approx(1.0));  // one action, reported 1 s late
    CHECK(r.end_bias_s == doctest::Approx(0.0));
    // As segments: action 0's 5-9 s against the true 4-9 s is IoU 4 / 5; the false one overlaps nothing.
    CHECK(r.iou_matched_events == 1);
    CHECK(r.event_segment_f1 == doctest::Approx(2.0 * 1 / (2 + 2)));
    {
        // One action reported a second early, the other a second late: the
        // error is 1 s, the bias (what a constant offset would fix) none.
        host::OnlineResults both = r;
        const std::vector<std::vector<host::ReportedEvent>> early_and_late{{
            event(ActionEvent::Kind::started, 0, 3, 4, 6),
            event(ActionEvent::Kind::ended, 0, 3, 10, 12),
            event(ActionEvent::Kind::started, 1, 15, 16, 17),
            event(ActionEvent::Kind::ended, 1, 15, 16, 19),
        }};
        host::score_events(both, truth, times, starts, early_and_late);
        CHECK(both.matched_events == 2);
        // Both overlap their action, but only the first is a segment of it:
        // 3-10 s against 4-9 s is IoU 5 / 7, 15-16 s against 14-17 s only 1 / 3.
        CHECK(both.iou_matched_events == 1);
        CHECK(both.event_segment_f1 == doctest::Approx(0.5));
        CHECK(both.start_error_s == doctest::Approx(1.0));
        CHECK(both.start_bias_s == doctest::Approx(0.0));
        CHECK(both.end_error_s == doctest::Approx(1.0));  // 10 for 9, 16 for 17
        CHECK(both.end_bias_s == doctest::Approx(0.0));
    }
    // One false event in 9 s of no action (frame steps whose first frame is no action).
    CHECK_FALSE(r.false_events_per_stream_min);
    CHECK(r.false_events_per_min == doctest::Approx(60.0 / 9.0));

    // The intervals' units: the five true runs, each predicted run and reported
    // action with the run its middle falls in (scored again: the first
    // scoring's events are forgotten).
    host::score_events(r, truth, times, starts, events);
    REQUIRE(r.units.size() == 5);  // no action 0-3, action 0 4-9, no action 10-13, action 1 14-17, no action 18-19
    const std::size_t frames[] = {4, 6, 4, 4, 2}, right[] = {4, 5, 3, 0, 2};
    const std::size_t predicted_runs[] = {0, 1, 1, 0, 0};  // 5-9 in action 0; the false alarm at 12 in no action
    const std::size_t reported[] = {0, 1, 1, 0, 0};        // 5-9 s and 11-12 s, by their middles
    for (std::size_t u = 0; u < 5; ++u) {
        CAPTURE(u);
        CHECK(r.units[u].frames == frames[u]);
        CHECK(r.units[u].right == right[u]);
        CHECK(r.units[u].true_segments == (u % 2 == 1 ? 1u : 0u));
        CHECK(r.units[u].true_actions == (u % 2 == 1 ? 1u : 0u));
        CHECK(r.units[u].matched == (u == 1 ? 1u : 0u));
        CHECK(r.units[u].iou_matched_events == (u == 1 ? 1u : 0u));
        CHECK(r.units[u].predicted == predicted_runs[u]);
        CHECK(r.units[u].reported == reported[u]);
    }
    // Their sums are the figures: 14 of 20 frames; 2·1 / (2 predicted + 2 true).
    CHECK(r.frame_accuracy == doctest::Approx(14.0 / 20.0));
    CHECK(r.segment_f1 == doctest::Approx(2.0 / 4.0));
    host::add_intervals(r);
    CHECK(r.frame_accuracy_interval.low <= r.frame_accuracy);
    CHECK(r.frame_accuracy_interval.high >= r.frame_accuracy);
    CHECK(r.event_segment_f1_interval.low <= r.event_segment_f1_interval.high);
    // Paired with "unknown everywhere" (0.5 here): 0.2 better, within its interval.
    CHECK(r.gain_over_unknown_interval.low <= 0.2);
    CHECK(r.gain_over_unknown_interval.high >= 0.2);
    // Labels that are "unknown everywhere" gain exactly nothing on every resample,
    // though their own accuracy's interval is wide.
    host::OnlineResults silent = host::score_timeline(truth, std::vector<int>(20, unknown_frame), times, starts);
    host::add_intervals(silent);
    CHECK(silent.gain_over_unknown_interval.low == 0.0);
    CHECK(silent.gain_over_unknown_interval.high == 0.0);
    CHECK(silent.frame_accuracy_interval.high - silent.frame_accuracy_interval.low > 0.2);
}

TEST_CASE("the bootstrap interval of a ratio of sums") {
    // No items: nothing known.
    CHECK(host::bootstrap_ratio_interval({}, {}).low == 0.0);
    CHECK(host::bootstrap_ratio_interval({}, {}).high == 1.0);
    // Every item at one ratio: every resample has it.
    const host::Interval same = host::bootstrap_ratio_interval({1, 2, 3, 4}, {2, 4, 6, 8});
    CHECK(same.low == doctest::Approx(0.5));
    CHECK(same.high == doctest::Approx(0.5));
    // Two items, 1/1 and 0/1: resamples give 0, 1/2 and 1 a quarter, half and quarter of the time.
    const host::Interval two = host::bootstrap_ratio_interval({1, 0}, {1, 1});
    CHECK(two.low == 0.0);
    CHECK(two.high == 1.0);
    // Independent trials (80 of 100 right, one each): close to the Wilson interval (0.711-0.867).
    std::vector<double> successes(100, 0.0), trials(100, 1.0);
    for (std::size_t i = 0; i < 80; ++i) successes[i] = 1.0;
    const host::Interval wide = host::bootstrap_ratio_interval(successes, trials);
    const host::Interval wilson = host::wilson_interval(80, 100);
    CHECK(wide.low == doctest::Approx(wilson.low).epsilon(0.04));
    CHECK(wide.high == doctest::Approx(wilson.high).epsilon(0.04));
    // Deterministic: the same seed, the same interval.
    const host::Interval again = host::bootstrap_ratio_interval(successes, trials);
    CHECK(again.low == wide.low);
    CHECK(again.high == wide.high);
}
