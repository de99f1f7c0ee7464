// The online filter's arm torque and wall evaluate the model's code: the
// friction columns are the catalogue's joint_friction (ArmFriction), and the
// filter and the dense baselines confine the shaft with one function.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "../../estimation/src/filter_internal_torque.h"
#include "pliant/estimation/filter.h"
#include "pliant/models/effects/joint_friction.h"
#include "paper_parameters.h"

namespace pliant::estimation {
namespace {

using filter_internal::ArmFriction;
using filter_internal::InternalTorque;

// Row j is (∂τ_j/∂coulomb_j, ∂τ_j/∂viscous_j) = (tanh(v_j/v_s), v_j).
TEST(ArmFriction, ColumnsAreTheEffectsDerivativesInClosedForm) {
  const double scale = 0.05;
  const Eigen::Vector2d velocity(0.3, -0.02);
  const Eigen::Matrix2d columns = ArmFriction(scale, velocity);
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(columns(j, 0), std::tanh(velocity[j] / scale), 1e-15);
    EXPECT_DOUBLE_EQ(columns(j, 1), velocity[j]);
  }
  // At rest the Coulomb level gives no torque (the effect has no stiction).
  EXPECT_EQ(ArmFriction(scale, Eigen::Vector2d::Zero()), Eigen::Matrix2d::Zero());
}

// The learned arm torque with coefficients (J, f, c, τ_b) = (0, F_j, b_j, 0) is
// the catalogue effect's torque with those levels, joint by joint.
TEST(ArmFriction, TheLearnedTorqueIsTheCatalogueEffectsTorque) {
  const double p[5] = {0.12, 0.33, 0.15, 0.14, 0.05};  // b1, b2, F1, F2, v_s: the real PSM2's
  models::JointState<double> state;
  state.velocity_rad_s << -0.7, 0.004;
  const models::Vec2<double> expected = models::JointFrictionEffect{}(p, state);
  const Eigen::Matrix2d columns = ArmFriction(p[4], state.velocity_rad_s);
  for (int j = 0; j < 2; ++j) {
    InternalTorque arm;
    arm.coefficients << 0.0, p[2 + j], p[j], 0.0;
    arm.SetMotion(3.0, columns.row(j));  // any acceleration: J is 0
    EXPECT_NEAR(arm.Torque(), expected[j], 1e-15) << "joint " << j + 1;
  }
}

// The learned J, f, c start from the options' σ unless the file states the
// arm's dynamics with σ (identified on free motion): then each joint's own.
TEST(ArmPriorSd, TheFilesArmDynamicsSetEachJointsPrior) {
  const FilterOptions o;
  const Eigen::Vector3d defaults(o.internal_inertia_sd_kg_m2, o.internal_coulomb_sd_nm,
                                 o.internal_viscous_sd_nm_s);
  EXPECT_EQ(filter_internal::ArmPriorSd(o, {}, 0), defaults);
  const std::vector<models::EffectParameters> effects = {
      {"joint_friction", {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"},
       {0.13, 0.41, 0.137, 0.124, 0.031}, {0.027, 0.16, 0.015, 0.025, 0.011}},
      {"joint_inertia", {"inertia1", "inertia2"}, {0.217, 0.165}, {0.009, 0.0}}};
  EXPECT_EQ(filter_internal::ArmPriorSd(o, effects, 0), Eigen::Vector3d(0.009, 0.015, 0.027));
  // Joint 2's inertia states no σ (0: held at its value): the option's stays.
  EXPECT_EQ(filter_internal::ArmPriorSd(o, effects, 1),
            Eigen::Vector3d(o.internal_inertia_sd_kg_m2, 0.025, 0.16));
}

// A held tip's J·θ̈ is taken out once: the option's motor inertia beside a
// file's identified joint_inertia is refused, by name, and each alone is not.
TEST(OptionsAgainstParameters, TheMotorInertiaBesideTheFilesInertiaIsRefused) {
  models::ModelParameters parameters = models::testing::PaperParameters();
  FilterOptions o;
  o.motor_inertia_kg_m2 = 0.08;
  EXPECT_EQ(OptionsAgainstParameters(parameters, o), "");
  EXPECT_NO_THROW(ComplianceFilter(parameters, o));
  parameters.effects.push_back({"joint_inertia", {"inertia1", "inertia2"}, {0.217, 0.165}, {0.009, 0.021}});
  const std::string why = OptionsAgainstParameters(parameters, o);
  EXPECT_NE(why.find("motor_inertia_kg_m2 = 0.08"), std::string::npos) << why;
  EXPECT_NE(why.find("\u2014 set it to 0"), std::string::npos) << why;
  EXPECT_THROW(ComplianceFilter(parameters, o), std::invalid_argument);
  o.motor_inertia_kg_m2 = 0.0;
  EXPECT_NO_THROW(ComplianceFilter(parameters, o));
}

TEST(ConfineToClearance, ClampsTheClearanceThenTheShaftToIt) {
  const double delta = 0.007;
  double e = 0.02, b = 0.02;  // twice the nominal clearance is the most there is
  ConfineToClearance(delta, &e, &b);
  EXPECT_DOUBLE_EQ(e, delta);
  EXPECT_DOUBLE_EQ(b, 2.0 * delta);
  e = -0.001;
  b = -0.0065;
  ConfineToClearance(delta, &e, &b);
  EXPECT_DOUBLE_EQ(e, -0.001);
  EXPECT_DOUBLE_EQ(b, -0.006);
  e = -0.01;  // no clearance at all: the shaft sits on its axis
  b = 0.003;
  ConfineToClearance(delta, &e, &b);
  EXPECT_DOUBLE_EQ(e, -delta);
  EXPECT_DOUBLE_EQ(b, 0.0);
  e = 0.0;
  b = 0.004;  // inside: untouched
  ConfineToClearance(delta, &e, &b);
  EXPECT_DOUBLE_EQ(b, 0.004);
}

}  // namespace
}  // namespace pliant::estimation
