// Each label's rejection bound from held-out positives and negatives.
#include "train/rejection.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "common/parallel.hpp"
#include "run/classify.hpp"

namespace actionstring {
namespace host {

float choose_label_bound(std::vector<float> positives, std::vector<float> negatives, double keep) {
    if (!(keep > 0.0 && keep <= 1.0)) throw std::invalid_argument("reject-keep must be in (0, 1]");
    if (positives.empty() || negatives.empty()) return detail::infinity();
    std::sort(positives.begin(), positives.end());
    std::sort(negatives.begin(), negatives.end());
    const std::size_t P = positives.size(), N = negatives.size();
    // Candidates: each positive distance from the keep-quantile up; the bound
    // then admits that positive and every one below it.
    const std::size_t first = static_cast<std::size_t>(std::ceil(keep * static_cast<double>(P))) - 1;
    std::size_t chosen = P - 1;
    double best = -1.0;
    for (std::size_t k = first; k < P; ++k) {
        if (k + 1 < P && positives[k + 1] == positives[k]) continue;  // a bound admits equal distances together
        const double kept = static_cast<double>(k + 1) / static_cast<double>(P);
        const auto above = static_cast<std::size_t>(negatives.end() -
                                                    std::upper_bound(negatives.begin(), negatives.end(), positives[k]));
        const double score = kept + static_cast<double>(above) / static_cast<double>(N);
        if (score >= best) best = score, chosen = k;  // ties: the larger bound, admitting more
    }
    // Halfway to the next distance above (positive or negative); none above: no bound.
    float next = detail::infinity();
    const auto negative_above = std::upper_bound(negatives.begin(), negatives.end(), positives[chosen]);
    if (negative_above != negatives.end()) next = *negative_above;
    if (chosen + 1 < P) next = std::min(next, positives[chosen + 1]);
    if (!detail::is_finite(next)) return detail::infinity();
    return positives[chosen] + 0.5f * (next - positives[chosen]);
}

namespace {

// The same cuts for characters (w = 1) and for their exemplar rows (w floats
// per character): `n` characters of `a`, `m` of `b`.
template <class T>
std::vector<T> spliced(const std::vector<T>& a, std::size_t n, const std::vector<T>& b, std::size_t m, std::size_t w) {
    std::vector<T> s(a.begin(), a.begin() + static_cast<long>(n / 2 * w));
    s.insert(s.end(), b.begin() + static_cast<long>(m / 2 * w), b.begin() + static_cast<long>(m * w));
    return s;
}

// Every other character: twice the speed.
template <class T>
std::vector<T> faster(const std::vector<T>& a, std::size_t n, std::size_t w) {
    std::vector<T> s;
    for (std::size_t t = 0; t < n; t += 2)
        s.insert(s.end(), a.begin() + static_cast<long>(t * w), a.begin() + static_cast<long>((t + 1) * w));
    return s;
}

// Each character twice: half the speed.
template <class T>
std::vector<T> slower(const std::vector<T>& a, std::size_t n, std::size_t w) {
    std::vector<T> s;
    for (std::size_t t = 0; t < n; ++t)
        for (int twice = 0; twice < 2; ++twice)
            s.insert(s.end(), a.begin() + static_cast<long>(t * w), a.begin() + static_cast<long>((t + 1) * w));
    return s;
}

// One string to classify: what it is, and which label it may not count against.
struct Sample {
    std::vector<Character> string;
    std::vector<float> rows;            // its exemplar rows (with exemplars)
    std::vector<float> descriptor;      // its descriptor's penalties (with a clip descriptor)
    std::vector<std::size_t> excluded;  // representatives left out (its subjects')
    LabelId own = unknown_label;        // positives: the true label; warped clips: the label they may land on
    bool positive = false;
};

}  // namespace

std::vector<SyntheticNegative> synthetic_negatives(const std::vector<std::vector<Character>>& strings,
                                                   const std::vector<LabelId>& labels, std::uint32_t seed,
                                                   const std::vector<PerCharacterRows>& per_character) {
    if (strings.size() != labels.size()) throw std::invalid_argument("synthetic_negatives: one label per string");
    for (const PerCharacterRows& set : per_character) {
        if (set.rows == nullptr || set.rows->size() != strings.size())
            throw std::invalid_argument("synthetic_negatives: one row set per string");
        for (std::size_t i = 0; i < strings.size(); ++i)
            if ((*set.rows)[i].size() != strings[i].size() * set.width)
                throw std::invalid_argument("synthetic_negatives: a string's rows are not `width` per character");
    }
    // Every row set cut as `cut` cuts the characters (w = 1).
    auto cut_rows = [&per_character](auto cut) {
        std::vector<std::vector<float>> out;
        for (const PerCharacterRows& set : per_character) out.push_back(cut(*set.rows, set.width));
        return out;
    };
    std::vector<SyntheticNegative> negatives;
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < strings.size(); ++i) {
        std::vector<std::size_t> others;
        for (std::size_t j = 0; j < strings.size(); ++j)
            if (labels[j] != labels[i] && strings[j].size() >= 2) others.push_back(j);
        if (others.empty() || strings[i].size() < 2) continue;
        const std::size_t j = others[std::uniform_int_distribution<std::size_t>(0, others.size() - 1)(rng)];
        const std::size_t n = strings[i].size(), m = strings[j].size();
        negatives.push_back({spliced(strings[i], n, strings[j], m, 1),
                             cut_rows([&](const std::vector<std::vector<float>>& rows, std::size_t w) {
                                 return spliced(rows[i], n, rows[j], m, w);
                             }),
                             unknown_label, i, j});
    }
    for (std::size_t i = 0; i < strings.size(); ++i) {
        const std::size_t n = strings[i].size();
        if (n < 2) continue;
        negatives.push_back({faster(strings[i], n, 1),
                             cut_rows([&](const std::vector<std::vector<float>>& rows, std::size_t w) {
                                 return faster(rows[i], n, w);
                             }),
                             labels[i], i, i});
        negatives.push_back({slower(strings[i], n, 1),
                             cut_rows([&](const std::vector<std::vector<float>>& rows, std::size_t w) {
                                 return slower(rows[i], n, w);
                             }),
                             labels[i], i, i});
    }
    return negatives;
}

std::vector<float> learn_label_bounds(const ModelView& model, const std::vector<std::vector<Character>>& strings,
                                      const std::vector<LabelId>& labels, const std::vector<std::string>& subjects,
                                      const std::vector<long>& own_representative,
                                      const std::vector<std::vector<Character>>& no_action, double keep,
                                      std::uint32_t seed, std::vector<LabelBoundReport>* report,
                                      const ExemplarRows* rows, const DescriptorSamples* descriptor) {
    if (strings.size() != labels.size() || strings.size() != subjects.size() ||
        strings.size() != own_representative.size())
        throw std::invalid_argument("learn_label_bounds: one label, subject and representative per string");
    const std::size_t L = model.label_count;
    // The exemplars' rows, when the model weighs exemplars: one set per string, label_count per character.
    const bool exemplars = rows != nullptr && model.has_exemplars();
    if (exemplars) {
        if (rows->strings.size() != strings.size() || rows->no_action.size() != no_action.size())
            throw std::invalid_argument("learn_label_bounds: one set of exemplar rows per string");
        for (std::size_t i = 0; i < no_action.size(); ++i)
            if (rows->no_action[i].size() != no_action[i].size() * L)
                throw std::invalid_argument(
                    "learn_label_bounds: a stretch's exemplar rows are not label_count per character");
    }
    const bool described = descriptor != nullptr && model.has_descriptor();
    if (described) {
        if (descriptor->strings.size() != strings.size() || descriptor->no_action.size() != no_action.size() ||
            !descriptor->of_strings || !descriptor->of_stretch)
            throw std::invalid_argument("learn_label_bounds: one set of features per string, and what measures them");
        for (std::size_t i = 0; i < strings.size(); ++i)
            if (descriptor->strings[i].size() != strings[i].size() * descriptor->width)
                throw std::invalid_argument(
                    "learn_label_bounds: a string's features are not feature_dim per character");
    }
    // What a string made from clip i is measured without: the representatives
    // made from its subject's clips, or with one subject only its own.
    const bool one_subject = std::all_of(subjects.begin(), subjects.end(),
                                         [&](const std::string& s) { return s == subjects.front(); });
    auto left_out = [&](std::size_t i, std::vector<std::size_t>& excluded) {
        for (std::size_t k = 0; k < strings.size(); ++k)
            if (own_representative[k] >= 0 && (one_subject ? k == i : subjects[k] == subjects[i]))
                excluded.push_back(static_cast<std::size_t>(own_representative[k]));
    };
    std::vector<Sample> samples;
    for (std::size_t i = 0; i < strings.size(); ++i) {
        if (strings[i].empty()) continue;
        samples.push_back({strings[i],
                           exemplars ? rows->strings[i] : std::vector<float>{},
                           described ? descriptor->of_strings(descriptor->strings[i], i, i) : std::vector<float>{},
                           {},
                           labels[i],
                           true});
        left_out(i, samples.back().excluded);
    }
    // The negatives' exemplar rows and features, cut and repeated as their characters are.
    std::vector<PerCharacterRows> per_character;
    if (exemplars) per_character.push_back({&rows->strings, L});
    if (described) per_character.push_back({&descriptor->strings, descriptor->width});
    std::vector<SyntheticNegative> synthetic = synthetic_negatives(strings, labels, seed, per_character);
    for (SyntheticNegative& n : synthetic) {
        samples.push_back({std::move(n.string),
                           exemplars ? std::move(n.rows.front()) : std::vector<float>{},
                           described ? descriptor->of_strings(n.rows.back(), n.first, n.second) : std::vector<float>{},
                           {},
                           n.own,
                           false});
        left_out(n.first, samples.back().excluded);
        if (n.second != n.first) left_out(n.second, samples.back().excluded);
    }
    for (std::size_t i = 0; i < no_action.size(); ++i)
        if (!no_action[i].empty())
            samples.push_back({no_action[i],
                               exemplars ? rows->no_action[i] : std::vector<float>{},
                               described ? descriptor->of_stretch(descriptor->no_action[i], i) : std::vector<float>{},
                               {},
                               unknown_label,
                               false});

    // Classify every sample with the runtime's code, bounds off; each on its own, so any order gives the same.
    // With exemplars, a sample's rows summed in order (as exemplar_sums() sums a clip's distances).
    std::vector<Classification> results(samples.size());
    parallel_for(samples.size(), hardware_workers(), [&](std::size_t k) {
        const std::vector<float> sums = exemplars ? sum_exemplar_rows(samples[k].rows, L) : std::vector<float>{};
        results[k] = classify_string(model, samples[k].string, samples[k].excluded, exemplars ? sums.data() : nullptr,
                                     described ? samples[k].descriptor.data() : nullptr);
    });
    std::vector<std::vector<float>> positives(L), negatives(L);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const Classification& c = results[k];
        if (c.nearest_label == unknown_label || !detail::is_finite(c.distance)) continue;
        const Sample& s = samples[k];
        if (s.positive && c.nearest_label == s.own) positives[c.nearest_label].push_back(c.distance);
        else if (!s.positive && c.nearest_label == s.own) continue;  // a warped clip on its own label: still that action
        else negatives[c.nearest_label].push_back(c.distance);
    }
    std::vector<float> bounds(L);
    if (report != nullptr) report->assign(L, LabelBoundReport{});
    for (std::size_t l = 0; l < L; ++l) {
        bounds[l] = choose_label_bound(positives[l], negatives[l], keep);
        if (report == nullptr) continue;
        LabelBoundReport& r = (*report)[l];
        r.positives = positives[l].size();
        r.negatives = negatives[l].size();
        r.bound = bounds[l];
        const auto within = [&](const std::vector<float>& v) {
            return static_cast<double>(std::count_if(v.begin(), v.end(), [&](float d) { return d <= bounds[l]; }));
        };
        if (!positives[l].empty()) r.positives_kept = within(positives[l]) / static_cast<double>(positives[l].size());
        if (!negatives[l].empty())
            r.negatives_rejected = 1.0 - within(negatives[l]) / static_cast<double>(negatives[l].size());
    }
    return bounds;
}

}  // namespace host
}  // namespace actionstring
