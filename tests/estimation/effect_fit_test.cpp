// WithFittedEffects: the file's covariance after a fit of effects with the
// base model's refit, against the first-order propagation written out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "paper_parameters.h"
#include "pliant/estimation/effect_fit.h"

namespace pliant::estimation {
namespace {

Eigen::Index IndexOf(const models::ParameterCovariance& c, const std::string& name) {
  const auto it = std::find(c.names.begin(), c.names.end(), name);
  return it == c.names.end() ? -1 : Eigen::Index(it - c.names.begin());
}

EffectFinding Finding(const std::string& name, std::vector<std::string> names,
                      std::vector<double> values, std::vector<double> sd) {
  EffectFinding f;
  f.name = name;
  f.parameter_names = std::move(names);
  f.parameters = std::move(values);
  f.parameter_sd = std::move(sd);
  return f;
}

// An identified file (inverse cubic for joint 1, with a covariance over its
// law and clearance, and an old coupling), a refit s1 = 0.1, d1 = 0.0005 rad
// and a coupling fitted with it, cov(s1, k12) = ρ.
TEST(WithFittedEffects, PropagatesTheRefitAndAppendsTheEffectToTheCovariance) {
  models::ModelParameters p = models::testing::PaperParameters();
  ASSERT_EQ(p.joints[0].compliance.form, models::ComplianceForm::kInverseCubic);
  const auto c = p.joints[0].compliance.cubic.coefficients;
  models::ParameterCovariance old;
  old.names = {"joint1.compliance.c3", "joint1.compliance.c0", "joint1.backlash_rad",
               "deflection_coupling.k12", "deflection_coupling.k21"};
  old.matrix = Eigen::MatrixXd::Identity(5, 5) * 4.0;
  p.covariance = old;
  p.effects.push_back({"deflection_coupling", {"k12", "k21"}, {0.1, 0.1}, {2.0, 2.0}});
  const double delta = p.joints[0].backlash_rad;

  FittedEffects fitted;
  fitted.recalibration = Finding("base_recalibration", {"s1", "s2", "d1", "d2"},
                                 {0.1, 0.0, 0.0005, 0.0}, {0.01, 0.01, 1e-4, 1e-4});
  fitted.effects = {Finding("deflection_coupling", {"k12", "k21"}, {0.006, 0.004}, {3e-5, 2e-5})};
  Eigen::MatrixXd sigma = Eigen::MatrixXd::Zero(6, 6);
  sigma.diagonal() << 1e-4, 1e-4, 1e-8, 1e-8, 9e-10, 4e-10;
  const double rho = 1e-7;
  sigma(0, 4) = sigma(4, 0) = rho;
  fitted.covariance = sigma;

  const auto out = WithFittedEffects(p, fitted, "a test");
  // The values: K scaled, 1/K's cubic divided; δ widened; the effect replaced.
  EXPECT_NEAR(out.joints[0].compliance.cubic.coefficients[0], c[0] / 1.1, 1e-9 * std::abs(c[0]));
  EXPECT_NEAR(out.joints[0].backlash_rad, delta + 0.0005, 1e-15);
  ASSERT_EQ(out.effects.size(), 1u);
  EXPECT_EQ(out.effects[0].values, (std::vector<double>{0.006, 0.004}));
  EXPECT_EQ(out.effects[0].sd, (std::vector<double>{3e-5, 2e-5}));

  ASSERT_TRUE(out.covariance);
  const auto& cov = *out.covariance;
  ASSERT_EQ(cov.names.size(), 5u);  // the old coupling's rows replaced, not duplicated
  const auto c3 = IndexOf(cov, "joint1.compliance.c3"), c0 = IndexOf(cov, "joint1.compliance.c0");
  const auto d = IndexOf(cov, "joint1.backlash_rad");
  const auto k12 = IndexOf(cov, "deflection_coupling.k12"), k21 = IndexOf(cov, "deflection_coupling.k21");
  ASSERT_TRUE(c3 >= 0 && c0 >= 0 && d >= 0 && k12 >= 0 && k21 >= 0);
  // c' = c/(1 + s): var c' = var c/(1 + s)² + (c/(1 + s)²)² var s.
  const double g3 = -c[0] / (1.1 * 1.1), g0 = -c[3] / (1.1 * 1.1);
  EXPECT_NEAR(cov.matrix(c3, c3), 4.0 / 1.21 + g3 * g3 * 1e-4, 1e-9 * cov.matrix(c3, c3));
  EXPECT_NEAR(cov.matrix(c3, c0), g3 * g0 * 1e-4, 1e-9 * std::abs(g3 * g0 * 1e-4));
  EXPECT_NEAR(cov.matrix(c3, k12), g3 * rho, 1e-9 * std::abs(g3 * rho));
  EXPECT_NEAR(cov.matrix(d, d), 4.0 + 1e-8, 1e-12);
  EXPECT_NEAR(cov.matrix(k12, k12), 9e-10, 1e-20);
  EXPECT_NEAR(cov.matrix(k21, k21), 4e-10, 1e-20);
  EXPECT_EQ(cov.matrix(k12, d), 0.0);
  EXPECT_TRUE(cov.matrix.isApprox(cov.matrix.transpose()));
}

// A refit with a depth tilt u1 = 0.05 on joint 1 (inverse cubic): the file's
// law is 1/K' = (1/K − u·x/K_mid)/(1 + s), x = (L − L_mid)/half over the
// depth range, exactly, and its c1, c0 carry u's variance.
TEST(WithFittedEffects, WritesTheDepthTiltInTheLawsOwnForm) {
  models::ModelParameters p = models::testing::PaperParameters();
  const auto& joint = p.joints[0];
  ASSERT_EQ(joint.compliance.form, models::ComplianceForm::kInverseCubic);
  const double middle = 0.5 * (joint.depth_min_m + joint.depth_max_m);
  const double half = 0.5 * (joint.depth_max_m - joint.depth_min_m);
  const double k_middle = models::ComplianceAt(joint, middle);
  models::ParameterCovariance old;
  old.names = {"joint1.compliance.c1", "joint1.compliance.c0"};
  old.matrix = Eigen::MatrixXd::Zero(2, 2);
  p.covariance = old;

  FittedEffects fitted;
  fitted.recalibration = Finding("base_recalibration", {"s1", "s2", "d1", "d2", "u1", "u2"},
                                 {0.1, 0.0, 0.0, 0.0, 0.05, 0.0}, {0.0, 0.0, 0.0, 0.0, 0.01, 0.0});
  fitted.effects = {Finding("deflection_coupling", {"k12", "k21"}, {0.006, 0.004}, {3e-5, 2e-5})};
  Eigen::MatrixXd sigma = Eigen::MatrixXd::Zero(8, 8);
  sigma(4, 4) = 1e-4;  // var u1
  sigma(6, 6) = 9e-10, sigma(7, 7) = 4e-10;
  fitted.covariance = sigma;

  const auto out = WithFittedEffects(p, fitted, "a test");
  for (double depth : {joint.depth_min_m, 0.13, middle, 0.2, joint.depth_max_m}) {
    const double k = models::ComplianceAt(joint, depth);
    const double x = (depth - middle) / half;
    const double expected = 1.1 / (1.0 / k - 0.05 * x / k_middle);
    EXPECT_NEAR(models::ComplianceAt(out.joints[0], depth), expected, 1e-12 * expected) << depth;
    EXPECT_NEAR(models::ComplianceAt(out.joints[1], depth), models::ComplianceAt(p.joints[1], depth),
                1e-15) << depth;
  }
  ASSERT_TRUE(out.covariance);
  const auto& cov = *out.covariance;
  const auto c1 = IndexOf(cov, "joint1.compliance.c1"), c0 = IndexOf(cov, "joint1.compliance.c0");
  ASSERT_TRUE(c1 >= 0 && c0 >= 0);
  // c1' = (c1 − u/(K_mid·half))/1.1, c0' = (c0 + u·L_mid/(K_mid·half))/1.1.
  const double g1 = -1.0 / (k_middle * half * 1.1), g0 = middle / (k_middle * half * 1.1);
  EXPECT_NEAR(cov.matrix(c1, c1), g1 * g1 * 1e-4, 1e-9 * g1 * g1 * 1e-4);
  EXPECT_NEAR(cov.matrix(c1, c0), g1 * g0 * 1e-4, 1e-9 * std::abs(g1 * g0 * 1e-4));
  EXPECT_NEAR(cov.matrix(c0, c0), g0 * g0 * 1e-4, 1e-9 * g0 * g0 * 1e-4);
}

}  // namespace
}  // namespace pliant::estimation
