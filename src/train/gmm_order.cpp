// The order of a GMM's components: co-live components share a block.
#include "train/gmm_order.hpp"

#include <cstdint>
#include <stdexcept>

#include "actionstring/gmm.hpp"

namespace actionstring {
namespace host {

std::vector<std::size_t> gmm_block_order(const ModelView& model, const Eigen::MatrixXd& samples) {
    const std::size_t J = model.component_count, d = model.feature_dim, block = ModelView::gmm_block;
    std::vector<std::size_t> order(J);
    for (std::size_t j = 0; j < J; ++j) order[j] = j;
    if (J <= block) return order;
    if (static_cast<std::size_t>(samples.rows()) != d)
        throw std::invalid_argument("gmm_block_order: samples do not have the GMM's dimension");

    // together[a·J + b]: training features on which a and b are both live
    // (the diagonal: on which a is live).
    std::vector<std::uint64_t> together(J * J, 0);
    std::vector<float> feature(d), log_joint(J), scratch(gmm_scratch_floats(model));
    std::vector<std::size_t> live;
    for (Eigen::Index i = 0; i < samples.cols(); ++i) {
        for (std::size_t k = 0; k < d; ++k) feature[k] = static_cast<float>(samples(static_cast<Eigen::Index>(k), i));
        gmm_log_joint(model, feature.data(), log_joint.data(), scratch.data());
        float peak = log_joint[0];
        for (std::size_t j = 1; j < J; ++j)
            if (log_joint[j] > peak) peak = log_joint[j];
        if (!detail::is_finite(peak)) continue;  // no finite likelihood: the runtime refuses such a pose
        live.clear();
        for (std::size_t j = 0; j < J; ++j)
            if (!(log_joint[j] - peak < detail::exp_underflow_bound)) live.push_back(j);
        for (const std::size_t a : live)
            for (const std::size_t b : live) ++together[a * J + b];
    }

    std::vector<bool> placed(J, false);
    std::size_t next = 0;
    while (next < J) {
        std::size_t seed = J;
        for (std::size_t j = 0; j < J; ++j)
            if (!placed[j] && (seed == J || together[j * J + j] > together[seed * J + seed])) seed = j;
        const std::size_t first = next;
        order[next++] = seed;
        placed[seed] = true;
        while (next < J && next - first < block) {
            std::size_t best = J;
            std::uint64_t best_count = 0;
            for (std::size_t j = 0; j < J; ++j) {
                if (placed[j]) continue;
                std::uint64_t count = 0;
                for (std::size_t m = first; m < next; ++m) count += together[j * J + order[m]];
                if (best == J || count > best_count) best = j, best_count = count;
            }
            order[next++] = best;
            placed[best] = true;
        }
    }
    return order;
}

}  // namespace host
}  // namespace actionstring
