// actionstring host library — principal axes of the training poses (design §1.2).
#pragma once

#include <Eigen/Core>

namespace actionstring {
namespace host {

/// Principal axes of the columns of `samples`: mean and the top `dim` axes as
/// rows of a dim × D matrix, largest variance first, each with its sign fixed
/// (largest |component| positive) so results do not depend on the solver.
void fit_pca(const Eigen::MatrixXd& samples, int dim, Eigen::VectorXd& mean, Eigen::MatrixXd& axes);

}  // namespace host
}  // namespace actionstring
