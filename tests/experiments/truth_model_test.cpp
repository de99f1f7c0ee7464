#include "pliant/experiments/truth_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pliant::experiments {
namespace {

Scenario PaperScenario() {
  Scenario s;
  s.truth = DefaultTruth();
  return s;
}

double InverseK1(double depth) {  // paper eq. (3)
  return ((639.16 * depth - 432.35) * depth + 136.32) * depth + 3.12;
}

TEST(TruthModel, ShaftTorqueInvertsThePapersCompliance) {
  const TruthModel truth(PaperScenario());
  models::JointState<double> state;
  state.insertion_depth_m = 0.15;
  Eigen::Matrix2d stiffness;
  const Eigen::Vector2d tau =
      truth.ShaftTorque({0.01, 0.0}, {true, false}, state, Eigen::Vector2d::Zero(), &stiffness);
  EXPECT_NEAR(tau[0], 0.01 * InverseK1(0.15), 1e-12);  // tau = deflection / K
  EXPECT_EQ(tau[1], 0.0);                              // joint 2 in the clearance
  EXPECT_NEAR(stiffness(0, 0), InverseK1(0.15), 1e-9);
  EXPECT_EQ(stiffness(1, 1), 0.0);
}

TEST(TruthModel, ShaftTorqueInvertsANonlinearCoupledLaw) {
  Scenario s = PaperScenario();
  s.hidden_effects = {{"load_dependent_compliance", {{"gamma1", 0.2}, {"gamma2", 0.5}}},
                      {"deflection_coupling", {{"k12", 0.005}, {"k21", -0.004}}}};
  const TruthModel truth(s);
  models::JointState<double> state;
  state.insertion_depth_m = 0.11;
  const Eigen::Vector2d deflection(0.03, -0.02);
  const Eigen::Vector2d tau =
      truth.ShaftTorque(deflection, {true, true}, state, Eigen::Vector2d::Zero());
  state.external_torque_nm = tau;
  EXPECT_LT((truth.Deflection(state) - deflection).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TruthModel, InternalTorqueIsTheBiasTableAndItsDepthSlope) {
  const Scenario s = PaperScenario();
  const TruthModel truth(s);
  models::JointState<double> state;
  state.encoder_angle_rad << s.truth.joints[0].bias_torque.angle_rad[3],
      s.truth.joints[1].bias_torque.angle_rad[5];
  state.insertion_depth_m = 0.205;
  const Eigen::Vector2d tau = truth.InternalTorque(state);
  EXPECT_NEAR(tau[0], s.truth.joints[0].bias_torque.torque_nm[3], 1e-12);
  EXPECT_NEAR(tau[1], s.truth.joints[1].bias_torque.torque_nm[5] - 0.2419 * (0.205 - 0.155), 1e-12);
  const auto jacobian = truth.InternalTorqueJacobian(state);
  EXPECT_EQ(jacobian(0, 2), 0.0);  // no friction: no velocity dependence
}

TEST(TruthModel, NamesTheComposedEffects) {
  Scenario s = PaperScenario();
  s.hidden_effects = {{"joint_friction", {}}, {"deflection_coupling", {}}};
  EXPECT_EQ(TruthModel(s).EffectNames(),
            (std::vector<std::string>{"bias_torque", "bias_torque_depth", "joint_friction",
                                      "compliance", "deflection_coupling"}));
}

}  // namespace
}  // namespace pliant::experiments
