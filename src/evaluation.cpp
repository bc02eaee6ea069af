// Clip-recognition evaluation and baselines.
#include "actionstring_host/evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <sstream>

#include "actionstring/annotator.hpp"
#include "actionstring_host/artifact.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/projection.hpp"
#include "actionstring/tree.hpp"
#include "actionstring_host/clustering.hpp"
#include "actionstring/sampler.hpp"
#include "actionstring/string_distance.hpp"

namespace actionstring {
namespace host {
namespace {

ClipResults start(const std::string& method, const std::vector<std::string>& model_labels, const std::vector<LabelledClip>& clips) {
    ClipResults r;
    r.method = method;
    r.labels = model_labels;
    for (const LabelledClip& c : clips)
        if (std::find(r.labels.begin(), r.labels.end(), c.label) == r.labels.end()) r.labels.push_back(c.label);
    return r;
}

int index_of(const std::vector<std::string>& labels, const std::string& label) {
    return static_cast<int>(std::find(labels.begin(), labels.end(), label) - labels.begin());
}

}  // namespace

std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        if (ch == '"' || ch == '\\') out += '\\';
        if (static_cast<unsigned char>(ch) < 0x20) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\u%04x", ch);
            out += buffer;
            continue;
        }
        out += ch;
    }
    return out + "\"";
}

namespace {

// Normalised poses of a clip at a fixed rate (the runtime's sampler picks the frames).
std::vector<std::vector<float>> pose_sequence(const ModelView& model, const Clip& clip, double rate_hz) {
    StringSampler sampler;
    sampler.configure(static_cast<std::uint32_t>(std::lround(1e6 / rate_hz)), std::int64_t{1} << 62);
    std::vector<std::vector<float>> out;
    std::vector<float> previous(model.pose_dim()), current(model.pose_dim());
    bool has_previous = false;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (normalize_pose(model, clip.frame(f), current.data()) != Status::ok) continue;
        const SamplePlan plan = sampler.advance(static_cast<std::int64_t>(std::llround(clip.times[f] * 1e6)));
        if (plan.status == Status::time_went_backwards) continue;
        for (std::uint32_t i = 0; i < plan.from_previous && has_previous; ++i) out.push_back(previous);
        for (std::uint32_t i = 0; i < plan.from_current; ++i) out.push_back(current);
        std::swap(previous, current);
        has_previous = true;
    }
    return out;
}

double pose_dtw(const std::vector<std::vector<float>>& a, const std::vector<std::vector<float>>& b, double cutoff) {
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> previous(b.size() + 1, inf), current(b.size() + 1, inf);
    previous[0] = 0;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = inf;
        double row_best = inf;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            double sum = 0;
            const auto& p = a[i - 1];
            const auto& q = b[j - 1];
            for (std::size_t k = 0; k < p.size(); ++k) {
                const double d = static_cast<double>(p[k]) - static_cast<double>(q[k]);
                sum += d * d;
            }
            current[j] = std::sqrt(sum) + std::min({previous[j - 1], previous[j], current[j - 1]});
            row_best = std::min(row_best, current[j]);
        }
        if (row_best > cutoff) return inf;  // every path already costs more than the best match so far
        std::swap(previous, current);
    }
    return previous[b.size()];
}

}  // namespace

void summarise(ClipResults& r, const std::vector<LabelledClip>& clips) {
    const std::size_t L = r.labels.size();
    r.confusion.assign(L, std::vector<int>(L + 1, 0));
    int right = 0, unknown = 0;
    for (std::size_t c = 0; c < clips.size(); ++c) {
        const int truth = index_of(r.labels, clips[c].label);
        const int predicted = r.predictions[c];
        ++r.confusion[static_cast<std::size_t>(truth)][predicted < 0 ? L : static_cast<std::size_t>(predicted)];
        right += predicted == truth;
        unknown += predicted < 0;
    }
    const double n = clips.empty() ? 1.0 : static_cast<double>(clips.size());
    r.clip_accuracy = right / n;
    r.unknown_rate = unknown / n;
    r.precision.assign(L, 0.0);
    r.recall.assign(L, 0.0);
    for (std::size_t l = 0; l < L; ++l) {
        int predicted_as = 0, support = 0;
        for (std::size_t t = 0; t < L; ++t) predicted_as += r.confusion[t][l];
        for (std::size_t p = 0; p <= L; ++p) support += r.confusion[l][p];
        if (predicted_as > 0) r.precision[l] = static_cast<double>(r.confusion[l][l]) / predicted_as;
        if (support > 0) r.recall[l] = static_cast<double>(r.confusion[l][l]) / support;
    }
}

ClipResults evaluate_model(const ModelView& model, const std::vector<LabelledClip>& clips) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
    ClipResults r = start("action strings (representatives, kNN)", names, clips);
    for (const LabelledClip& c : clips) {
        const Classification k = classify_string(model, clip_string(model, c.clip));
        r.predictions.push_back(k.label == unknown_label ? -1 : static_cast<int>(k.label));
    }
    summarise(r, clips);
    return r;
}

ClipResults evaluate_all_strings(const ModelView& model, const std::vector<LabelledClip>& train, const std::vector<LabelledClip>& clips) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
    ClipResults r = start("1-NN over all training strings", names, clips);
    std::vector<std::vector<Character>> references;
    for (const LabelledClip& t : train) references.push_back(clip_string(model, t.clip));
    std::vector<detail::Cell> workspace;
    for (const LabelledClip& c : clips) {
        const std::vector<Character> query = clip_string(model, c.clip);
        float best = detail::infinity();
        int label = -1;
        for (std::size_t t = 0; t < train.size(); ++t) {
            if (query.empty() || references[t].empty()) continue;
            workspace.resize(string_distance_cells(query.size(), references[t].size()));
            float d = 0;
            string_distance(query.data(), query.size(), references[t].data(), references[t].size(), character_weights(model),
                            MatchOptions{model.variant, model.normalization}, workspace.data(), &d);
            if (d < best) best = d, label = index_of(r.labels, train[t].label);
        }
        r.predictions.push_back(label);
    }
    summarise(r, clips);
    return r;
}

ClipResults evaluate_pca_characters(const ModelView& model, const std::vector<LabelledClip>& train,
                                   const std::vector<LabelledClip>& clips, std::uint32_t seed) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
    ClipResults r = start("1-NN, PCA-only characters (no GMM)", names, clips);
    const std::size_t d = model.feature_dim;
    const double rate_hz = 1e6 / static_cast<double>(model.string_period_us);
    // Features: the runtime's normalisation and projection at the string rate.
    auto features_of = [&](const Clip& clip) {
        std::vector<float> out;
        std::vector<float> feature(d);
        for (const std::vector<float>& pose : pose_sequence(model, clip, rate_hz)) {
            project_pose(model, pose.data(), feature.data());
            out.insert(out.end(), feature.begin(), feature.end());
        }
        return out;
    };
    std::vector<std::vector<float>> train_features;
    std::vector<float> pooled;
    for (const LabelledClip& t : train) {
        train_features.push_back(features_of(t.clip));
        pooled.insert(pooled.end(), train_features.back().begin(), train_features.back().end());
    }
    if (pooled.empty()) throw std::invalid_argument("PCA-only baseline: no usable training frames");
    // The same top-down 2-means tree with as many leaves as the model has
    // characters, built on projected poses instead of GMM posteriors; ε is
    // tiny so the leaf count, not the diameter, ends the splitting.
    const ClusterTree tree = build_cluster_tree(pooled, d, 1e-9, model.character_count, seed);
    const std::size_t K = static_cast<std::size_t>(tree.character_count);
    std::vector<const float*> leaf(K, nullptr);
    for (std::size_t n = 0; n < tree.characters.size(); ++n)
        if (tree.children[2 * n] < 0) leaf[tree.characters[n]] = &tree.centroids[n * d];
    std::vector<float> distances(K * K, 0.0f);
    for (std::size_t a = 0; a < K; ++a)
        for (std::size_t b = 0; b < K; ++b) {
            double sum = 0;
            for (std::size_t k = 0; k < d; ++k) sum += std::pow(double(leaf[a][k]) - double(leaf[b][k]), 2.0);
            distances[a * K + b] = static_cast<float>(std::sqrt(sum));
        }
    // The runtime's descent over this tree: a view whose "components" are the projected coordinates.
    ModelView pca_view = model;
    pca_view.component_count = static_cast<std::uint16_t>(d);
    pca_view.node_count = static_cast<std::uint16_t>(tree.characters.size());
    pca_view.node_centroids = tree.centroids.data();
    pca_view.node_children = tree.children.data();
    pca_view.node_characters = tree.characters.data();
    const CharacterWeights weights{distances.data(), K};
    auto string_of = [&](const std::vector<float>& features) {
        std::vector<Character> string;
        for (std::size_t i = 0; i + d <= features.size(); i += d) string.push_back(descend_tree(pca_view, features.data() + i));
        return string;
    };
    std::vector<std::vector<Character>> references;
    for (const auto& f : train_features) references.push_back(string_of(f));
    std::vector<detail::Cell> workspace;
    for (const LabelledClip& c : clips) {
        const std::vector<Character> query = string_of(features_of(c.clip));
        float best = detail::infinity();
        int label = -1;
        for (std::size_t t = 0; t < train.size(); ++t) {
            if (query.empty() || references[t].empty()) continue;
            workspace.resize(string_distance_cells(query.size(), references[t].size()));
            float distance = 0;
            if (string_distance(query.data(), query.size(), references[t].data(), references[t].size(), weights,
                                MatchOptions{model.variant, model.normalization}, workspace.data(), &distance) != Status::ok)
                continue;
            if (distance < best) best = distance, label = index_of(r.labels, train[t].label);
        }
        r.predictions.push_back(label);
    }
    summarise(r, clips);
    return r;
}

ClipResults evaluate_pose_dtw(const ModelView& model, const std::vector<LabelledClip>& train, const std::vector<LabelledClip>& clips,
                              double rate_hz) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
    ClipResults r = start("DTW 1-NN on normalised poses", names, clips);
    std::vector<std::vector<std::vector<float>>> references;
    for (const LabelledClip& t : train) references.push_back(pose_sequence(model, t.clip, rate_hz));
    for (const LabelledClip& c : clips) {
        const auto query = pose_sequence(model, c.clip, rate_hz);
        double best = std::numeric_limits<double>::infinity();
        int label = -1;
        for (std::size_t t = 0; t < train.size(); ++t) {
            const double d = pose_dtw(query, references[t], best);
            if (d < best) best = d, label = index_of(r.labels, train[t].label);
        }
        r.predictions.push_back(label);
    }
    summarise(r, clips);
    return r;
}

std::vector<double> annotator_frame_times(const ModelView& model, const std::vector<LabelledClip>& clips) {
    auto annotator = std::make_unique<Annotator<HostCapacity>>();
    std::vector<double> times;
    if (annotator->init(model) != Status::ok) return times;
    std::int64_t offset = 0;
    for (const LabelledClip& c : clips) {
        for (std::size_t f = 0; f < c.clip.frame_count(); ++f) {
            const std::int64_t t = offset + static_cast<std::int64_t>(std::llround(c.clip.times[f] * 1e6));
            const auto begin = std::chrono::steady_clock::now();
            annotator->push_frame(t, c.clip.frame(f));
            times.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - begin).count());
        }
        offset += static_cast<std::int64_t>(std::llround(c.clip.duration() * 1e6)) + 1;
    }
    std::sort(times.begin(), times.end());
    return times;
}

std::string to_json(const ClipResults& r, const std::vector<LabelledClip>& clips) {
    std::ostringstream out;
    out.precision(6);
    out << "{\"method\": " << json_string(r.method) << ", \"clips\": " << clips.size() << ", \"clip_accuracy\": " << r.clip_accuracy
        << ", \"unknown_rate\": " << r.unknown_rate << ", \"labels\": [";
    for (std::size_t l = 0; l < r.labels.size(); ++l) out << (l ? ", " : "") << json_string(r.labels[l]);
    out << "], \"confusion\": [";
    for (std::size_t t = 0; t < r.confusion.size(); ++t) {
        out << (t ? ", " : "") << "[";
        for (std::size_t p = 0; p < r.confusion[t].size(); ++p) out << (p ? ", " : "") << r.confusion[t][p];
        out << "]";
    }
    out << "], \"per_class\": {";
    for (std::size_t l = 0; l < r.labels.size(); ++l) {
        int support = 0;
        for (int v : r.confusion[l]) support += v;
        out << (l ? ", " : "") << json_string(r.labels[l]) << ": {\"precision\": " << r.precision[l] << ", \"recall\": " << r.recall[l]
            << ", \"support\": " << support << "}";
    }
    out << "}}";
    return out.str();
}

}  // namespace host
}  // namespace actionstring

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

OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted, const std::vector<double>& times,
                             const std::vector<std::size_t>& stream_starts, const std::vector<double>* emitted) {
    OnlineResults r;
    r.frames = truth.size();
    if (r.frames == 0) return r;
    std::size_t right = 0;
    std::size_t no_action = 0, no_action_right = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        right += truth[i] == predicted[i];
        no_action += truth[i] == -1;
        no_action_right += truth[i] == -1 && predicted[i] == -1;
    }
    r.frame_accuracy = static_cast<double>(right) / static_cast<double>(r.frames);
    r.no_action_frames = no_action;
    if (no_action < r.frames)
        r.action_frame_accuracy = static_cast<double>(right - no_action_right) / static_cast<double>(r.frames - no_action);
    if (no_action > 0) r.no_action_accuracy = static_cast<double>(no_action_right) / static_cast<double>(no_action);

    // Segments and label changes, per stream so boundaries between subjects do not count.
    int true_segments = 0, predicted_segments = 0, matched = 0, found = 0;
    double delay_sum = 0, minutes = 0;
    int predicted_changes = 0, true_changes = 0;
    for (std::size_t s = 0; s + 1 < stream_starts.size(); ++s) {
        const std::size_t begin = stream_starts[s], end = stream_starts[s + 1];
        if (end <= begin) continue;
        const std::vector<int> t(truth.begin() + static_cast<long>(begin), truth.begin() + static_cast<long>(end));
        const std::vector<int> p(predicted.begin() + static_cast<long>(begin), predicted.begin() + static_cast<long>(end));
        const auto true_runs = runs(t), predicted_runs = runs(p);
        minutes += (times[end - 1] - times[begin]) / 60.0;
        true_changes += static_cast<int>(true_runs.size()) - 1;
        predicted_changes += static_cast<int>(predicted_runs.size()) - 1;
        std::vector<bool> used(predicted_runs.size(), false);
        for (const Segment& segment : predicted_runs) predicted_segments += segment.label >= 0;
        for (const Segment& segment : true_runs) {
            if (segment.label == -1) continue;  // "no action": judged frame by frame only
            ++true_segments;
            for (std::size_t q = 0; q < predicted_runs.size(); ++q) {
                const Segment& guess = predicted_runs[q];
                if (used[q] || guess.label != segment.label) continue;
                const std::size_t overlap_begin = std::max(segment.begin, guess.begin), overlap_end = std::min(segment.end, guess.end);
                if (overlap_end <= overlap_begin) continue;
                const double overlap = static_cast<double>(overlap_end - overlap_begin);
                const double joined = static_cast<double>(std::max(segment.end, guess.end) - std::min(segment.begin, guess.begin));
                if (overlap / joined >= 0.5) {
                    used[q] = true;
                    ++matched;
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
    if (minutes > 0) {
        r.label_changes_per_min = predicted_changes / minutes;
        r.true_changes_per_min = true_changes / minutes;
        r.flicker_per_min = std::max(0.0, r.label_changes_per_min - r.true_changes_per_min);
    }
    return r;
}

StreamLabels label_stream(const ModelView& model, const AnnotatorConfig& config, const std::vector<double>& times_s,
                          const float* positions, std::size_t joints) {
    auto annotator = std::make_unique<Annotator<HostCapacity>>();
    if (annotator->init(model, config) != Status::ok)
        throw std::invalid_argument("the model or the segmenter settings do not fit the host annotator");
    const std::size_t frames = times_s.size();
    StreamLabels out;
    out.window.assign(frames, -1);
    out.live.assign(frames, -1);
    out.settled.assign(frames, -1);
    out.settled_at_s.assign(frames, 0.0);
    auto id = [](LabelId label) { return label == unknown_label ? -1 : static_cast<int>(label); };
    // Characters of every stream epoch (a restart begins a new one), with their final label and when it came.
    std::vector<int> char_label;
    std::vector<double> char_emitted;
    std::vector<long long> frame_char(frames, -1);
    std::size_t epoch = 0;  // index in char_label of the current epoch's character 0
    for (std::size_t f = 0; f < frames; ++f) {
        const double now = times_s[f];
        const FrameResult r = annotator->push_frame(static_cast<std::int64_t>(std::llround(now * 1e6)), positions + f * joints * 3);
        if (r.status == Status::stream_restarted) {
            // The old epoch's unsettled tail is gone with the reset; it stays unknown, emitted now.
            for (std::size_t c = epoch; c < char_label.size(); ++c)
                if (char_label[c] == -3) char_label[c] = -1, char_emitted[c] = now;
            epoch = char_label.size();
        }
        while (char_label.size() < epoch + annotator->characters()) {
            char_label.push_back(-3);  // not settled yet
            char_emitted.push_back(now);
        }
        if (r.characters_settled > 0) {
            const std::uint64_t last = annotator->settled_character();
            for (std::uint64_t k = 0; k < r.characters_settled; ++k) {
                const std::uint64_t c = last - (r.characters_settled - 1 - k);
                char_label[epoch + c] = id(annotator->settled_label(c));
                char_emitted[epoch + c] = now;
            }
        }
        out.window[f] = id(annotator->label());
        out.live[f] = id(annotator->live_label());
        if (annotator->characters() > 0) frame_char[f] = static_cast<long long>(epoch + annotator->characters() - 1);
    }
    // At the end of the stream, the unsettled tail gets what the best explanation says of it then.
    for (std::uint64_t c = annotator->has_settled() ? annotator->settled_character() + 1 : 0; c < annotator->characters(); ++c) {
        char_label[epoch + c] = id(annotator->provisional_label(c));
        char_emitted[epoch + c] = times_s.back();
    }
    for (std::size_t f = 0; f < frames; ++f) {
        if (frame_char[f] < 0) {
            out.settled_at_s[f] = times_s[f];
            continue;
        }
        const auto c = static_cast<std::size_t>(frame_char[f]);
        out.settled[f] = char_label[c] == -3 ? -1 : char_label[c];
        out.settled_at_s[f] = std::max(char_emitted[c], times_s[f]);
    }
    return out;
}

namespace {

// Appends one stream's timeline to the pooled per-frame vectors.
struct PooledTimelines {
    std::vector<int> truth, window, live, settled;
    std::vector<double> times, settled_at;
    std::vector<std::size_t> stream_starts;

    void add(const StreamTimeline& timeline) {
        stream_starts.push_back(truth.size());
        truth.insert(truth.end(), timeline.truth.begin(), timeline.truth.end());
        times.insert(times.end(), timeline.times_s.begin(), timeline.times_s.end());
        window.insert(window.end(), timeline.labels.window.begin(), timeline.labels.window.end());
        live.insert(live.end(), timeline.labels.live.begin(), timeline.labels.live.end());
        settled.insert(settled.end(), timeline.labels.settled.begin(), timeline.labels.settled.end());
        settled_at.insert(settled_at.end(), timeline.labels.settled_at_s.begin(), timeline.labels.settled_at_s.end());
    }
    void score(OnlineReport& report) {
        stream_starts.push_back(truth.size());
        report.settled = score_timeline(truth, settled, times, stream_starts, &settled_at);
        report.live = score_timeline(truth, live, times, stream_starts);
        report.window = score_timeline(truth, window, times, stream_starts);
    }
};

int model_label(const std::vector<std::string>& names, const std::string& label) {
    const auto found = std::find(names.begin(), names.end(), label);
    return found == names.end() ? -2 : static_cast<int>(found - names.begin());
}

}  // namespace

OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed,
                             const AnnotatorConfig& config) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
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
        const ConcatenatedStream stream = concatenate_stream(segments);
        StreamTimeline timeline;
        timeline.name = "subject " + subject.first;
        for (std::size_t f = 0; f < stream.frame_count(); ++f) timeline.times_s.push_back(static_cast<double>(stream.times_us[f]) * 1e-6);
        timeline.truth.assign(stream.frame_count(), -1);
        for (std::size_t s = 0; s < stream.segment_labels.size(); ++s) {
            const int label = model_label(names, stream.segment_labels[s]);
            const std::size_t end = s + 1 < stream.segment_first_frame.size() ? stream.segment_first_frame[s + 1] : stream.frame_count();
            for (std::size_t f = stream.segment_first_frame[s]; f < end; ++f) timeline.truth[f] = label;
        }
        timeline.labels = label_stream(model, config, timeline.times_s, stream.positions.data(), stream.joints);
        pooled.add(timeline);
        report.streams.push_back(std::move(timeline));
    }
    pooled.score(report);
    return report;
}

std::vector<LabelledRecording> read_recordings(const std::vector<ClipListEntry>& entries, const ReadOptions& read) {
    std::vector<LabelledRecording> recordings;
    std::map<std::string, std::size_t> index;
    for (const ClipListEntry& entry : entries) {
        if (!entry.has_interval)
            throw ReadError(entry.path, 0, "list line " + std::to_string(entry.line) +
                                               ": a continuous recording needs 'start' and 'end' columns for its labelled intervals");
        auto found = index.find(entry.path);
        if (found == index.end()) {
            ClipListEntry whole = entry;
            whole.has_interval = false;
            recordings.push_back({entry.subject, read_clip(whole, read), {}});
            found = index.emplace(entry.path, recordings.size() - 1).first;
        }
        recordings[found->second].intervals.push_back({entry.label, entry.start_s, entry.end_s});
    }
    return recordings;
}

OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings,
                                 const AnnotatorConfig& config) {
    std::vector<std::string> names(model.label_names, model.label_names + model.label_count);
    OnlineReport report;
    PooledTimelines pooled;
    for (const LabelledRecording& recording : recordings) {
        const Clip& clip = recording.clip;
        StreamTimeline timeline;
        const std::size_t slash = clip.source.find_last_of('/');
        timeline.name = clip.source.substr(slash == std::string::npos ? 0 : slash + 1);
        timeline.times_s = clip.times;
        timeline.truth.assign(clip.frame_count(), -1);
        for (const auto& interval : recording.intervals) {
            const int label = model_label(names, interval.label);
            for (std::size_t f = 0; f < clip.frame_count(); ++f)
                if (clip.times[f] >= interval.start_s && clip.times[f] <= interval.end_s) timeline.truth[f] = label;
        }
        timeline.labels = label_stream(model, config, clip.times, clip.positions.data(), clip.joint_count());
        pooled.add(timeline);
        report.streams.push_back(std::move(timeline));
    }
    pooled.score(report);
    return report;
}

}  // namespace host
}  // namespace actionstring

namespace actionstring {
namespace host {

std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip, const AnnotatorConfig& config) {
    const StreamLabels labels = label_stream(model, config, clip.times, clip.positions.data(), clip.joint_count());
    std::vector<LabelSpan> spans;
    std::size_t agreeing = 0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const int label = labels.settled[f];
        if (spans.empty() || spans.back().label != label) {
            if (!spans.empty()) spans.back().end_s = clip.times[f];
            spans.push_back({clip.times[f], clip.times[f], label, 0.0, 0});
            agreeing = 0;
        }
        LabelSpan& span = spans.back();
        agreeing += labels.live[f] == label;
        ++span.frames;
        span.agreement = static_cast<double>(agreeing) / static_cast<double>(span.frames);
        span.end_s = clip.times[f];
    }
    return spans;
}

}  // namespace host
}  // namespace actionstring
