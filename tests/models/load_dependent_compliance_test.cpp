// The load-dependent compliance: K(L)·(β·τ|τ| + γ·τ³) per joint, against closed forms.
#include "pliant/models/effects/load_dependent_compliance.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

namespace pliant::models {
namespace {

JointState<double> Loaded(double tau1, double tau2, double k1 = 0.05, double k2 = 0.03) {
  JointState<double> s;
  s.external_torque_nm = {tau1, tau2};
  s.compliance_rad_per_nm = {k1, k2};
  return s;
}

// gamma1, gamma2, beta1, beta2.
TEST(LoadDependentCompliance, IsTheCompliancesShareBetaTauAbsTauPlusGammaTauCubed) {
  const double p[4] = {0.1, -0.05, -0.25, 0.08};
  const Vec2<double> d = LoadDependentComplianceEffect{}(p, Loaded(0.5, -2.0));
  EXPECT_NEAR(d[0], 0.05 * (-0.25 * 0.25 + 0.1 * 0.125), 1e-15);
  EXPECT_NEAR(d[1], 0.03 * (0.08 * -4.0 + -0.05 * -8.0), 1e-15);
  // Odd in the load.
  const Vec2<double> m = LoadDependentComplianceEffect{}(p, Loaded(-0.5, 2.0));
  EXPECT_DOUBLE_EQ(m[0], -d[0]);
  EXPECT_DOUBLE_EQ(m[1], -d[1]);
  // In proportion to the shaft's compliance at the depth: twice K, twice the extra bend.
  const Vec2<double> twice = LoadDependentComplianceEffect{}(p, Loaded(0.5, -2.0, 0.1, 0.06));
  EXPECT_NEAR(twice[0], 2.0 * d[0], 1e-15);
  EXPECT_NEAR(twice[1], 2.0 * d[1], 1e-15);
}

// A stiffness growing with the load's size, K/(1 + a|τ|) (the second
// generator's stiffening, a = 0.35 /(N·m)), is K·τ·(1 − a|τ| + a²τ² − …):
// over 0–1 N·m the β term fits what γ alone cannot, and one pair (β, γ)
// serves every depth. Least squares of the extra deflection's share
// τ/(1 + a|τ|) − τ on 100 loads, in closed form by QR.
TEST(LoadDependentCompliance, OnePairCarriesAStiffeningAtEveryDepth) {
  const double a = 0.35;
  Eigen::MatrixXd both(100, 2);
  Eigen::VectorXd share(100);
  for (int i = 0; i < 100; ++i) {
    const double tau = (i + 1) / 100.0;
    share(i) = tau / (1.0 + a * tau) - tau;
    both(i, 0) = tau * tau * tau;
    both(i, 1) = tau * std::abs(tau);
  }
  const Eigen::VectorXd fit = both.colPivHouseholderQr().solve(share);
  const Eigen::VectorXd cubic = both.col(0).colPivHouseholderQr().solve(share);
  const double rms_both = (both * fit - share).norm() / 10.0;
  const double rms_cubic = (both.col(0) * cubic - share).norm() / 10.0;
  // β near −a, and a tenth of the cubic's misfit or less.
  EXPECT_NEAR(fit[1], -a, 0.2 * a);
  EXPECT_LT(rms_both, 0.1 * rms_cubic);
  const double p[4] = {fit[0], fit[0], fit[1], fit[1]};
  for (double k : {0.03, 0.06}) {  // two depths' compliances
    for (int i = 0; i < 100; ++i) {
      const double tau = (i + 1) / 100.0;
      const double truth = k * tau / (1.0 + a * tau) - k * tau;
      EXPECT_NEAR(LoadDependentComplianceEffect{}(p, Loaded(tau, -tau, k, k))[0], truth, 1e-4 * k / 0.03);
    }
  }
}

// Its slope is K·(2β|τ| + 3γτ²): zero at no load from either side.
TEST(LoadDependentCompliance, ItsSlopeIsContinuousAtNoLoad) {
  const double p[4] = {0.1, 0.1, -0.25, -0.25};
  const double h = 1e-6;
  const auto at = [&](double tau) { return LoadDependentComplianceEffect{}(p, Loaded(tau, 0.0))[0]; };
  EXPECT_NEAR((at(h) - at(0.0)) / h, 0.0, 1e-7);
  EXPECT_NEAR((at(0.0) - at(-h)) / h, 0.0, 1e-7);
  const double tau = 0.7, slope = (at(tau + h) - at(tau - h)) / (2.0 * h);
  EXPECT_NEAR(slope, 0.05 * (2.0 * -0.25 * tau + 3.0 * 0.1 * tau * tau), 1e-8);
}

}  // namespace
}  // namespace pliant::models
