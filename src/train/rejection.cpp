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

std::vector<Character> spliced(const std::vector<Character>& a, const std::vector<Character>& b) {
    std::vector<Character> s(a.begin(), a.begin() + static_cast<long>(a.size() / 2));
    s.insert(s.end(), b.begin() + static_cast<long>(b.size() / 2), b.end());
    return s;
}

std::vector<Character> faster(const std::vector<Character>& a) {  // every other character: twice the speed
    std::vector<Character> s;
    for (std::size_t t = 0; t < a.size(); t += 2) s.push_back(a[t]);
    return s;
}

std::vector<Character> slower(const std::vector<Character>& a) {  // each character twice: half the speed
    std::vector<Character> s;
    for (const Character c : a) s.insert(s.end(), 2, c);
    return s;
}

// One string to classify: what it is, and which label it may not count against.
struct Sample {
    std::vector<Character> string;
    std::vector<std::size_t> excluded;  // representatives left out (its subjects')
    LabelId own = unknown_label;  // positives: the true label; warped clips: the label they may land on
    bool positive = false;
};

}  // namespace

std::vector<SyntheticNegative> synthetic_negatives(const std::vector<std::vector<Character>>& strings,
                                                   const std::vector<LabelId>& labels, std::uint32_t seed) {
    if (strings.size() != labels.size()) throw std::invalid_argument("synthetic_negatives: one label per string");
    std::vector<SyntheticNegative> negatives;
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < strings.size(); ++i) {
        std::vector<std::size_t> others;
        for (std::size_t j = 0; j < strings.size(); ++j)
            if (labels[j] != labels[i] && strings[j].size() >= 2) others.push_back(j);
        if (others.empty() || strings[i].size() < 2) continue;
        const std::size_t j = others[std::uniform_int_distribution<std::size_t>(0, others.size() - 1)(rng)];
        negatives.push_back({spliced(strings[i], strings[j]), unknown_label, i, j});
    }
    for (std::size_t i = 0; i < strings.size(); ++i) {
        if (strings[i].size() < 2) continue;
        negatives.push_back({faster(strings[i]), labels[i], i, i});
        negatives.push_back({slower(strings[i]), labels[i], i, i});
    }
    return negatives;
}

std::vector<float> learn_label_bounds(const ModelView& model, const std::vector<std::vector<Character>>& strings,
                                      const std::vector<LabelId>& labels, const std::vector<std::string>& subjects,
                                      const std::vector<long>& own_representative,
                                      const std::vector<std::vector<Character>>& no_action, double keep,
                                      std::uint32_t seed, std::vector<LabelBoundReport>* report) {
    if (strings.size() != labels.size() || strings.size() != subjects.size() ||
        strings.size() != own_representative.size())
        throw std::invalid_argument("learn_label_bounds: one label, subject and representative per string");
    const std::size_t L = model.label_count;
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
        samples.push_back({strings[i], {}, labels[i], true});
        left_out(i, samples.back().excluded);
    }
    for (SyntheticNegative& n : synthetic_negatives(strings, labels, seed)) {
        samples.push_back({std::move(n.string), {}, n.own, false});
        left_out(n.first, samples.back().excluded);
        if (n.second != n.first) left_out(n.second, samples.back().excluded);
    }
    for (const auto& s : no_action)
        if (!s.empty()) samples.push_back({s, {}, unknown_label, false});

    // Classify every sample with the runtime's code, bounds off; each on its own, so any order gives the same.
    std::vector<Classification> results(samples.size());
    parallel_for(samples.size(), hardware_workers(), [&](std::size_t k) {
        results[k] = classify_string(model, samples[k].string, samples[k].excluded);
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
