// The online segmenter: incremental labels == a plain full-table reference,
// exact recovery of streams made of the representatives, "no action", limits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "actionstring/segmenter.hpp"
#include "run/state.hpp"
#include "test_support.hpp"

using namespace actionstring;

namespace {


// Matching tables of a small model whose W holds multiples of 1/4, so every
// sum is exact and the reference and the incremental state agree bit for bit.
struct Tables {
    std::vector<float> w;
    std::vector<std::uint32_t> offsets{0};
    std::vector<Character> strings;
    std::vector<LabelId> labels;
    std::vector<float> votes;  // log P(c | label), label by label, when the model has votes
    std::vector<float> none;   // log P(c | no action), when it has those too
    std::vector<float> centres;          // one-dimensional exemplars (whole numbers: exact squares), when it has them
    std::vector<LabelId> centre_labels;
    static constexpr char names_text[] = "a\0b\0c\0d";
    static constexpr std::uint32_t names_offsets[5] = {0, 2, 4, 6, 8};
    ModelView view;

    void finish(int K) {
        view.character_count = static_cast<std::uint16_t>(K);
        view.character_distances = w.data();
        view.representative_count = static_cast<std::uint16_t>(labels.size());
        view.representative_offsets = offsets.data();
        view.representative_chars = strings.data();
        view.representative_labels = labels.data();
        view.label_count = 4;
        view.label_names = NameTable{names_text, names_offsets};
        view.window_chars = 4;
        view.step_chars = 2;
        view.neighbours = 1;
        view.string_period_us = 100000;  // 10 characters per second
        if (!votes.empty()) {
            view.vote_weight = 1.0f;
            view.character_votes = votes.data();
        }
        if (!none.empty()) {
            view.has_no_action_votes = 1;
            view.no_action_votes = none.data();
        }
        view.feature_dim = 1;
        if (!centres.empty()) {
            view.exemplar_weight = 1.0f;
            view.exemplar_scale = 1.0f;
            view.exemplar_count = static_cast<std::uint16_t>(centres.size());
            view.exemplars = centres.data();
            view.exemplar_labels = centre_labels.data();
        }
    }
    void add(const std::vector<Character>& rep, LabelId label) {
        strings.insert(strings.end(), rep.begin(), rep.end());
        offsets.push_back(static_cast<std::uint32_t>(strings.size()));
        labels.push_back(label);
    }
};

Tables random_tables(std::mt19937& rng) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Tables t;
    const int K = uniform(2, 10);
    for (int a = 0; a < K * K; ++a) t.w.push_back(static_cast<float>(uniform(0, 8)) * 0.25f);
    if (uniform(0, 1) == 1)  // half the models have a symmetric W, as trained ones do (the segmenter reads its rows)
        for (int a = 0; a < K; ++a)
            for (int b = 0; b < a; ++b) t.w[static_cast<std::size_t>(b * K + a)] = t.w[static_cast<std::size_t>(a * K + b)];
    const int R = uniform(1, 6);
    for (int r = 0; r < R; ++r) {
        // 1 to 24 characters: with SIMD, a representative of four or more has
        // its lowest four cells in one block, blocks of eight (AVX2) and four
        // from the top, and at most one cell in the scalar loop; shorter ones
        // take the scalar code alone (detail/lanes.hpp).
        std::vector<Character> rep(static_cast<std::size_t>(uniform(1, 24)));
        for (auto& c : rep) c = static_cast<Character>(uniform(0, K - 1));
        t.add(rep, static_cast<LabelId>(uniform(0, 3)));
    }
    if (uniform(0, 1) == 1)  // half the models carry the characters' votes (multiples of 1/4: exact sums)
        for (int v = 0; v < 4 * K; ++v) t.votes.push_back(-static_cast<float>(uniform(0, 16)) * 0.25f);
    if (!t.votes.empty() && uniform(0, 1) == 1)
        for (int v = 0; v < K; ++v) t.none.push_back(-static_cast<float>(uniform(0, 16)) * 0.25f);
    if (uniform(0, 1) == 1) {  // half carry exemplars: one or two whole-number centres per label
        for (LabelId l = 0; l < 4; ++l)
            for (int e = uniform(1, 2); e > 0; --e) {
                t.centres.push_back(static_cast<float>(uniform(0, 3)));
                t.centre_labels.push_back(l);
            }
        for (int e = uniform(0, 2); e > 0; --e) {  // and some of those, of "no action" too (last)
            t.centres.push_back(static_cast<float>(uniform(0, 3)));
            t.centre_labels.push_back(unknown_label);
        }
    }
    t.finish(K);
    return t;
}

// The recurrence of segmenter.hpp over the whole stream at once: absolute
// costs (no shift), every column and every segment end kept, and for each
// character t the label that the best explanation at t + settle gives it.
// `margins` receives, per character, how far the best explanation's label
// leads the best one with another label (live_margin()).
// `features`, when given, holds each stream character's one-dimensional feature (exemplars).
// `stable` (characters, 0: none) settles a character sooner, once every best
// explanation since `stable` characters ago has given it one label (the
// characters before it settled); `settled_at`, when given, receives the
// character each one settled at.
std::vector<LabelId> reference_settled(const ModelView& m, const SegmenterConfig& config, std::uint32_t settle,
                                       const std::vector<Character>& stream, std::vector<float>* margins = nullptr,
                                       const std::vector<float>* features = nullptr, std::uint32_t stable = 0,
                                       std::vector<std::size_t>* settled_at = nullptr) {
    const float inf = std::numeric_limits<float>::infinity();
    const std::size_t T = stream.size(), R = m.representative_count;
    struct End {
        int rep;
        std::size_t start;
    };
    std::vector<End> ends(T);
    std::vector<float> end_cost(T);
    std::vector<std::vector<float>> cost(R);
    std::vector<std::vector<std::size_t>> start(R);
    for (std::size_t r = 0; r < R; ++r)
        cost[r].assign(m.representative_length(r) + 1, inf), start[r].assign(m.representative_length(r) + 1, 0);
    std::vector<LabelId> settled(T, unknown_label);
    if (settled_at != nullptr) settled_at->assign(T, T);
    // Early settling: each character's label in the best explanation, and since when.
    std::vector<LabelId> candidate(T, unknown_label);
    std::vector<std::size_t> since(T, 0);
    std::size_t next_to_settle = 0;
    auto weight = [&](Character a, Character b) { return m.character_distances[a * m.character_count + b]; };
    auto label = [&](int rep) { return rep < 0 ? unknown_label : m.representative_labels[rep]; };
    // The characters' votes: what character c costs label l's explanations.
    // The characters' votes: what character c costs label l's explanations
    // (l = unknown_label: "no action", when the model learned its votes).
    auto vote = [&](LabelId l, Character c) {
        if (!(config.vote_weight > 0.0f) || !m.has_votes()) return 0.0f;
        const std::size_t K = m.character_count;
        float best_vote = m.has_no_action_votes ? m.no_action_votes[c] : -inf;
        for (std::size_t k = 0; k < m.label_count; ++k) best_vote = std::max(best_vote, m.character_votes[k * K + c]);
        if (l == unknown_label) return m.has_no_action_votes ? config.vote_weight * (best_vote - m.no_action_votes[c]) : 0.0f;
        return config.vote_weight * (best_vote - m.character_votes[l * K + c]);
    };
    // The exemplars: what character t's feature costs label l's explanations
    // (l = unknown_label: "no action", when the model has centres of it).
    auto exemplar = [&](LabelId l, std::size_t t) {
        if (!(config.exemplar_weight > 0.0f) || !m.has_exemplars() || features == nullptr) return 0.0f;
        const std::size_t L = m.label_count;
        std::vector<float> nearest(L + 1, inf);  // the last: no action
        for (std::size_t e = 0; e < m.exemplar_count; ++e) {
            const float d = (*features)[t] - m.exemplars[e];
            const std::size_t slot = m.exemplar_labels[e] == unknown_label ? L : m.exemplar_labels[e];
            nearest[slot] = std::min(nearest[slot], d * d);
        }
        const float best = *std::min_element(nearest.begin(), nearest.end());
        const float own = nearest[l == unknown_label ? L : l];
        if (best == inf || (l == unknown_label && own == inf)) return 0.0f;
        return (own - best) * (config.exemplar_weight / m.exemplar_scale);
    };
    for (std::size_t t = 0; t < T; ++t) {
        const float before = t == 0 ? 0.0f : end_cost[t - 1];
        const float entry = before + config.segment_penalty;
        const float no_action = config.unknown_cost + (vote(unknown_label, stream[t]) + exemplar(unknown_label, t));
        float best = before + no_action, best_end = best;
        int best_rep = -1, end_rep = -1;
        std::size_t best_start = t, end_start = t;
        std::vector<std::vector<float>> next = cost;
        std::vector<std::vector<std::size_t>> next_start = start;
        for (std::size_t r = 0; r < R; ++r) {
            const std::size_t n = m.representative_length(r);
            const Character* rep = m.representative_chars + m.representative_offsets[r];
            for (std::size_t i = 1; i <= n; ++i) {
                float v = i >= 2 ? cost[r][i - 1] : entry;
                std::size_t from = i >= 2 ? start[r][i - 1] : t;
                if (cost[r][i] + config.stay_penalty < v) v = cost[r][i] + config.stay_penalty, from = start[r][i];
                const float skip =
                    i >= 3 ? cost[r][i - 2] + config.skip_penalty : (i == 2 ? entry + config.skip_penalty : inf);
                if (skip < v) v = skip, from = i >= 3 ? start[r][i - 2] : t;
                next[r][i] = v + (weight(rep[i - 1], stream[t]) + (vote(m.representative_labels[r], stream[t]) +
                                                                   exemplar(m.representative_labels[r], t)));
                next_start[r][i] = from;
            }
        }
        // The incremental code scans representatives in order and cells from last to first.
        for (std::size_t r = 0; r < R; ++r) {
            const std::size_t n = m.representative_length(r);
            for (std::size_t i = n; i >= 1; --i)
                if (next[r][i] < best) best = next[r][i], best_rep = static_cast<int>(r), best_start = next_start[r][i];
            if (next[r][n] < best_end)
                best_end = next[r][n], end_rep = static_cast<int>(r), end_start = next_start[r][n];
        }
        if (margins != nullptr) {
            const LabelId live = label(best_rep);
            float rival = live == unknown_label ? inf : before + no_action;
            for (std::size_t r = 0; r < R; ++r)
                if (label(static_cast<int>(r)) != live)
                    for (std::size_t i = 1; i <= m.representative_length(r); ++i) rival = std::min(rival, next[r][i]);
            margins->push_back(rival - best);
        }
        cost = next;
        start = next_start;
        ends[t] = {end_rep, end_start};
        end_cost[t] = best_end;
        if (stable > 0) {
            // The whole best explanation traced back, then the rule, oldest first.
            int rep = best_rep;
            std::size_t s = best_start;
            for (std::size_t c = t + 1; c-- > next_to_settle;) {
                while (s > c) {
                    rep = ends[s - 1].rep;
                    s = ends[s - 1].start;
                }
                if (c == t || candidate[c] != label(rep)) candidate[c] = label(rep), since[c] = t;
            }
            while (next_to_settle <= t && (t - next_to_settle >= settle || t - since[next_to_settle] >= stable)) {
                settled[next_to_settle] = candidate[next_to_settle];
                if (settled_at != nullptr) (*settled_at)[next_to_settle] = t;
                ++next_to_settle;
            }
            continue;
        }
        if (t < settle) continue;
        if (settled_at != nullptr) (*settled_at)[t - settle] = t;
        const std::size_t target = t - settle;
        int rep = best_rep;
        std::size_t s = best_start;
        while (s > target) {
            rep = ends[s - 1].rep;
            s = ends[s - 1].start;
        }
        settled[target] = label(rep);
    }
    return settled;
}

// Random online settings of the trial (exact quarters, as W holds): the settle
// delay 0 to 3 s, the penalties, and on some trials "no action" and the votes.
SegmenterConfig random_config(std::mt19937& rng, int trial) {
    SegmenterConfig config;
    config.settle_delay_us = std::uniform_int_distribution<int>(0, 30)(rng) * 100000;
    config.segment_penalty = static_cast<float>(std::uniform_int_distribution<int>(0, 8)(rng)) * 0.25f;
    config.stay_penalty = static_cast<float>(std::uniform_int_distribution<int>(0, 4)(rng)) * 0.25f;
    config.skip_penalty = static_cast<float>(std::uniform_int_distribution<int>(0, 4)(rng)) * 0.25f;
    if (trial % 3 == 0) config.unknown_cost = static_cast<float>(std::uniform_int_distribution<int>(0, 8)(rng)) * 0.25f;
    if (trial % 2 == 0) config.vote_weight = static_cast<float>(std::uniform_int_distribution<int>(0, 4)(rng)) * 0.25f;
    return config;
}

}  // namespace

TEST_CASE("settled labels equal a full-table reference of the same recurrence") {
    std::mt19937 rng(2024);
    host::Stateful<ActionSegmenter> segmenter;
    for (int trial = 0; trial < 200; ++trial) {
        Tables t = random_tables(rng);
        SegmenterConfig config = random_config(rng, trial);
        if (trial % 4 < 2)
            config.exemplar_weight = static_cast<float>(std::uniform_int_distribution<int>(0, 4)(rng)) * 0.25f;
        REQUIRE(segmenter.init(t.view, config) == Status::ok);
        const std::uint32_t settle = segmenter->settle_chars();
        CHECK(settle == static_cast<std::uint32_t>(config.settle_delay_us / 100000));
        std::vector<Character> stream(static_cast<std::size_t>(std::uniform_int_distribution<int>(1, 150)(rng)));
        for (auto& c : stream)
            c = static_cast<Character>(std::uniform_int_distribution<int>(0, t.view.character_count - 1)(rng));
        std::vector<float> features(stream.size());  // whole numbers: exact squared distances
        for (auto& f : features) f = static_cast<float>(std::uniform_int_distribution<int>(0, 3)(rng));
        std::vector<float> margins;
        const std::vector<LabelId> expected = reference_settled(t.view, config, settle, stream, &margins, &features);
        std::vector<LabelId> got(stream.size(), unknown_label);
        CHECK(segmenter->live_margin() == 0.0f);
        for (std::size_t i = 0; i < stream.size(); ++i) {
            const bool settled = segmenter->push(stream[i], &features[i]);
            CHECK(segmenter->live_margin() >= 0.0f);
            CHECK(segmenter->live_margin() == margins[i]);  // exact: W holds multiples of 1/4
            CHECK(settled == (i >= settle));
            if (!settled) continue;
            CHECK(segmenter->settled_character() == i - settle);
            got[i - settle] = segmenter->settled_label();
        }
        for (std::size_t i = 0; i + settle < stream.size(); ++i) {
            INFO("trial ", trial, " character ", i);
            CHECK(got[i] == expected[i]);
            if (stream.size() - 1 - i < segmenter->settled_history()) CHECK(segmenter->settled_label(i) == got[i]);
        }
    }
}

TEST_CASE("early settling (settle_stable_us) equals a full-table reference of its rule") {
    std::mt19937 rng(2026);
    host::Stateful<ActionSegmenter> segmenter, delay_only;
    std::size_t early = 0;  // characters settled before their delay, over all trials
    for (int trial = 0; trial < 200; ++trial) {
        Tables t = random_tables(rng);
        SegmenterConfig config = random_config(rng, trial);
        config.settle_stable_us = std::uniform_int_distribution<int>(0, 30)(rng) * 100000;
        REQUIRE(segmenter.init(t.view, config) == Status::ok);
        const std::uint32_t settle = segmenter->settle_chars();
        // Rounded to characters, at least one; none when the delay comes first.
        const std::uint32_t asked = static_cast<std::uint32_t>(config.settle_stable_us / 100000);
        const std::uint32_t stable = config.settle_stable_us == 0 ? 0u : std::max(asked, 1u);
        CHECK(segmenter->stable_chars() == (stable < settle ? stable : 0u));
        SegmenterConfig alone = config;
        alone.settle_stable_us = 0;
        REQUIRE(delay_only.init(t.view, alone) == Status::ok);
        // Two more rings, only when the rule can settle anything early.
        if (segmenter->stable_chars() == 0)
            CHECK(ActionSegmenter::required_bytes(t.view, config) == ActionSegmenter::required_bytes(t.view, alone));
        else CHECK(ActionSegmenter::required_bytes(t.view, config) > ActionSegmenter::required_bytes(t.view, alone));
        std::vector<Character> stream(static_cast<std::size_t>(std::uniform_int_distribution<int>(1, 150)(rng)));
        for (auto& c : stream)
            c = static_cast<Character>(std::uniform_int_distribution<int>(0, t.view.character_count - 1)(rng));
        std::vector<std::size_t> at;
        const std::vector<LabelId> expected =
            reference_settled(t.view, config, settle, stream, nullptr, nullptr, segmenter->stable_chars(), &at);
        std::uint64_t settled_count = 0;
        for (std::size_t i = 0; i < stream.size(); ++i) {
            const bool settled = segmenter->push(stream[i]);
            delay_only->push(stream[i]);
            // The same explanation: early settling changes what is final, never the search.
            CHECK(segmenter->live_label() == delay_only->live_label());
            CHECK(segmenter->live_margin() == delay_only->live_margin());
            CHECK(settled == (segmenter->just_settled() > 0));
            for (std::uint32_t k = 0; k < segmenter->just_settled(); ++k) {
                const std::uint64_t c = settled_count++;
                INFO("trial ", trial, " character ", c, " at ", i);
                CHECK(segmenter->settled_character() - (segmenter->just_settled() - 1 - k) == c);
                CHECK(segmenter->settled_label(c) == expected[c]);
                CHECK(at[c] == i);       // settled on the same character as the reference
                CHECK(i - c <= settle);  // never later than the delay
                early += i - c < settle;
            }
            CHECK(settled_count == (segmenter->has_settled() ? segmenter->settled_character() + 1 : 0u));
        }
        for (std::size_t c = settled_count; c < stream.size(); ++c) CHECK(at[c] == stream.size());  // none left behind
    }
    CHECK(early > 1000);  // the rule did settle characters early
}

TEST_CASE("a character's work in slices (begin, advance) gives push()'s state bit for bit") {
    const auto same_bits = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    std::mt19937 rng(77);
    host::Stateful<ActionSegmenter> whole, sliced;
    for (int trial = 0; trial < 150; ++trial) {
        Tables t = random_tables(rng);
        SegmenterConfig config;
        config.settle_delay_us = std::uniform_int_distribution<int>(0, 20)(rng) * 100000;
        config.segment_penalty = static_cast<float>(std::uniform_int_distribution<int>(0, 8)(rng)) * 0.25f;
        if (trial % 2 == 0) config.unknown_cost = 1.5f;
        if (trial % 3 == 0) config.vote_weight = 0.5f;
        if (trial % 4 < 2) config.exemplar_weight = 0.75f;
        REQUIRE(whole.init(t.view, config) == Status::ok);
        REQUIRE(sliced.init(t.view, config) == Status::ok);
        CHECK(sliced->advance(5) == ActionSegmenter::Progress::idle);
        CHECK(sliced->work_left() == 0);
        std::vector<Character> stream(static_cast<std::size_t>(std::uniform_int_distribution<int>(1, 80)(rng)));
        for (auto& c : stream)
            c = static_cast<Character>(std::uniform_int_distribution<int>(0, t.view.character_count - 1)(rng));
        const std::size_t slice = static_cast<std::size_t>(std::uniform_int_distribution<int>(0, 40)(rng));
        for (std::size_t i = 0; i < stream.size(); ++i) {
            INFO("trial ", trial, " character ", i, " slice ", slice);
            const float feature = static_cast<float>(std::uniform_int_distribution<int>(0, 3)(rng));
            const LabelId live_before = sliced->live_label();
            const float margin_before = sliced->live_margin();
            const bool settled = whole->push(stream[i], &feature);
            float copy = feature;
            REQUIRE(sliced->begin(stream[i], &copy));
            copy = -100.0f;  // begin() keeps its own copy of the feature
            CHECK(sliced->in_progress());
            ActionSegmenter::Progress progress = ActionSegmenter::Progress::working;
            std::size_t left = sliced->work_left();
            CHECK(left > 0);
            while (progress == ActionSegmenter::Progress::working) {
                // Until the character is in, the queries answer as before it.
                CHECK(sliced->characters_pushed() == i);
                CHECK(sliced->live_label() == live_before);
                CHECK(same_bits(sliced->live_margin(), margin_before));
                progress = sliced->advance(slice);
                const std::size_t now_left = sliced->work_left();
                CHECK(now_left < left);  // every call moves on
                left = now_left;
            }
            CHECK(left == 0);
            CHECK_FALSE(sliced->in_progress());
            CHECK(progress == (settled ? ActionSegmenter::Progress::settled : ActionSegmenter::Progress::done));
            CHECK(sliced->characters_pushed() == whole->characters_pushed());
            CHECK(sliced->live_label() == whole->live_label());
            CHECK(same_bits(sliced->live_margin(), whole->live_margin()));
            if (settled) CHECK(sliced->settled_label() == whole->settled_label());
            for (std::uint64_t c = i > 25 ? i - 25 : 0; c <= i; ++c) {
                CHECK(sliced->provisional_label(c) == whole->provisional_label(c));
                CHECK(sliced->settled_label(c) == whole->settled_label(c));
            }
        }
        // begin() over a character in progress finishes it first.
        const Character c = stream.front();
        const float feature = 1.0f;
        whole->push(c, &feature);
        whole->push(c, &feature);
        REQUIRE(sliced->begin(c, &feature));
        REQUIRE(sliced->begin(c, &feature));
        sliced->finish();
        CHECK(sliced->characters_pushed() == whole->characters_pushed());
        CHECK(same_bits(sliced->live_margin(), whole->live_margin()));
        CHECK(sliced->provisional_label(stream.size()) == whole->provisional_label(stream.size()));
        // reset() drops a character in progress.
        REQUIRE(sliced->begin(c, &feature));
        sliced->reset();
        CHECK_FALSE(sliced->in_progress());
        CHECK(sliced->characters_pushed() == 0);
        CHECK_FALSE(sliced->begin(static_cast<Character>(t.view.character_count), &feature));
    }
}

TEST_CASE("a stream made of the representatives is segmented exactly") {
    // Three distinct characters per label, W = 0 on the diagonal and 2 elsewhere.
    Tables t;
    const int K = 12;
    for (int a = 0; a < K; ++a)
        for (int b = 0; b < K; ++b) t.w.push_back(a == b ? 0.0f : 2.0f);
    t.add({0, 1, 2, 1, 0}, 0);
    t.add({3, 4, 5, 5, 4, 3, 4}, 1);
    t.add({6, 7, 8}, 2);
    t.add({9, 10, 11, 10}, 3);
    t.finish(K);
    host::Stateful<ActionSegmenter> segmenter;
    SegmenterConfig config;
    config.settle_delay_us = 1000000;  // 10 characters
    REQUIRE(segmenter.init(t.view, config) == Status::ok);
    std::vector<Character> stream;
    std::vector<LabelId> truth;
    std::mt19937 rng(5);
    for (int k = 0; k < 60; ++k) {
        const std::size_t r = static_cast<std::size_t>(std::uniform_int_distribution<int>(0, 3)(rng));
        for (std::uint32_t i = t.offsets[r]; i < t.offsets[r + 1]; ++i) {
            // Stretch some characters in time as a slower performer would.
            const int repeat = std::uniform_int_distribution<int>(0, 3)(rng) == 0 ? 2 : 1;
            for (int j = 0; j < repeat; ++j) stream.push_back(t.strings[i]), truth.push_back(t.labels[r]);
        }
    }
    std::size_t right = 0, settled = 0;
    for (std::size_t i = 0; i < stream.size(); ++i) {
        if (!segmenter->push(stream[i])) continue;
        ++settled;
        right += segmenter->settled_label() == truth[segmenter->settled_character()];
    }
    for (std::size_t i = stream.size() - segmenter->settle_chars(); i < stream.size(); ++i)
        right += segmenter->provisional_label(i) == truth[i];
    CHECK(settled == stream.size() - segmenter->settle_chars());
    CHECK(right == stream.size());
    CHECK(segmenter->live_label() == truth.back());
}

TEST_CASE("characters unlike every representative are 'no action' when the unknown cost allows") {
    Tables t;
    const int K = 4;
    for (int a = 0; a < K; ++a)
        for (int b = 0; b < K; ++b) t.w.push_back(a == b ? 0.0f : (a == 3 || b == 3 ? 2.0f : 1.0f));
    t.add({0, 1, 2}, 1);
    t.finish(K);
    host::Stateful<ActionSegmenter> segmenter;
    SegmenterConfig config;
    config.settle_delay_us = 500000;
    config.segment_penalty = 0.5f;
    config.unknown_cost = 0.5f;
    REQUIRE(segmenter.init(t.view, config) == Status::ok);
    std::vector<Character> stream{3, 3, 3, 3, 3, 3, 0, 1, 2, 0, 1, 2, 3, 3, 3, 3, 3, 3, 3, 3};
    std::vector<LabelId> got;
    for (Character c : stream)
        if (segmenter->push(c)) got.push_back(segmenter->settled_label());
    for (std::size_t i = got.size(); i < stream.size(); ++i) got.push_back(segmenter->provisional_label(i));
    const std::vector<LabelId> expected{unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        1,
                                        1,
                                        1,
                                        1,
                                        1,
                                        1,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label,
                                        unknown_label};
    CHECK(got == expected);

    // Without the unknown cost the same characters must go to the only action.
    config.unknown_cost = std::numeric_limits<float>::infinity();
    REQUIRE(segmenter.init(t.view, config) == Status::ok);
    for (Character c : stream) segmenter->push(c);
    CHECK(segmenter->live_label() == 1);
}

TEST_CASE("costs stay bounded on a long stream, and reset forgets it") {
    std::mt19937 rng(11);
    Tables t = random_tables(rng);
    host::Stateful<ActionSegmenter> segmenter;
    REQUIRE(segmenter.init(t.view, segmenter_config(t.view)) == Status::ok);
    // Two copies fed the same characters, one restarted halfway: after a reset
    // it must behave exactly like a fresh segmenter.
    host::Stateful<ActionSegmenter> fresh;
    REQUIRE(fresh.init(t.view, segmenter_config(t.view)) == Status::ok);
    for (int i = 0; i < 200000; ++i) {
        const auto c = static_cast<Character>(i * 7 % t.view.character_count);
        segmenter->push(c);
        if (i == 100000) segmenter->reset();
        if (i > 100000) fresh->push(c);
    }
    CHECK(segmenter->characters_pushed() == 99999);
    CHECK(segmenter->settled_label() == fresh->settled_label());
    CHECK(segmenter->live_label() == fresh->live_label());
    CHECK(segmenter->live_label() != unknown_label);
}

TEST_CASE("segmenter refuses bad settings and storage too small for them") {
    std::mt19937 rng(3);
    Tables t = random_tables(rng);
    // The rings grow with the settle delay: 41 characters need a ring of 64.
    SegmenterConfig config;
    config.settle_delay_us = 4100000;
    const std::size_t long_delay = ActionSegmenter::required_bytes(t.view, config);
    config.settle_delay_us = 1000000;
    const std::size_t short_delay = ActionSegmenter::required_bytes(t.view, config);
    CHECK(long_delay > short_delay);
    alignas(state_alignment) static unsigned char block[1 << 16];
    REQUIRE(long_delay <= sizeof block);
    ActionSegmenter segmenter;
    config.settle_delay_us = 4100000;
    CHECK(segmenter.init(t.view, config, block, short_delay) == Status::storage_too_small);
    CHECK(!segmenter.initialized());
    CHECK(!segmenter.push(0));
    CHECK(segmenter.live_label() == unknown_label);
    REQUIRE(segmenter.init(t.view, config, block, long_delay) == Status::ok);
    CHECK(segmenter.settle_chars() == 41);
    CHECK(segmenter.settled_history() == 64);
    // Settings are refused as settings, whatever the storage.
    config = SegmenterConfig{};
    config.segment_penalty = std::nanf("");
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    CHECK(ActionSegmenter::required_bytes(t.view, config) > 0);
    config = SegmenterConfig{};
    config.stay_penalty = -1.0f;
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    config = SegmenterConfig{};
    config.settle_delay_us = -1;
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    CHECK(ActionSegmenter::required_bytes(t.view, config) == unsatisfiable_bytes);
    config.settle_delay_us = max_settle_delay_us + 1;
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    config = SegmenterConfig{};
    config.settle_stable_us = -1;
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    CHECK(ActionSegmenter::required_bytes(t.view, config) == unsatisfiable_bytes);
    config.settle_stable_us = max_settle_delay_us + 1;
    CHECK(segmenter.init(t.view, config, block, sizeof block) == Status::invalid_argument);
    CHECK(ActionSegmenter::required_bytes(t.view, config) == unsatisfiable_bytes);
    ModelView no_period = t.view;
    no_period.string_period_us = 0;
    CHECK(segmenter.init(no_period, segmenter_config(no_period), block, sizeof block) == Status::invalid_model);
    // A character the model does not have is ignored.
    REQUIRE(segmenter.init(t.view, segmenter_config(t.view), block, sizeof block) == Status::ok);
    CHECK(!segmenter.push(static_cast<Character>(t.view.character_count)));
    CHECK(segmenter.characters_pushed() == 0);
}

TEST_CASE("votes learned for 'no action' make the segmenter reject what only they explain") {
    // Label a: characters 0 and 1. Character 3 sits 1 from everything, so without
    // votes label a explains a stream of 3s more cheaply than "no action" (cost 2).
    Tables t;
    const int K = 4;
    for (int a = 0; a < K; ++a)
        for (int b = 0; b < K; ++b) t.w.push_back(a == b ? 0.0f : 1.0f);
    t.add({0, 1, 0, 1}, 0);
    t.votes.assign(4 * K, -8.0f);  // every label: all characters unlikely …
    t.votes[0] = t.votes[1] = -0.75f;  // … but label a's own
    t.none = {-8.0f, -8.0f, -8.0f, -0.25f};  // no action: character 3
    t.finish(K);
    SegmenterConfig config;
    config.settle_delay_us = 0;
    config.unknown_cost = 2.0f;
    host::Stateful<ActionSegmenter> segmenter;
    const std::vector<Character> stream{0, 1, 0, 1, 3, 3, 3, 3, 3, 3, 0, 1, 0, 1};
    auto labels = [&](float vote_weight) {
        config.vote_weight = vote_weight;
        REQUIRE(segmenter.init(t.view, config) == Status::ok);
        std::vector<LabelId> out;
        for (const Character c : stream) {
            segmenter->push(c);
            out.push_back(segmenter->settled_label());
        }
        return out;
    };
    const std::vector<LabelId> plain = labels(0.0f);
    for (std::size_t i = 4; i < 10; ++i) CHECK(plain[i] == 0);  // no votes: the 3s are "a"
    const std::vector<LabelId> voted = labels(1.0f);
    for (std::size_t i = 0; i < 4; ++i) CHECK(voted[i] == 0);
    for (std::size_t i = 4; i < 10; ++i) CHECK(voted[i] == unknown_label);  // rejected
    for (std::size_t i = 10; i < stream.size(); ++i) CHECK(voted[i] == 0);
    CHECK(labels(1.0f) == voted);  // deterministic
}

TEST_CASE("exemplars of 'no action' make the segmenter reject poses only they lie near") {
    // Label a: characters 0 and 1, its poses near 0. Character 3 sits 1 from
    // everything, so by the strings alone label a explains a stretch of 3s more
    // cheaply than "no action" (cost 2); their poses lie near 3, where only
    // "no action" has a centre (as from a recording's unlabelled stretches).
    Tables t;
    const int K = 4;
    for (int a = 0; a < K; ++a)
        for (int b = 0; b < K; ++b) t.w.push_back(a == b ? 0.0f : 1.0f);
    t.add({0, 1, 0, 1}, 0);
    t.centres = {0.0f, 3.0f};
    t.centre_labels = {0, unknown_label};
    t.finish(K);
    REQUIRE(t.view.has_no_action_exemplars());
    const std::vector<Character> stream{0, 1, 0, 1, 3, 3, 3, 3, 3, 3, 0, 1, 0, 1};
    std::vector<float> features(stream.size(), 0.0f);
    for (std::size_t i = 4; i < 10; ++i) features[i] = 3.0f;
    SegmenterConfig config;
    config.settle_delay_us = 0;
    config.unknown_cost = 2.0f;
    host::Stateful<ActionSegmenter> segmenter;
    auto labels = [&](float exemplar_weight, bool with_none) {
        t.view.exemplar_count = static_cast<std::uint16_t>(with_none ? 2 : 1);
        config.exemplar_weight = exemplar_weight;
        REQUIRE(segmenter.init(t.view, config) == Status::ok);
        std::vector<LabelId> out;
        for (std::size_t i = 0; i < stream.size(); ++i) {
            segmenter->push(stream[i], &features[i]);
            out.push_back(segmenter->settled_label());
        }
        return out;
    };
    const std::vector<LabelId> plain = labels(0.0f, true);
    for (std::size_t i = 4; i < 10; ++i) CHECK(plain[i] == 0);  // no exemplars weighed: the 3s are "a"
    const std::vector<LabelId> without_none = labels(1.0f, false);
    for (std::size_t i = 4; i < 10; ++i) CHECK(without_none[i] == 0);  // a's centres alone: still "a"
    const std::vector<LabelId> with_none = labels(1.0f, true);
    for (std::size_t i = 0; i < 4; ++i) CHECK(with_none[i] == 0);
    for (std::size_t i = 4; i < 10; ++i) CHECK(with_none[i] == unknown_label);  // rejected
    for (std::size_t i = 10; i < stream.size(); ++i) CHECK(with_none[i] == 0);
}
