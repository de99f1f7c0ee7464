// The load-dependent compliance: β·τ|τ| + γ·τ³ per joint, against closed forms.
#include "pliant/models/effects/load_dependent_compliance.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

namespace pliant::models {
namespace {

JointState<double> Loaded(double tau1, double tau2) {
  JointState<double> s;
  s.external_torque_nm = {tau1, tau2};
  return s;
}

// gamma1, gamma2, beta1, beta2.
TEST(LoadDependentCompliance, IsBetaTauAbsTauPlusGammaTauCubed) {
  const double p[4] = {0.004, -0.002, -0.01, 0.003};
  const Vec2<double> d = LoadDependentComplianceEffect{}(p, Loaded(0.5, -2.0));
  EXPECT_NEAR(d[0], -0.01 * 0.25 + 0.004 * 0.125, 1e-15);
  EXPECT_NEAR(d[1], 0.003 * -4.0 + -0.002 * -8.0, 1e-15);
  // Odd in the load.
  const Vec2<double> m = LoadDependentComplianceEffect{}(p, Loaded(-0.5, 2.0));
  EXPECT_DOUBLE_EQ(m[0], -d[0]);
  EXPECT_DOUBLE_EQ(m[1], -d[1]);
}

// A stiffness growing with the load's size, K/(1 + a|τ|) (the second
// generator's stiffening, a = 0.35 /(N·m)), is K·τ − a·K·τ|τ| + a²·K·τ³ − …:
// over 0–1 N·m the β term fits what γ alone cannot. Least squares of the
// extra deflection K·τ/(1 + a|τ|) − K·τ on 100 loads, in closed form by QR.
TEST(LoadDependentCompliance, TheBetaTermCarriesAStiffeningFromSmallLoads) {
  const double k = 0.03, a = 0.35;
  Eigen::MatrixXd both(100, 2);
  Eigen::VectorXd extra(100);
  for (int i = 0; i < 100; ++i) {
    const double tau = (i + 1) / 100.0;
    extra(i) = k * tau / (1.0 + a * tau) - k * tau;
    both(i, 0) = tau * tau * tau;
    both(i, 1) = tau * std::abs(tau);
  }
  const Eigen::VectorXd fit = both.colPivHouseholderQr().solve(extra);
  const Eigen::VectorXd cubic = both.col(0).colPivHouseholderQr().solve(extra);
  const double rms_both = (both * fit - extra).norm() / 10.0;
  const double rms_cubic = (both.col(0) * cubic - extra).norm() / 10.0;
  // β near −a·K (−0.0105), and a tenth of the cubic's misfit or less.
  EXPECT_NEAR(fit[1], -a * k, 0.2 * a * k);
  EXPECT_LT(rms_both, 0.1 * rms_cubic);
  const double p[4] = {fit[0], fit[0], fit[1], fit[1]};
  for (int i = 0; i < 100; ++i) {
    const double tau = (i + 1) / 100.0;
    EXPECT_NEAR(LoadDependentComplianceEffect{}(p, Loaded(tau, -tau))[0], extra(i), 1e-4);
  }
}

// Its slope is 2β|τ| + 3γτ²: zero at no load from either side.
TEST(LoadDependentCompliance, ItsSlopeIsContinuousAtNoLoad) {
  const double p[4] = {0.004, 0.004, -0.01, -0.01};
  const double h = 1e-6;
  const auto at = [&](double tau) { return LoadDependentComplianceEffect{}(p, Loaded(tau, 0.0))[0]; };
  EXPECT_NEAR((at(h) - at(0.0)) / h, 0.0, 1e-7);
  EXPECT_NEAR((at(0.0) - at(-h)) / h, 0.0, 1e-7);
  const double tau = 0.7, slope = (at(tau + h) - at(tau - h)) / (2.0 * h);
  EXPECT_NEAR(slope, 2.0 * -0.01 * tau + 3.0 * 0.004 * tau * tau, 1e-8);
}

}  // namespace
}  // namespace pliant::models
