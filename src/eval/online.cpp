// Online labelling of unsegmented streams, judged frame by frame.
#include "eval/online.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "common/time.hpp"
#include "model/model_data.hpp"
#include "io/stream.hpp"

namespace actionstring {
namespace host {
namespace {

struct Segment {
    int label;
    std::size_t begin, end;  // frames [begin, end)
};

std::vector<Segment> runs(const std::vector<int>& labels) {
    std::vector<Segment> out;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (out.empty() || out.back().label != labels[i]) out.push_back({labels[i], i, i + 1});
        else out.back().end = i + 1;
    }
    return out;
}

}  // namespace

std::size_t OnlineResults::confused(int row, int column) const {
    const std::size_t side = confusion_labels + 1;
    if (row < unknown_frame - 1 || column < unknown_frame || frame_confusion.size() != (side + 1) * side) return 0;
    // Rows: "no action", the labels, then the labels the model does not know (−2) last.
    const std::size_t r = row == unknown_frame - 1 ? side : static_cast<std::size_t>(row + 1);
    const std::size_t c = static_cast<std::size_t>(column + 1);
    if ((row != unknown_frame - 1 && r >= side) || c >= side) return 0;
    return frame_confusion[r * side + c];
}

std::string frame_class_name(int label, const std::vector<std::string>& labels) {
    if (label < 0) return "no action";
    return static_cast<std::size_t>(label) < labels.size() ? labels[static_cast<std::size_t>(label)]
                                                           : std::to_string(label);
}

std::vector<FrameClassScore> frame_class_scores(const OnlineResults& r) {
    std::vector<FrameClassScore> out;
    const int labels = static_cast<int>(r.confusion_labels);
    for (int row = unknown_frame; row < labels; ++row) {
        FrameClassScore c;
        c.label = row;
        c.labelled = r.confused(unknown_frame - 1, row);  // frames of labels the model does not know
        for (int column = unknown_frame; column < labels; ++column) {
            const std::size_t n = r.confused(row, column);
            c.frames += n;
            c.labelled += r.confused(column, row);
            if (column == row) c.right = n;
            else if (n > c.most_taken_for_frames) c.most_taken_for = column, c.most_taken_for_frames = n;
        }
        if (c.frames == 0) continue;
        c.recall = static_cast<double>(c.right) / static_cast<double>(c.frames);
        c.precision = c.labelled > 0 ? static_cast<double>(c.right) / static_cast<double>(c.labelled) : 0.0;
        c.f1 = c.frames + c.labelled > 0
                   ? 2.0 * static_cast<double>(c.right) / static_cast<double>(c.frames + c.labelled)
                   : 0.0;
        out.push_back(c);
    }
    return out;
}

OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted,
                             const std::vector<double>& times, const std::vector<std::size_t>& stream_starts,
                             const std::vector<double>* emitted) {
    OnlineResults r;
    r.frames = truth.size();
    if (r.frames == 0) return r;
    std::size_t right = 0;
    std::size_t no_action = 0, no_action_right = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        right += truth[i] == predicted[i];
        no_action += truth[i] == unknown_frame;
        no_action_right += truth[i] == unknown_frame && predicted[i] == unknown_frame;
    }
    r.frame_accuracy = static_cast<double>(right) / static_cast<double>(r.frames);
    r.no_action_frames = no_action;
    if (no_action < r.frames)
        r.action_frame_accuracy =
            static_cast<double>(right - no_action_right) / static_cast<double>(r.frames - no_action);
    if (no_action > 0) r.no_action_accuracy = static_cast<double>(no_action_right) / static_cast<double>(no_action);
    int highest = -1;
    for (std::size_t i = 0; i < truth.size(); ++i) highest = std::max({highest, truth[i], predicted[i]});
    r.confusion_labels = static_cast<std::size_t>(highest + 1);
    const std::size_t side = r.confusion_labels + 1;
    r.frame_confusion.assign((side + 1) * side, 0);
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (predicted[i] < unknown_frame) continue;  // never: a prediction is unknown or a model label
        const std::size_t row = truth[i] >= unknown_frame ? static_cast<std::size_t>(truth[i] + 1) : side;
        ++r.frame_confusion[row * side + static_cast<std::size_t>(predicted[i] + 1)];
    }

    // Segments and label changes, per stream so boundaries between subjects do not count.
    int true_segments = 0, predicted_segments = 0, matched = 0, found = 0;
    double delay_sum = 0, minutes = 0;
    int predicted_changes = 0, true_changes = 0;
    for (std::size_t s = 0; s + 1 < stream_starts.size(); ++s) {
        const std::size_t begin = stream_starts[s], end = stream_starts[s + 1];
        if (end <= begin) continue;
        const std::vector<int> t(truth.begin() + static_cast<long>(begin), truth.begin() + static_cast<long>(end));
        const std::vector<int> p(predicted.begin() + static_cast<long>(begin),
                                 predicted.begin() + static_cast<long>(end));
        const auto true_runs = runs(t), predicted_runs = runs(p);
        minutes += (times[end - 1] - times[begin]) / 60.0;
        true_changes += static_cast<int>(true_runs.size()) - 1;
        predicted_changes += static_cast<int>(predicted_runs.size()) - 1;
        std::vector<bool> used(predicted_runs.size(), false);
        for (const Segment& segment : predicted_runs) predicted_segments += segment.label >= 0;
        // The stream's units: its true runs, each predicted action run with the one its middle falls in.
        const std::size_t first_unit = r.units.size();
        for (const Segment& segment : true_runs) {
            OnlineResults::Unit unit;
            unit.frames = segment.end - segment.begin;
            for (std::size_t i = segment.begin; i < segment.end; ++i) unit.right += p[i] == segment.label;
            unit.true_segments = segment.label != unknown_frame;
            r.units.push_back(unit);
        }
        for (const Segment& guess : predicted_runs) {
            if (guess.label < 0) continue;
            const std::size_t middle = guess.begin + (guess.end - guess.begin - 1) / 2;
            const auto holder = std::upper_bound(true_runs.begin(), true_runs.end(), middle,
                                                 [](std::size_t i, const Segment& run) { return i < run.begin; });
            ++r.units[first_unit + static_cast<std::size_t>(holder - true_runs.begin()) - 1].predicted;
        }
        for (std::size_t u = 0; u < true_runs.size(); ++u) {
            const Segment& segment = true_runs[u];
            if (segment.label == unknown_frame) continue;  // "no action": judged frame by frame only
            ++true_segments;
            for (std::size_t q = 0; q < predicted_runs.size(); ++q) {
                const Segment& guess = predicted_runs[q];
                if (used[q] || guess.label != segment.label) continue;
                const std::size_t overlap_begin = std::max(segment.begin, guess.begin),
                                  overlap_end = std::min(segment.end, guess.end);
                if (overlap_end <= overlap_begin) continue;
                const double overlap = static_cast<double>(overlap_end - overlap_begin);
                const double joined =
                    static_cast<double>(std::max(segment.end, guess.end) - std::min(segment.begin, guess.begin));
                if (overlap / joined >= 0.5) {
                    used[q] = true;
                    ++matched;
                    r.units[first_unit + u].matched = 1;
                    break;
                }
            }
            std::size_t first = segment.end;
            for (std::size_t i = segment.begin; i < segment.end; ++i)
                if (p[i] == segment.label) {
                    first = i;
                    break;
                }
            if (first < segment.end) {
                const double shown = emitted ? (*emitted)[begin + first] : times[begin + first];
                delay_sum += shown - times[begin + segment.begin];
                ++found;
            } else {
                ++r.missed_segments;
            }
        }
    }
    r.segment_precision = predicted_segments > 0 ? static_cast<double>(matched) / predicted_segments : 0.0;
    r.segment_recall = true_segments > 0 ? static_cast<double>(matched) / true_segments : 0.0;
    r.segment_f1 = r.segment_precision + r.segment_recall > 0
                       ? 2 * r.segment_precision * r.segment_recall / (r.segment_precision + r.segment_recall)
                       : 0.0;
    r.mean_delay_s = found > 0 ? delay_sum / found : 0.0;
    if (emitted != nullptr && !times.empty()) {
        std::vector<double> after(times.size());
        for (std::size_t i = 0; i < times.size(); ++i) after[i] = std::max(0.0, (*emitted)[i] - times[i]);
        std::sort(after.begin(), after.end());
        // Nearest rank: the smallest value at least the share of the frames lies at or below.
        const auto rank = [&after](double share) {
            const std::size_t k = static_cast<std::size_t>(std::ceil(share * static_cast<double>(after.size())));
            return after[k == 0 ? 0 : k - 1];
        };
        r.final_after_median_s = rank(0.5);
        r.final_after_p95_s = rank(0.95);
    }
    r.unknown_everywhere_accuracy = static_cast<double>(no_action) / static_cast<double>(r.frames);
    // Frame F1 per action class present in the truth, then their mean.
    std::map<int, std::array<std::size_t, 3>> counts;  // label → true positives, false positives, false negatives
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (truth[i] >= 0) counts[truth[i]];
    }
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (truth[i] >= 0 && predicted[i] == truth[i]) ++counts[truth[i]][0];
        else {
            if (predicted[i] >= 0 && counts.count(predicted[i]) > 0) ++counts[predicted[i]][1];
            if (truth[i] >= 0) ++counts[truth[i]][2];
        }
    }
    double f1_sum = 0;
    for (const auto& [label, c] : counts) {
        const double denominator = static_cast<double>(2 * c[0] + c[1] + c[2]);
        f1_sum += denominator > 0 ? 2.0 * static_cast<double>(c[0]) / denominator : 0.0;
    }
    r.frame_f1 = counts.empty() ? 0.0 : f1_sum / static_cast<double>(counts.size());
    if (minutes > 0) {
        r.label_changes_per_min = predicted_changes / minutes;
        r.true_changes_per_min = true_changes / minutes;
        r.flicker_per_min = std::max(0.0, r.label_changes_per_min - r.true_changes_per_min);
    }
    return r;
}

void score_events(OnlineResults& r, const std::vector<int>& truth, const std::vector<double>& times,
                  const std::vector<std::size_t>& stream_starts,
                  const std::vector<std::vector<ReportedEvent>>& stream_events) {
    r.has_events = true;
    for (OnlineResults::Unit& unit : r.units) unit.true_actions = unit.iou_matched_events = unit.reported = 0;
    struct Action {
        int label;
        double start_s, end_s, reported_s;
        bool used = false;   // matched to a true action it overlaps
        bool taken = false;  // matched to a true action as a segment of it (IoU ≥ 0.5)
    };
    std::size_t true_actions = 0, matched = 0, reported = 0, iou_matched = 0;
    std::size_t unit = 0;  // the first of this stream's units
    double latency = 0, start_error = 0, end_error = 0, start_bias = 0, end_bias = 0, no_action_s = 0, stream_s = 0;
    for (std::size_t s = 0; s + 1 < stream_starts.size() && s < stream_events.size(); ++s) {
        const std::size_t begin = stream_starts[s], end = stream_starts[s + 1];
        if (end <= begin) continue;
        // Reported actions: each started event with the end its ended event gives.
        std::vector<Action> actions;
        for (const ReportedEvent& e : stream_events[s]) {
            const double start = us_to_seconds(e.event.start_time_us), stop = us_to_seconds(e.event.end_time_us);
            if (e.event.kind == ActionEvent::Kind::started) {
                actions.push_back({static_cast<int>(e.event.label), start, stop, e.reported_s});
            } else {
                for (auto a = actions.rbegin(); a != actions.rend(); ++a)
                    if (a->label == static_cast<int>(e.event.label) && a->start_s == start) {
                        a->end_s = stop;
                        break;
                    }
            }
        }
        reported += actions.size();
        // This stream's units (score_timeline()'s true runs, in the same order).
        std::vector<std::size_t> run_begins;
        for (std::size_t i = begin; i < end; ++i)
            if (i == begin || truth[i] != truth[i - 1]) run_begins.push_back(i);
        const bool units = unit + run_begins.size() <= r.units.size();
        if (units)
            for (const Action& a : actions) {
                const double middle = 0.5 * (a.start_s + a.end_s);
                std::size_t k = 0;
                while (k + 1 < run_begins.size() && times[run_begins[k + 1]] <= middle) ++k;
                ++r.units[unit + k].reported;
            }
        for (std::size_t i = begin; i + 1 < end; ++i) {
            const double step = times[i + 1] - times[i];
            stream_s += step;
            if (truth[i] == unknown_frame) no_action_s += step;
        }
        // True actions: runs of one label.
        for (std::size_t i = begin; i < end;) {
            std::size_t j = i;
            while (j < end && truth[j] == truth[i]) ++j;
            OnlineResults::Unit* const held = units ? &r.units[unit++] : nullptr;
            if (truth[i] >= 0) {
                ++true_actions;
                if (held != nullptr) held->true_actions = 1;
                const double t_begin = times[i], t_end = times[j - 1];
                for (Action& a : actions) {
                    if (a.used || a.label != truth[i] || a.start_s > t_end || a.end_s < t_begin) continue;
                    a.used = true;
                    ++matched;
                    latency += a.reported_s - t_begin;
                    start_error += std::fabs(a.start_s - t_begin);
                    end_error += std::fabs(a.end_s - t_end);
                    start_bias += a.start_s - t_begin;
                    end_bias += a.end_s - t_end;
                    break;
                }
                // Judged as a segment: one-to-one, at temporal IoU ≥ 0.5 (segment_f1's rule).
                for (Action& a : actions) {
                    if (a.taken || a.label != truth[i]) continue;
                    const double overlap = std::min(t_end, a.end_s) - std::max(t_begin, a.start_s);
                    const double joined = std::max(t_end, a.end_s) - std::min(t_begin, a.start_s);
                    if (overlap > 0 && overlap / joined >= 0.5) {
                        a.taken = true;
                        ++iou_matched;
                        if (held != nullptr) held->iou_matched_events = 1;
                        break;
                    }
                }
            }
            i = j;
        }
    }
    r.events = reported;
    r.matched_events = matched;
    r.event_precision = reported > 0 ? static_cast<double>(matched) / static_cast<double>(reported) : 0.0;
    r.event_recall = true_actions > 0 ? static_cast<double>(matched) / static_cast<double>(true_actions) : 0.0;
    r.event_f1 = r.event_precision + r.event_recall > 0
                     ? 2 * r.event_precision * r.event_recall / (r.event_precision + r.event_recall)
                     : 0.0;
    r.iou_matched_events = iou_matched;
    // F1 = 2·matched / (reported + true), the same as 2PR / (P + R).
    r.event_segment_f1 = reported + true_actions > 0
                             ? 2.0 * static_cast<double>(iou_matched) / static_cast<double>(reported + true_actions)
                             : 0.0;
    if (matched > 0) {
        r.detection_latency_s = latency / static_cast<double>(matched);
        r.start_error_s = start_error / static_cast<double>(matched);
        r.end_error_s = end_error / static_cast<double>(matched);
        r.start_bias_s = start_bias / static_cast<double>(matched);
        r.end_bias_s = end_bias / static_cast<double>(matched);
    }
    const std::size_t false_events = reported - matched;
    r.false_events_per_stream_min = no_action_s <= 0.0;
    const double minutes = (r.false_events_per_stream_min ? stream_s : no_action_s) / 60.0;
    r.false_events_per_min = minutes > 0 ? static_cast<double>(false_events) / minutes : 0.0;
}

void add_intervals(OnlineResults& r) {
    const std::size_t n = r.units.size();
    std::vector<double> right(n), gain(n), frames(n), matched(n), segments(n), events_matched(n), events(n);
    for (std::size_t u = 0; u < n; ++u) {
        const OnlineResults::Unit& unit = r.units[u];
        right[u] = static_cast<double>(unit.right);
        // "Unknown everywhere" gets every frame of a stretch of no action right, and nothing else.
        gain[u] = right[u] - (unit.true_segments == 0 ? static_cast<double>(unit.frames) : 0.0);
        frames[u] = static_cast<double>(unit.frames);
        // F1 = 2·matched / (predicted + true): a ratio of sums like accuracy.
        matched[u] = 2.0 * static_cast<double>(unit.matched);
        segments[u] = static_cast<double>(unit.predicted + unit.true_segments);
        events_matched[u] = 2.0 * static_cast<double>(unit.iou_matched_events);
        events[u] = static_cast<double>(unit.reported + unit.true_actions);
    }
    r.frame_accuracy_interval = bootstrap_ratio_interval(right, frames);
    r.gain_over_unknown_interval = bootstrap_ratio_interval(gain, frames);
    r.segment_f1_interval = bootstrap_ratio_interval(matched, segments);
    if (r.has_events) r.event_segment_f1_interval = bootstrap_ratio_interval(events_matched, events);
}

namespace {

// Appends one stream's timeline to the pooled per-frame vectors.
struct PooledTimelines {
    std::vector<int> truth, window, live, settled;
    std::vector<double> times, settled_at;
    std::vector<std::size_t> stream_starts;
    std::vector<std::vector<ReportedEvent>> events;

    void add(const StreamTimeline& timeline) {
        stream_starts.push_back(truth.size());
        truth.insert(truth.end(), timeline.truth.begin(), timeline.truth.end());
        times.insert(times.end(), timeline.times_s.begin(), timeline.times_s.end());
        window.insert(window.end(), timeline.labels.window.begin(), timeline.labels.window.end());
        live.insert(live.end(), timeline.labels.live.begin(), timeline.labels.live.end());
        settled.insert(settled.end(), timeline.labels.settled.begin(), timeline.labels.settled.end());
        settled_at.insert(settled_at.end(), timeline.labels.settled_at_s.begin(), timeline.labels.settled_at_s.end());
        events.push_back(timeline.labels.events);
    }
    void score(OnlineReport& report) {
        stream_starts.push_back(truth.size());
        report.settled = score_timeline(truth, settled, times, stream_starts, &settled_at);
        score_events(report.settled, truth, times, stream_starts, events);
        report.live = score_timeline(truth, live, times, stream_starts);
        report.window = score_timeline(truth, window, times, stream_starts);
        for (OnlineResults* results : {&report.settled, &report.live, &report.window}) add_intervals(*results);
        report.per_stream.clear();
        for (std::size_t s = 0; s + 1 < stream_starts.size(); ++s) {
            const auto begin = static_cast<std::ptrdiff_t>(stream_starts[s]),
                       end = static_cast<std::ptrdiff_t>(stream_starts[s + 1]);
            auto slice = [&](const auto& v) { return std::vector(v.begin() + begin, v.begin() + end); };
            const std::vector<int> stream_truth = slice(truth);
            const std::vector<double> stream_times = slice(times), stream_settled_at = slice(settled_at);
            const std::vector<std::size_t> starts{0, stream_truth.size()};
            OnlineResults one = score_timeline(stream_truth, slice(settled), stream_times, starts, &stream_settled_at);
            score_events(one, stream_truth, stream_times, starts, {events[s]});
            report.per_stream.push_back(std::move(one));
        }
    }
};

int model_label(const std::vector<std::string>& names, const std::string& label) {
    const auto found = std::find(names.begin(), names.end(), label);
    return found == names.end() ? foreign_label : static_cast<int>(found - names.begin());
}

}  // namespace

OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed,
                             const AnnotatorConfig& config, bool paper_rule) {
    const std::vector<std::string> names = name_strings(model.label_names, model.label_count);
    std::map<std::string, std::vector<std::size_t>> by_subject;
    for (std::size_t c = 0; c < clips.size(); ++c) by_subject[clips[c].subject].push_back(c);
    std::mt19937 rng(seed);

    OnlineReport report;
    PooledTimelines pooled;
    for (auto& subject : by_subject) {
        std::vector<std::size_t>& order = subject.second;
        std::shuffle(order.begin(), order.end(), rng);
        std::vector<StreamSegment> segments;
        for (const std::size_t c : order) segments.push_back({&clips[c].clip, clips[c].label, 0.0});
        ConcatenatedStream stream = concatenate_stream(segments);
        StreamTimeline timeline;
        timeline.name = "subject " + subject.first;
        for (std::size_t f = 0; f < stream.frame_count(); ++f)
            timeline.times_s.push_back(us_to_seconds(stream.times_us[f]));
        timeline.truth.assign(stream.frame_count(), unknown_frame);
        for (std::size_t s = 0; s < stream.segment_labels.size(); ++s) {
            const int label = model_label(names, stream.segment_labels[s]);
            const std::size_t end =
                s + 1 < stream.segment_first_frame.size() ? stream.segment_first_frame[s + 1] : stream.frame_count();
            for (std::size_t f = stream.segment_first_frame[s]; f < end; ++f) timeline.truth[f] = label;
        }
        timeline.labels =
            label_stream(model, config, timeline.times_s, stream.positions.data(), stream.joints, paper_rule);
        timeline.joints = stream.joints;
        timeline.positions = std::move(stream.positions);
        timeline.parents = clips[order.front()].clip.parents;
        timeline.up_axis = clips[order.front()].clip.up_axis;
        pooled.add(timeline);
        report.streams.push_back(std::move(timeline));
    }
    pooled.score(report);
    return report;
}

StreamTimeline stream_recording(const ModelView& model, const Clip& clip,
                                const std::vector<LabelledRecording::Interval>* intervals,
                                const AnnotatorConfig& config, bool paper_rule) {
    StreamTimeline timeline;
    const std::size_t slash = clip.source.find_last_of('/');
    timeline.name = clip.source.substr(slash == std::string::npos ? 0 : slash + 1);
    timeline.times_s = clip.times;
    if (intervals != nullptr) {
        const std::vector<std::string> names = name_strings(model.label_names, model.label_count);
        timeline.truth.assign(clip.frame_count(), unknown_frame);
        std::vector<int> labels;
        for (const auto& interval : *intervals) labels.push_back(model_label(names, interval.label));
        // Where intervals overlap, the one that starts last (interval_at()).
        for (std::size_t f = 0; f < clip.frame_count(); ++f) {
            const int i = interval_at(*intervals, clip.times[f]);
            if (i >= 0) timeline.truth[f] = labels[static_cast<std::size_t>(i)];
        }
    }
    timeline.labels = label_stream(model, config, clip.times, clip.positions.data(), clip.joint_count(), paper_rule);
    timeline.joints = clip.joint_count();
    timeline.positions = clip.positions;
    timeline.parents = clip.parents;
    timeline.up_axis = clip.up_axis;
    return timeline;
}

OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings,
                                 const AnnotatorConfig& config, bool paper_rule) {
    OnlineReport report;
    report.recordings = true;
    PooledTimelines pooled;
    for (const LabelledRecording& recording : recordings) {
        StreamTimeline timeline = stream_recording(model, recording.clip, &recording.intervals, config, paper_rule);
        pooled.add(timeline);
        report.streams.push_back(std::move(timeline));
    }
    pooled.score(report);
    return report;
}

OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed) {
    return evaluate_online(model, clips, seed, annotator_config(model));
}

OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings) {
    return evaluate_recordings(model, recordings, annotator_config(model));
}

}  // namespace host
}  // namespace actionstring
