// The GMM's blocks of four components give every component the bits of the
// textbook loop, one component at a time, whatever the block (full, or the
// short last one) and whatever the path: this file is built into the unit
// tests (SIMD lanes on x86-64) and into the scalar-path tests (what a
// Cortex-M4 runs). Header-only: the models are built here, not by the trainer.
#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "actionstring/gmm.hpp"

using namespace actionstring;

namespace {

struct LaneModel {
    std::vector<float> means, factors, log_normalizers, log_weights;
    ModelView view{};
};

// Random factors written through gmm_factor_index(), so the layout under test
// is the one the view declares.
LaneModel make_model(std::mt19937& rng, std::size_t d, std::size_t J, Covariance kind) {
    LaneModel m;
    m.view.feature_dim = static_cast<std::uint16_t>(d);
    m.view.component_count = static_cast<std::uint16_t>(J);
    m.view.covariance = kind;
    std::normal_distribution<float> normal(0.0f, 1.0f);
    m.means.resize(J * d);
    for (float& v : m.means) v = normal(rng);
    const std::size_t size = m.view.factor_size();
    m.factors.assign(J * size, 0.0f);
    for (std::size_t j = 0; j < J; ++j)
        for (std::size_t k = 0; k < size; ++k) m.factors[m.view.gmm_factor_index(j, k)] = 0.5f + 0.3f * normal(rng);
    for (std::size_t j = 0; j < J; ++j) {
        m.log_normalizers.push_back(0.1f * normal(rng));
        m.log_weights.push_back(-1.0f - 0.1f * static_cast<float>(j));
    }
    m.view.gmm_means = m.means.data();
    m.view.gmm_factors = m.factors.data();
    m.view.gmm_log_normalizers = m.log_normalizers.data();
    m.view.gmm_log_weights = m.log_weights.data();
    return m;
}

// One component at a time, in the order documented in gmm.hpp: y[r] adds
// U[r][c] (z_c − μ_c) for increasing c, then q adds y[r]² for increasing r.
float reference_log_joint(const ModelView& m, std::size_t j, const float* z) {
    const std::size_t d = m.feature_dim;
    const float* mean = m.gmm_means + j * d;
    float q = 0.0f;
    if (m.covariance == Covariance::diagonal) {
        for (std::size_t c = 0; c < d; ++c) {
            const float v = m.gmm_factors[m.gmm_factor_index(j, c)] * (z[c] - mean[c]);
            q += v * v;
        }
    } else {
        std::vector<float> y(d, 0.0f);
        std::size_t k = 0;
        for (std::size_t c = 0; c < d; ++c) {
            const float e = z[c] - mean[c];
            for (std::size_t r = 0; r <= c; ++r) y[r] += m.gmm_factors[m.gmm_factor_index(j, k++)] * e;
        }
        for (std::size_t r = 0; r < d; ++r) q += y[r] * y[r];
    }
    return m.gmm_log_weights[j] + m.gmm_log_normalizers[j] - 0.5f * q;
}

std::uint32_t bits(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

}  // namespace

TEST_CASE("the interleaved layout places every element of every component once") {
    for (std::size_t J = 1; J <= 13; ++J) {
        ModelView v{};
        v.feature_dim = 5;
        v.component_count = static_cast<std::uint16_t>(J);
        v.covariance = Covariance::full;
        const std::size_t size = v.factor_size();
        std::vector<int> seen(J * size, 0);
        for (std::size_t j = 0; j < J; ++j)
            for (std::size_t k = 0; k < size; ++k) {
                const std::size_t at = v.gmm_factor_index(j, k);
                REQUIRE(at < seen.size());
                ++seen[at];
                // A block's components sit side by side, element by element.
                const std::size_t first = j - j % 4, lanes = J - first < 4 ? J - first : 4;
                CHECK(at == first * size + k * lanes + (j - first));
            }
        for (int s : seen) CHECK(s == 1);
    }
}

TEST_CASE("blocks of components give the bits of one component at a time") {
    std::mt19937 rng(2024);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    std::size_t compared = 0;
    for (const Covariance kind : {Covariance::full, Covariance::diagonal})
        for (std::size_t J = 1; J <= 11; ++J)  // every tail (1 … 3) beside full blocks
            for (const std::size_t d : {1u, 2u, 3u, 5u, 8u, 13u, 24u}) {
                const LaneModel m = make_model(rng, d, J, kind);
                std::vector<float> z(d), log_joint(J), scratch(gmm_scratch_floats(m.view));
                for (int sample = 0; sample < 4; ++sample) {
                    for (float& v : z) v = 2.0f * normal(rng);
                    REQUIRE(gmm_log_joint(m.view, z.data(), log_joint.data(), scratch.data()) == Status::ok);
                    for (std::size_t j = 0; j < J; ++j) {
                        CHECK(bits(log_joint[j]) == bits(reference_log_joint(m.view, j, z.data())));
                        ++compared;
                    }
                }
            }
    CHECK(compared > 1000);
}

TEST_CASE("the GMM needs one y per component of a block (two blocks with AVX2), and none without a GMM") {
    ModelView v{};
    v.feature_dim = 24;
    CHECK(gmm_scratch_floats(v) == 0);
    v.component_count = 2;
    CHECK(gmm_scratch_floats(v) == 48);
    v.component_count = 4;
    CHECK(gmm_scratch_floats(v) == 96);
    v.component_count = 40;
#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
    CHECK(gmm_scratch_floats(v) == 192);
#else
    CHECK(gmm_scratch_floats(v) == 96);
#endif
}

namespace {

// The posterior the textbook way: every log joint in full, then the peak, the
// exponentials and the normalisation in gmm_posterior()'s order.
struct ReferencePosterior {
    std::vector<float> posterior;
    float log_likelihood = 0.0f;
    std::size_t most_probable = 0;
};

ReferencePosterior reference_posterior(const ModelView& m, const float* z) {
    const std::size_t J = m.component_count;
    ReferencePosterior out;
    out.posterior.resize(J);
    float peak = -detail::infinity();
    for (std::size_t j = 0; j < J; ++j) {
        out.posterior[j] = reference_log_joint(m, j, z);
        if (out.posterior[j] > peak) peak = out.posterior[j], out.most_probable = j;
    }
    float sum = 0.0f;
    for (float& p : out.posterior) {
        p = detail::exp_portable(p - peak);
        sum += p;
    }
    const float inverse = 1.0f / sum;
    for (float& p : out.posterior) p *= inverse;
    out.log_likelihood = peak + detail::log_portable(sum);
    return out;
}

}  // namespace

TEST_CASE("a posterior whose blocks stop early has the bits of the full computation") {
    // Means spread from tight to far apart, so that from a few components to
    // nearly all of them underflow, and some lie near exp's underflow bound,
    // where a wrong bound would show; every start the caller may give.
    std::mt19937 rng(77);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    std::size_t compared = 0, zeros = 0, near_bound = 0;
    for (const Covariance kind : {Covariance::full, Covariance::diagonal})
        for (const std::size_t J : {1u, 4u, 7u, 13u, 20u, 40u})  // with AVX2, pairs of blocks and single ones
            for (const std::size_t d : {3u, 8u, 9u, 13u, 16u, 24u, 25u})
                for (const float spread : {0.5f, 3.0f, 8.0f}) {
                    LaneModel m = make_model(rng, d, J, kind);
                    for (float& v : m.means) v *= spread;
                    std::vector<float> z(d), posterior(J), scratch(gmm_scratch_floats(m.view));
                    for (int sample = 0; sample < 3; ++sample) {
                        const std::size_t near = static_cast<std::size_t>(sample) % J;
                        for (std::size_t c = 0; c < d; ++c) z[c] = m.means[near * d + c] + 0.5f * normal(rng);
                        const ReferencePosterior want = reference_posterior(m.view, z.data());
                        for (std::size_t j = 0; j < J; ++j) {
                            const float gap = reference_log_joint(m.view, j, z.data()) -
                                              reference_log_joint(m.view, want.most_probable, z.data());
                            if (gap < -60.0f && gap > -120.0f) ++near_bound;
                        }
                        for (const std::size_t start : {std::size_t{0}, J / 2, J - 1, J + 5}) {
                            std::size_t most_probable = start;
                            float log_likelihood = 0.0f;
                            REQUIRE(gmm_posterior(m.view, z.data(), posterior.data(), scratch.data(), &log_likelihood,
                                                  &most_probable) == Status::ok);
                            for (std::size_t j = 0; j < J; ++j) {
                                CHECK(bits(posterior[j]) == bits(want.posterior[j]));
                                zeros += posterior[j] == 0.0f;
                            }
                            CHECK(bits(log_likelihood) == bits(want.log_likelihood));
                            CHECK(most_probable == want.most_probable);
                            ++compared;
                        }
                        // Without a start, the same bits.
                        REQUIRE(gmm_posterior(m.view, z.data(), posterior.data(), scratch.data()) == Status::ok);
                        for (std::size_t j = 0; j < J; ++j) CHECK(bits(posterior[j]) == bits(want.posterior[j]));
                    }
                }
    CHECK(compared > 1000);
    CHECK(zeros > 10000);      // many components underflowed, so blocks had reasons to stop
    CHECK(near_bound > 300);  // and many lay near the bound
}

namespace {

// What gmm_block_distances<L> must do for the L components from 0: without a
// peak the bits of gmm_log_joint(); with a peak just above their best no stop;
// with one beyond every bound a stop.
template <std::size_t L>
void check_block_stops(std::mt19937& rng, Covariance kind, std::size_t d) {
    const LaneModel m = make_model(rng, d, L, kind);
    std::vector<float> z(d), scratch(gmm_scratch_floats(m.view));
    float want[L], q[L];
    for (std::size_t c = 0; c < d; ++c) z[c] = m.means[c] + 1000.0f;  // far from every component
    REQUIRE(gmm_log_joint(m.view, z.data(), want, scratch.data()) == Status::ok);
    // No peak: every distance in full, the bits of gmm_log_joint().
    REQUIRE(detail::gmm_block_distances<L>(m.view, 0, z.data(), scratch.data(), q, nullptr));
    for (std::size_t l = 0; l < L; ++l) CHECK(bits(detail::gmm_log_joint_of(m.view, l, q[l])) == bits(want[l]));
    // A peak just above the best of them: none can underflow, so no stop.
    float best = want[0];
    for (float w : want) best = w > best ? w : best;
    const float close = best + 1.0f;
    CHECK(detail::gmm_block_distances<L>(m.view, 0, z.data(), scratch.data(), q, &close));
    // A peak more than exp's underflow above every bound (a log joint is at
    // most log w + log normalizer): the block stops at its first check.
    float ceiling = -detail::infinity();
    for (std::size_t l = 0; l < L; ++l) {
        const float c = m.log_weights[l] + m.log_normalizers[l];
        ceiling = c > ceiling ? c : ceiling;
    }
    const float far = ceiling + 100.0f;
    CHECK_FALSE(detail::gmm_block_distances<L>(m.view, 0, z.data(), scratch.data(), q, &far));
}

}  // namespace

TEST_CASE("a block stops early exactly when its posteriors cannot be above zero") {
    std::mt19937 rng(5);
    for (const Covariance kind : {Covariance::full, Covariance::diagonal})
        for (const std::size_t d : {9u, 24u}) check_block_stops<4>(rng, kind, d);
#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
    // Two blocks side by side (full covariance only): the same rule over eight lanes.
    for (const std::size_t d : {9u, 13u, 24u}) check_block_stops<8>(rng, Covariance::full, d);
#endif
}

TEST_CASE("the lane paths are the ones the compiler's target selects") {
#if defined(ACTIONSTRING_NO_SIMD)
    CHECK(ACTIONSTRING_DETAIL_LANES == 0);
    CHECK(ACTIONSTRING_DETAIL_WIDE_LANES == 0);
#elif defined(__AVX2__)
    CHECK(ACTIONSTRING_DETAIL_LANES == 4);
    CHECK(ACTIONSTRING_DETAIL_WIDE_LANES == 8);  // the AVX2 build of these tests runs the eight-lane paths
#elif defined(__SSE2__)
    CHECK(ACTIONSTRING_DETAIL_LANES == 4);
    CHECK(ACTIONSTRING_DETAIL_WIDE_LANES == 0);
#endif
}

TEST_CASE("a posterior taken a few blocks at a time has gmm_posterior()'s bits") {
    // gmm_pass_advance() in random steps, as spread work takes it
    // (AnnotatorConfig::spread_work): the same blocks in the same order.
    std::mt19937 rng(91);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    std::uniform_int_distribution<std::size_t> step(0, 3);
    std::size_t compared = 0, split = 0;
    for (const Covariance kind : {Covariance::full, Covariance::diagonal})
        for (const std::size_t J : {1u, 4u, 7u, 13u, 40u})
            for (const std::size_t d : {3u, 9u, 24u}) {
                LaneModel m = make_model(rng, d, J, kind);
                for (float& v : m.means) v *= 3.0f;
                std::vector<float> z(d), want(J), got(J), scratch(gmm_scratch_floats(m.view));
                for (int sample = 0; sample < 4; ++sample) {
                    for (std::size_t c = 0; c < d; ++c)
                        z[c] = m.means[(static_cast<std::size_t>(sample) % J) * d + c] + 0.7f * normal(rng);
                    for (const std::size_t start : {std::size_t{0}, J / 2, J - 1}) {
                        std::size_t want_best = start, got_best = start;
                        float want_ll = 0.0f, got_ll = 0.0f;
                        REQUIRE(gmm_posterior(m.view, z.data(), want.data(), scratch.data(), &want_ll, &want_best) ==
                                Status::ok);
                        GmmPass pass;
                        gmm_pass_begin(m.view, pass, start);
                        std::size_t left = gmm_pass_blocks_left(m.view, pass), calls = 0;
                        CHECK(left == (J + 3) / 4);
                        for (bool more = true; more; ++calls) {
                            more = gmm_pass_advance(m.view, pass, z.data(), got.data(), scratch.data(), step(rng));
                            const std::size_t now = gmm_pass_blocks_left(m.view, pass);
                            CHECK(now < left);  // every call moves on
                            CHECK(more == (now > 0));
                            left = now;
                        }
                        split += calls > 1;
                        REQUIRE(gmm_pass_finish(m.view, pass, got.data(), &got_ll, &got_best) == Status::ok);
                        for (std::size_t j = 0; j < J; ++j) CHECK(bits(got[j]) == bits(want[j]));
                        CHECK(bits(got_ll) == bits(want_ll));
                        CHECK(got_best == want_best);
                        ++compared;
                    }
                }
            }
    CHECK(compared == 360);
    CHECK(split > 150);
}
