// Schmidt's consider covariance against its closed form on a linear fit.
#include "../../estimation/src/consider_covariance.h"

#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace pliant::estimation::detail {
namespace {

// y = Jθ θ + Jc c + unit noise; θ (3) estimated, c (2) held at its prior mean
// with sd 0.3 and 0.7. The linearised fit with c free has information
// H = JᵀJ + diag(0, 0, 0, 1/0.3², 1/0.7²), C = H⁻¹.
struct LinearFit {
  Eigen::MatrixXd j_theta, j_c, covariance;
  std::vector<double> prior_sd{0.3, 0.7};
  LinearFit() {
    std::mt19937 rng(7);
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::MatrixXd j(30, 5);
    for (long r = 0; r < j.rows(); ++r)
      for (long c = 0; c < j.cols(); ++c) j(r, c) = n(rng) + (c == 3 ? 0.8 * j(r, 0) : 0.0);
    j_theta = j.leftCols(3), j_c = j.rightCols(2);
    Eigen::MatrixXd h = j.transpose() * j;
    h(3, 3) += 1.0 / (0.3 * 0.3), h(4, 4) += 1.0 / (0.7 * 0.7);
    covariance = h.inverse();
  }
};

TEST(ConsiderCovariance, MatchesTheClosedForm) {
  const LinearFit fit;
  const auto r = ConsiderCovariance(fit.covariance, {3, 4}, fit.prior_sd);
  const Eigen::MatrixXd a = fit.j_theta.transpose() * fit.j_theta;
  const Eigen::MatrixXd b = fit.j_theta.transpose() * fit.j_c;
  const Eigen::MatrixXd a_inv = a.inverse();
  const Eigen::MatrixXd s = -a_inv * b;  // ∂θ̂/∂c with c held
  const Eigen::Matrix2d sigma = Eigen::Vector2d(0.09, 0.49).asDiagonal();
  EXPECT_LT((r.covariance.topLeftCorner(3, 3) - (a_inv + s * sigma * s.transpose())).norm(),
            1e-9 * a_inv.norm());
  EXPECT_LT((r.covariance.topRightCorner(3, 2) - s * sigma).norm(), 1e-9 * s.norm());
  EXPECT_LT((r.covariance.bottomRightCorner(2, 2) - Eigen::MatrixXd(sigma)).norm(), 1e-12);
  EXPECT_LT((r.conditional.topLeftCorner(3, 3) - a_inv).norm(), 1e-9 * a_inv.norm());
  EXPECT_EQ(r.conditional.rightCols(2).norm(), 0.0);
  // The held parameters' uncertainty shows: θ0 (correlated with c0) grows most.
  EXPECT_GT(r.covariance(0, 0), 1.5 * a_inv(0, 0));
}

TEST(ConsiderCovariance, AVarianceFactorScalesTheFitNotThePrior) {
  const LinearFit fit;
  const double factor = 4.0;
  const auto r = ConsiderCovariance(factor * fit.covariance, {3, 4}, fit.prior_sd);
  const Eigen::MatrixXd a_inv = (fit.j_theta.transpose() * fit.j_theta).inverse();
  const Eigen::MatrixXd s = -a_inv * fit.j_theta.transpose() * fit.j_c;
  const Eigen::Matrix2d sigma = Eigen::Vector2d(0.09, 0.49).asDiagonal();
  EXPECT_LT((r.covariance.topLeftCorner(3, 3) - (factor * a_inv + s * sigma * s.transpose())).norm(),
            1e-9 * a_inv.norm());
}

TEST(ConsiderCovariance, IndependentParametersAreUnchanged) {
  Eigen::MatrixXd c = Eigen::Vector3d(4.0, 0.25, 9.0).asDiagonal();
  const auto r = ConsiderCovariance(c, {1}, {2.0});
  EXPECT_DOUBLE_EQ(r.covariance(0, 0), 4.0);
  EXPECT_DOUBLE_EQ(r.covariance(2, 2), 9.0);
  EXPECT_DOUBLE_EQ(r.covariance(1, 1), 4.0);  // the prior's, not the fit's 0.25
  EXPECT_DOUBLE_EQ(r.covariance(0, 1), 0.0);
  EXPECT_THROW(ConsiderCovariance(c, {3}, {1.0}), std::invalid_argument);
  EXPECT_THROW(ConsiderCovariance(c, {1}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace pliant::estimation::detail
