// Clip-recognition evaluation and baselines.
#include "actionstring_host/evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "actionstring/annotator.hpp"
#include "actionstring/normalize.hpp"
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
