// The clustered sandwich (estimation/src/clustered_sandwich.h) against its
// closed form, and the joint smoother's σ on an instrument whose clamps each
// bend off the law (docs/decisions/0009-identification-clustered-sandwich-for-the-smoother.md).
#include "../../estimation/src/clustered_sandwich.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "clamped_beam_log.h"
#include "paper_parameters.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/estimation/parameter_query.h"

namespace pliant::estimation {
namespace {

// A mean y = μ + e over rows in clusters: the fit is the mean, H = n, and the
// sandwich is c/(c−1)·Σ_c (Σ_{i∈c} r_i)² / n²; a prior row keeps its
// information: it adds a²/(n + a²)² for a row of weight a.
TEST(ClusteredSandwich, TheMeanOfClusteredRowsHasTheLiangZegerVariance) {
  const std::vector<double> r = {0.3, -0.1, 0.5, -0.4, -0.2, 0.1, 0.6, -0.8};
  const std::vector<int> cluster = {0, 0, 1, 1, 1, 2, 2, -1};  // the last: a prior
  const double a = 0.5;                                        // the prior row's weight
  Eigen::SparseMatrix<double> jacobian(8, 2);                  // column 1 untouched
  for (int i = 0; i < 7; ++i) jacobian.insert(i, 0) = 1.0;
  jacobian.insert(7, 0) = a;
  const Eigen::VectorXd residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), 8);
  const auto s = detail::ClusteredSandwich(jacobian, residuals, cluster, {0, 1});
  const double h = 7.0 + a * a;
  const double sums[3] = {0.3 - 0.1, 0.5 - 0.4 - 0.2, 0.1 + 0.6};
  double meat = 0.0;
  for (double g : sums) meat += g * g;
  EXPECT_EQ(s.clusters, 3);
  EXPECT_NEAR(s.clustered(0, 0), (1.5 * meat + a * a) / (h * h), 1e-14);
  EXPECT_NEAR(s.model(0, 0), 1.0 / h, 1e-14);
  EXPECT_EQ(s.clustered(1, 1), 0.0);  // a column no row touches has no variance
  EXPECT_EQ(s.model(1, 1), 0.0);
}

// A mean over 120 rows in 24 clusters of 5 whose errors alternate in runs of
// 30 rows: the clusters are shorter than the errors' correlation and their
// sandwich is small. The blocking takes runs of 2, 3, 4, 6, 8 clusters
// (while three remain) and keeps the largest, the 6-cluster runs', whose
// scores are ±30: 4/3 · 4 · 30² / 120².
TEST(ClusteredSandwich, TheBlockingKeepsTheLongestRunsVarianceWhereErrorsOutlastTheClusters) {
  const int n = 120;
  Eigen::SparseMatrix<double> jacobian(n, 1);
  Eigen::VectorXd residuals(n);
  std::vector<int> cluster(n);
  for (int i = 0; i < n; ++i) {
    jacobian.insert(i, 0) = 1.0;
    residuals[i] = (i / 30) % 2 == 0 ? 1.0 : -1.0;
    cluster[i] = i / 5;
  }
  const auto base = detail::ClusteredSandwich(jacobian, residuals, cluster, {0});
  EXPECT_NEAR(base.clustered(0, 0), 24.0 / 23.0 * 24 * 25.0 / (n * n), 1e-14);
  const auto blocked = detail::BlockedSandwich(jacobian, residuals, cluster, {0}, 3);
  EXPECT_NEAR(blocked.clustered(0, 0), 4.0 / 3.0 * 4 * 900.0 / (n * n), 1e-14);
  EXPECT_EQ(blocked.clusters, 24);
  // Ten clusters at the least: runs of 2 (12 clusters) only, scores ±10.
  const auto few = detail::BlockedSandwich(jacobian, residuals, cluster, {0}, 10);
  EXPECT_NEAR(few.clustered(0, 0), 12.0 / 11.0 * 12 * 100.0 / (n * n), 1e-14);
}

TEST(ClusteredSandwich, NotBelowRaisesOnlyTheDirectionsUnderTheFloor) {
  Eigen::Matrix2d a, floor;
  a << 4.0, 0.0, 0.0, 0.25;
  floor = Eigen::Matrix2d::Identity();
  const Eigen::MatrixXd b = detail::NotBelow(a, floor);
  EXPECT_NEAR(b(0, 0), 4.0, 1e-12);  // above the floor: kept
  EXPECT_NEAR(b(1, 1), 1.0, 1e-12);  // below: raised to it
  EXPECT_NEAR(b(0, 1), 0.0, 1e-12);
}

TEST(ClusteredSandwich, NotBelowHoldsAcrossParametersOfVeryDifferentScales) {
  // A law coefficient (sd ~30) beside a clearance (sd ~1e-5 rad): the result
  // must dominate both A and the floor, Loewner order, in every direction.
  Eigen::Matrix3d floor, a;
  floor << 900.0, 1.5e-4, 0.0, 1.5e-4, 1e-10, 0.0, 0.0, 0.0, 0.0;  // the third held
  a << 400.0, -1e-4, 0.0, -1e-4, 4e-10, 0.0, 0.0, 0.0, 0.0;
  const Eigen::MatrixXd b = detail::NotBelow(a, floor);
  const Eigen::Vector3d unit(30.0, 1e-5, 1.0);
  const auto scaled = [&](const Eigen::MatrixXd& m) {
    return Eigen::MatrixXd(unit.cwiseInverse().asDiagonal() * m * unit.cwiseInverse().asDiagonal());
  };
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> over_floor(scaled(b - floor));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> over_a(scaled(b - a));
  EXPECT_GT(over_floor.eigenvalues().minCoeff(), -1e-9);
  EXPECT_GT(over_a.eigenvalues().minCoeff(), -1e-9);
  EXPECT_GE(b(0, 0), 900.0 * (1.0 - 1e-9));  // A below the floor on the law: raised
  EXPECT_GE(b(1, 1), 4e-10 * (1.0 - 1e-9));  // above it on the clearance: kept
  EXPECT_LT(b(1, 1), 8e-10);
  EXPECT_EQ(b(2, 2), 0.0);  // held in both: exactly zero
  EXPECT_EQ(b(0, 2), 0.0);
}

// Each clamp of this instrument bends a few percent off the depth law (as the
// real clamped beams do, docs/decisions/0001-…): the law's σ must come from
// how the clamps disagree, not from the row noise, which a long log shrinks.
IdentificationData ScatteredClamps(unsigned seed, double clamp_scatter) {
  IdentificationData data;
  testing::CalibrationLogSpec sweep;
  sweep.truth = models::testing::PaperParameters();
  sweep.clamp = false;
  sweep.seed = seed;
  AppendSamples(testing::MakeCalibrationLog(sweep), "sweep.csv", {}, &data);
  std::mt19937 rng(seed);
  std::normal_distribution<double> scatter(0.0, clamp_scatter);
  for (int i = 0; i < 12; ++i) {
    testing::CalibrationLogSpec clamp = sweep;
    clamp.clamp = true;
    clamp.bias_sweep = false;
    clamp.joints = {0};
    clamp.depths_m = {0.09 + 0.13 * i / 11.0};
    clamp.seed = seed * 100 + unsigned(i);
    // K of this clamp ×(1 + ε): an inverse cubic's coefficients ÷ (1 + ε).
    for (double& c : clamp.truth.joints[0].compliance.cubic.coefficients) c /= 1.0 + scatter(rng);
    AppendSamples(testing::MakeCalibrationLog(clamp), "clamp.csv", {}, &data);
  }
  return data;
}

TEST(JointSmoother, SigmaCoversTheClampToClampScatterOfTheCompliance) {
  const auto truth = models::testing::PaperParameters();
  const double k_true = models::ComplianceAt(truth.joints[0], 0.155);
  const int seeds = 5;
  double reported = 0.0, square_error = 0.0;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const auto r = RunJointSmoother(ScatteredClamps(seed, 0.02), PaperPrior());
    const auto at = QueryParametersAtDepth(r.parameters, 0.155).joints[0];
    std::printf("seed %u: K1(0.155) %.5f ± %.5f, truth %.5f (z %+.1f)\n", seed,
                at.compliance_rad_per_nm, at.compliance_sd, k_true,
                (at.compliance_rad_per_nm - k_true) / at.compliance_sd);
    reported += at.compliance_sd * at.compliance_sd / seeds;
    square_error += std::pow(at.compliance_rad_per_nm - k_true, 2) / seeds;
  }
  // The RMS error over the seeds against the RMS stated σ: 5 seeds pin a sd
  // to about ±35 % (χ²₅), accept a factor 2 either way. White row noise
  // (times the variance factor) states σ several times below the error.
  const double ratio = std::sqrt(square_error / reported);
  std::printf("K1(0.155): RMS error %.3g, RMS stated sd %.3g (ratio %.2f)\n",
              std::sqrt(square_error), std::sqrt(reported), ratio);
  EXPECT_LT(ratio, 2.0);
  EXPECT_GT(ratio, 0.5);
}

}  // namespace
}  // namespace pliant::estimation
