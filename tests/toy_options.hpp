// Training settings the host tests use on the toy world (toy/toy.hpp).
#pragma once

#include "train/options.hpp"

namespace test {

/// A GMM of six components on the toy's unprojected 12-dimensional pose,
/// 10 characters a second: enough to tell the toy's actions apart in a second.
inline actionstring::host::TrainingOptions toy_options() {
    actionstring::host::TrainingOptions o;
    o.components = 6;
    o.pca_dim = 0;  // the toy pose has 12 dimensions
    o.string_rate_hz = 10.0;
    o.sigma = 4.0;
    o.covariance_floor = 1e-3;
    return o;
}

}  // namespace test
