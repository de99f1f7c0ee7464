// The cluster jackknife (estimation/src/clustered_sandwich.h, JackknifeSandwich)
// against explicit leave-one-cluster-out refits, and its coverage where a
// few clusters carry a parameter's information — the case of a short
// diagnosis log, whose dozen segments are the clusters
// (docs/decisions/diagnosis-sd-by-segment-jackknife.md).
#include "../../estimation/src/clustered_sandwich.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

struct LinearFit {
  Eigen::MatrixXd j;  // rows: the clustered rows, then the prior rows
  Eigen::VectorXd y;
  std::vector<int> cluster;  // −1: a prior row
};

// Least squares of J β = y over the rows `keep` selects.
Eigen::VectorXd Solve(const LinearFit& f, int drop_cluster) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(f.j.cols(), f.j.cols());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(f.j.cols());
  for (Eigen::Index r = 0; r < f.j.rows(); ++r) {
    if (f.cluster[std::size_t(r)] == drop_cluster && drop_cluster >= 0) continue;
    h += f.j.row(r).transpose() * f.j.row(r);
    b += f.j.row(r).transpose() * f.y[r];
  }
  return h.ldlt().solve(b);
}

detail::SandwichCovariance Jackknife(const LinearFit& f, const Eigen::VectorXd& beta) {
  const Eigen::VectorXd residuals = f.j * beta - f.y;
  const Eigen::SparseMatrix<double> sparse = f.j.sparseView();
  return detail::JackknifeSandwich(sparse, residuals, f.cluster);
}

// A line y = a + b·x in five clusters of unequal size and one prior row on b:
// for a linear fit the one Gauss–Newton step is the refit itself, so the
// jackknife equals (c−1)/c Σ_c (β₋c − β)(β₋c − β)ᵀ + H⁻¹ J_mᵀ J_m H⁻¹ from
// explicit refits.
TEST(JackknifeSandwich, EqualsTheLeaveOneClusterOutRefitsOfALinearFit) {
  LinearFit f;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.2);
  const int sizes[5] = {3, 7, 4, 9, 5};
  std::vector<Eigen::RowVector2d> rows;
  for (int c = 0; c < 5; ++c) {
    for (int i = 0; i < sizes[c]; ++i) {
      const double x = 0.3 * c + 0.1 * i - 0.5;
      rows.emplace_back(1.0, x);
      f.cluster.push_back(c);
    }
  }
  rows.emplace_back(0.0, 2.0);  // a prior on b of weight 2
  f.cluster.push_back(-1);
  f.j.resize(Eigen::Index(rows.size()), 2);
  f.y.resize(Eigen::Index(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    f.j.row(Eigen::Index(r)) = rows[r];
    f.y[Eigen::Index(r)] = f.cluster[r] < 0 ? 1.4 : 0.7 + 1.5 * rows[r][1] + noise(rng) + 0.1 * f.cluster[r];
  }
  const Eigen::VectorXd beta = Solve(f, -1);
  const auto s = Jackknife(f, beta);

  Eigen::Matrix2d expected = Eigen::Matrix2d::Zero();
  for (int c = 0; c < 5; ++c) {
    const Eigen::Vector2d d = Solve(f, c) - beta;
    expected += 0.8 * d * d.transpose();
  }
  const Eigen::Matrix2d h = f.j.transpose() * f.j;
  const Eigen::Matrix2d h_inverse = h.inverse();
  const Eigen::RowVector2d prior = f.j.bottomRows(1);
  expected += h_inverse * prior.transpose() * prior * h_inverse;
  EXPECT_EQ(s.clusters, 5);
  EXPECT_NEAR((s.clustered - expected).norm() / expected.norm(), 0.0, 1e-10);
  EXPECT_NEAR((s.model - h_inverse).norm() / h_inverse.norm(), 0.0, 1e-10);
}

// Twelve clusters of 20 rows; the slope's regressor is non-zero in four of
// them only, and each cluster's slope differs by u_c ~ N(0, 0.3²) — the
// misfit a segment shares. Over 4000 draws the jackknife's variance is, on
// average, not below the slope's squared error and at most 1.4 × it
// (measured 1.27: CV3 errs on the safe side, as MacKinnon, Nielsen & Webb
// find). The Liang–Zeger form, solving with all of H, lets each of the four
// clusters pull the fit toward its own slope and shrink its residual:
// measured 0.80 of it. With four clusters informing the slope, a ±1.96 σ
// interval still covers only what Student's t with 3 degrees of freedom
// allows (measured 87.6 %, Liang–Zeger 81.8 %).
TEST(JackknifeSandwich, ItsVarianceIsNotBelowTheSquaredErrorOfASlopeThatFewClustersInform) {
  std::mt19937 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  const int clusters = 12, per = 20, draws = 4000;
  double squared_error = 0.0, jackknife = 0.0, liang_zeger = 0.0;
  for (int draw = 0; draw < draws; ++draw) {
    LinearFit f;
    f.j.resize(clusters * per, 2);
    f.y.resize(clusters * per);
    for (int c = 0; c < clusters; ++c) {
      const double slope = 1.0 + 0.3 * unit(rng);
      const double scale = c % 3 == 0 ? 1.0 + 0.5 * c / clusters : 0.0;  // 4 informative clusters
      for (int i = 0; i < per; ++i) {
        const int r = c * per + i;
        const double x = scale * (i - 9.5) / 10.0;
        f.j.row(r) << 1.0, x;
        f.y[r] = 0.2 + slope * x + 0.1 * unit(rng);
        f.cluster.push_back(c);
      }
    }
    const Eigen::VectorXd beta = Solve(f, -1);
    const Eigen::SparseMatrix<double> sparse = f.j.sparseView();
    squared_error += std::pow(beta[1] - 1.0, 2) / draws;
    jackknife += Jackknife(f, beta).clustered(1, 1) / draws;
    liang_zeger += detail::ClusteredSandwich(sparse, f.j * beta - f.y, f.cluster, {0, 1}).clustered(1, 1) / draws;
  }
  std::printf("  mean variance / squared error of the slope: jackknife %.3f, Liang–Zeger %.3f\n",
              jackknife / squared_error, liang_zeger / squared_error);
  EXPECT_GE(jackknife / squared_error, 1.0);
  EXPECT_LE(jackknife / squared_error, 1.4);
  EXPECT_LT(liang_zeger / squared_error, 0.9);
}

}  // namespace
}  // namespace pliant::estimation
