// The simulator against the physics it claims: the paper's Fig. 5 on the
// clamped beam, the bias torque of Fig. 4, the clearance of a free tip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pliant/experiments/clamped_beam_analysis.h"
#include "pliant/experiments/simulator.h"
#include "pliant/experiments/truth_model.h"
#include "simulation_support.h"

namespace pliant::experiments {
namespace {

using testing::Load;

TEST(SimulatorPhysics, ClampedBeamSlopesAreOneOverKAndGapsAreTwiceTheBacklash) {
  // All 14 depths and both joints; shorter settling than the scenario file
  // (0.12 s is about four closed-loop time constants) keeps the test quick.
  const Scenario s = Load("clamped_beam", {"experiment.settle_s=0.12", "experiment.move_s=0.05"});
  const SimulationResult result = Simulate(s, 1);
  const auto fits = FitClampedBeam(result);
  ASSERT_EQ(fits.size(), 28u);
  std::printf("joint depth_m  1/K_true  upper/true lower/true  gap/2delta  holds\n");
  for (const auto& fit : fits) {
    const auto& joint = s.truth.joints[fit.joint - 1];
    const double inverse_k = 1.0 / models::ComplianceAt(joint, fit.depth_m);
    const double upper = fit.upper_wall.slope / inverse_k, lower = fit.lower_wall.slope / inverse_k;
    const double gap = fit.gap_rad / (2.0 * joint.backlash_rad);
    std::printf("%d     %.3f   %7.3f   %.4f     %.4f     %.4f      %zu\n", fit.joint, fit.depth_m,
                inverse_k, upper, lower, gap, fit.angle_rad.size());
    EXPECT_NEAR(upper, 1.0, 0.03) << "joint " << fit.joint << " depth " << fit.depth_m;
    EXPECT_NEAR(lower, 1.0, 0.03) << "joint " << fit.joint << " depth " << fit.depth_m;
    EXPECT_NEAR(gap, 1.0, 0.05) << "joint " << fit.joint << " depth " << fit.depth_m;
    EXPECT_GE(fit.upper_wall.points, 8);
    EXPECT_GE(fit.lower_wall.points, 8);
  }
}

TEST(SimulatorPhysics, BiasSweepGivesBackTheBiasTorqueWithinTheEffortNoise) {
  const Scenario& s = testing::BiasSweepScenario();
  const SimulationResult& result = testing::BiasSweepRun();
  const TruthModel truth(s);
  // The mean of 20 samples of noise sd 0.01 N·m: sd 0.0022 N·m; 4 sd plus one
  // ADC step bounds every hold.
  const double sd = s.sensors.effort_noise_sd_nm / std::sqrt(20.0);
  double sum_squares = 0.0, worst = 0.0;
  int holds = 0;
  for (const HoldRecord& hold : result.holds) {
    models::JointState<double> state;
    state.encoder_angle_rad = hold.encoder_rad;
    state.insertion_depth_m = hold.depth_m;
    const Eigen::Vector2d error = hold.effort_nm - truth.InternalTorque(state);
    for (int j = 0; j < 2; ++j) sum_squares += error[j] * error[j];
    worst = std::max(worst, error.cwiseAbs().maxCoeff());
    ++holds;
  }
  const double rms = std::sqrt(sum_squares / (2.0 * holds));
  std::printf("bias sweep: %d holds, rms error %.5f N·m (noise of a mean %.5f), worst %.5f\n",
              holds, rms, sd, worst);
  EXPECT_EQ(holds, 2 * (37 + 21));
  EXPECT_LT(worst, 4.0 * sd + s.sensors.effort_count_nm);
  EXPECT_NEAR(rms, sd, 0.5 * sd);
}

TEST(SimulatorPhysics, AFreeTipStaysWithinTheClearance) {
  const Scenario s = Load("free_motion", {"experiment.duration_s=20"});
  const SimulationResult result = Simulate(s, 3);
  const io::Log& log = result.log;
  const io::StandardColumns c(log.header);
  double worst[2] = {0.0, 0.0};
  for (std::size_t row = 0; row < log.Rows(); ++row) {
    worst[0] = std::max(worst[0], std::abs(log.Value(row, c.q1) - log.Value(row, c.q1_true)));
    worst[1] = std::max(worst[1], std::abs(log.Value(row, c.q2) - log.Value(row, c.q2_true)));
  }
  std::printf("free tip: worst |q - q_true| %.6f, %.6f rad (delta %.6f, %.6f)\n", worst[0],
              worst[1], s.truth.joints[0].backlash_rad, s.truth.joints[1].backlash_rad);
  // The light tip needs a little bend to be dragged and accelerated: under a
  // count here, plus a count of quantisation.
  for (int j = 0; j < 2; ++j) {
    EXPECT_LE(worst[j], s.truth.joints[j].backlash_rad + 2 * s.sensors.encoder_count_rad);
    EXPECT_GT(worst[j], 0.9 * s.truth.joints[j].backlash_rad);  // it does cross the clearance
  }
}

TEST(SimulatorPhysics, EffortSaturatesAtTheLimit) {
  const Scenario s =
      Load("divot", {"experiment.depths_m=[0.15]", "experiment.directions_deg=[0]",
                     "experiment.peak_torques_nm=[1.0]", "experiment.speeds_rad_s=[0.05]",
                     "controller.effort_limit_nm=0.6", "sensors.effort_noise_sd_nm=0"});
  const auto tau = Simulate(s, 1).log.Column("tau1");
  const double peak = *std::max_element(tau.begin(), tau.end());
  EXPECT_NEAR(peak, 0.6, s.sensors.effort_count_nm);
}

TEST(SimulatorPhysics, IsDeterministicForASeedAndLabelsItsLog) {
  const Scenario s = Load("free_motion", {"experiment.duration_s=1"});
  const SimulationResult a = Simulate(s, 11), b = Simulate(s, 11), other = Simulate(s, 12);
  EXPECT_EQ(a.log.values, b.log.values);
  EXPECT_NE(a.log.values, other.log.values);
  EXPECT_EQ(a.log.header.Metadata("seed"), "11");
  for (const char* column : {"t", "q1", "q2", "q3", "tau1", "tau2", "q1_true", "q2_true",
                             "tip_fixed", "segment", "q1_ref", "q2_ref"}) {
    EXPECT_TRUE(a.log.header.Has(column)) << column;
  }
  EXPECT_EQ(a.log.Rows(), 1500u);  // 1 s at the dVRK's 1.5 kHz
}

}  // namespace
}  // namespace pliant::experiments
