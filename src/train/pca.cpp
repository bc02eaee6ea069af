// Principal axes of training poses, in double precision.
#include "train/pca.hpp"

#include <Eigen/Eigenvalues>

#include <stdexcept>
#include <string>

namespace actionstring {
namespace host {

void fit_pca(const Eigen::MatrixXd& samples, int dim, Eigen::VectorXd& mean, Eigen::MatrixXd& axes) {
    if (dim <= 0 || dim > samples.rows())
        throw std::invalid_argument("PCA dimension " + std::to_string(dim) + " must be between 1 and the input's " +
                                    std::to_string(samples.rows()) +
                                    " coordinates (the pose's, and its velocity's and acceleration's when "
                                    "weighed): give --pca " +
                                    std::to_string(samples.rows()) + " or less");
    if (samples.cols() < 2) throw std::invalid_argument("PCA needs at least two samples");
    mean = samples.rowwise().mean();
    const Eigen::MatrixXd centred = samples.colwise() - mean;
    const Eigen::MatrixXd covariance = centred * centred.transpose() / static_cast<double>(samples.cols() - 1);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    if (solver.info() != Eigen::Success) throw std::invalid_argument("PCA: eigen-decomposition failed");
    axes.resize(dim, samples.rows());
    for (int r = 0; r < dim; ++r) {
        Eigen::VectorXd axis = solver.eigenvectors().col(samples.rows() - 1 - r);  // ascending order
        Eigen::Index largest = 0;
        axis.cwiseAbs().maxCoeff(&largest);
        if (axis[largest] < 0) axis = -axis;
        axes.row(r) = axis.transpose();
    }
}

}  // namespace host
}  // namespace actionstring
