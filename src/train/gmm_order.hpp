// actionstring host library — the order of a GMM's components in the model,
// chosen so that components active on the same poses share a block of four.
//
// The runtime computes a block's four distances together and leaves the block
// early only when all four posteriors underflow (gmm.hpp). Which components
// share a block is the order of the components in the model, free at training:
// a permuted mixture is the same mixture, and each component's log joint has
// the same bits in any block. EM's order is arbitrary, so a pose's few live
// components (at J = 40 on HDM05, 5.4 on average) fall into 4.3 blocks of 10;
// grouped by how often they are live together on the training poses, into 2.6,
// and the posterior computes about a fifth fewer multiply-adds (design.md §1.3).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "actionstring/model.hpp"

namespace actionstring {
namespace host {

/// Component order for the blocks of `model`'s GMM, from the training features
/// (the columns of `samples`, feature_dim × N, as EM saw them): entry k names
/// the component that goes to position k. A component is live on a feature
/// when its log joint lies within exp's underflow of the feature's largest
/// (its posterior is not 0 in float). Blocks are filled greedily: the most
/// often live component not yet placed, then, three times, the one live most
/// often together with the block's members so far; ties go to the lower index.
/// Deterministic. With at most one block, the identity.
std::vector<std::size_t> gmm_block_order(const ModelView& model, const Eigen::MatrixXd& samples);

}  // namespace host
}  // namespace actionstring
