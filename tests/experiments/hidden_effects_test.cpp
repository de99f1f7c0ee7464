// Each hidden effect, switched on, changes the log the way its one-line
// explanation says (models/include/pliant/models/effects/*.h).
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

double Rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / v.size());
}

TEST(HiddenEffects, FrictionShowsInTheEffortWhileMoving) {
  const std::vector<std::string> base = {"experiment.duration_s=8", "hidden_effects={}"};
  auto with = base;
  with.push_back(
      "hidden_effects.joint_friction={\"viscous1\":0.3,\"coulomb1\":0.1,\"velocity_scale\":0.01}");
  const io::Log off = Simulate(Load("free_motion", base), 1).log;
  const io::Log on = Simulate(Load("free_motion", with), 1).log;
  const auto tau_off = off.Column("tau1"), tau_on = on.Column("tau1"), v = on.Column("v1");
  std::vector<double> residual, predicted;
  for (std::size_t i = 3000; i < v.size(); ++i) {  // after the 2 s fade-in
    const double friction = 0.3 * v[i] + 0.1 * std::tanh(v[i] / 0.01);
    predicted.push_back(friction);
    residual.push_back(tau_on[i] - tau_off[i] - friction);
  }
  std::printf("friction: rms predicted %.4f N·m, rms (measured - predicted) %.4f N·m\n",
              Rms(predicted), Rms(residual));
  EXPECT_GT(Rms(predicted), 0.1);
  EXPECT_LT(Rms(residual), 0.1 * Rms(predicted));
}

TEST(HiddenEffects, EffortDriftAddsASlowOffset) {
  const std::vector<std::string> base = {"experiment.duration_s=30",
                                         "experiment.amplitude_rad=[0,0]",
                                         "experiment.depth_amplitude_m=0", "hidden_effects={}"};
  auto with = base;
  with.push_back(
      "hidden_effects.effort_drift={\"rate1\":0.02,\"rate2\":-0.01,\"settling_rate\":0.1}");
  const io::Log off = Simulate(Load("free_motion", base), 1).log;
  const io::Log on = Simulate(Load("free_motion", with), 1).log;
  const auto t = on.Column("t");
  for (const char* column : {"tau1", "tau2"}) {
    const auto a = off.Column(column), b = on.Column(column);
    const double size = column[3] == '1' ? 0.2 : -0.1;  // rate / settling_rate, N·m
    for (double at : {5.0, 10.0, 20.0, 29.0}) {  // mean over 0.2 s around `at`
      double sum = 0.0;
      int n = 0;
      for (std::size_t i = 0; i < t.size(); ++i) {
        if (std::abs(t[i] - at) < 0.1) sum += b[i] - a[i], ++n;
      }
      std::printf("drift %s at %4.0f s: measured %+.4f N·m, a(1 - exp(-t/T)) %+.4f N·m\n", column,
                  at, sum / n, size * (1.0 - std::exp(-at / 10.0)));
      EXPECT_NEAR(sum / n, size * (1.0 - std::exp(-at / 10.0)), 0.003) << column << " at " << at;
    }
  }
}

// One clamped-beam run of joint 1 at 0.15 m, with extra overrides.
SimulationResult ClampedJoint1(const std::vector<std::string>& extra) {
  std::vector<std::string> sets = {"experiment.depths_m=[0.15]", "experiment.joints=[1]",
                                   "experiment.settle_s=0.12", "experiment.move_s=0.05"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  return Simulate(Load("clamped_beam", sets), 1);
}

TEST(HiddenEffects, LoadDependentComplianceBendsTheShaftMoreUnderLoad) {
  const double gamma = 0.33, delta = 0.008478;  // a share of K(L) per (N·m)²
  const std::vector<std::string> sets = {
      "experiment.depths_m=[0.15]", "experiment.joints=[1]", "hidden_effects={}",
      "hidden_effects.load_dependent_compliance={\"gamma1\":0.33}"};
  const Scenario s = Load("clamped_beam", sets);
  const SimulationResult r = Simulate(s, 1);
  const TruthModel truth(s);
  const double k = models::ComplianceAt(s.truth.joints[0], 0.15);
  int checked = 0;
  double largest_extra = 0.0, worst = 0.0;
  for (const HoldRecord& hold : r.holds) {
    models::JointState<double> state;
    state.encoder_angle_rad = hold.encoder_rad;
    state.insertion_depth_m = 0.15;
    const double tau = hold.effort_nm[0] - truth.InternalTorque(state)[0];
    if (std::abs(tau) < 0.2) continue;  // on a wall
    const double bend = hold.encoder_rad[0] - hold.true_angle_rad[0] - std::copysign(delta, tau);
    // The shaft's deflection beyond the clearance is K·(tau + gamma·tau³), within
    // 4 sd of a 20-sample effort mean (through the law's slope) and a count.
    const double slope = k * (1.0 + 3.0 * gamma * tau * tau);  // d bend / d tau
    const double extra = k * gamma * tau * tau * tau;
    EXPECT_NEAR(bend, k * tau + extra, slope * 0.009 + 7.7e-6) << tau;
    worst = std::max(worst, std::abs(bend - k * tau - extra) / slope);
    largest_extra = std::max(largest_extra, std::abs(extra));
    ++checked;
  }
  std::printf(
      "load-dependent compliance: %d holds, largest K·gamma·tau³ %.4f rad, worst misfit "
      "%.4f N·m of load\n",
      checked, largest_extra, worst);
  EXPECT_GT(checked, 20);
  EXPECT_GT(largest_extra, 0.01);  // the effect is large against the tolerance
}

TEST(HiddenEffects, DeflectionCouplingBendsJointOneUnderAPitchLoad) {
  const Scenario s =
      Load("divot", {"experiment.depths_m=[0.15]", "experiment.directions_deg=[45]",
                     "experiment.peak_torques_nm=[1.0]", "experiment.speeds_rad_s=[0.05]",
                     "sensors.effort_noise_sd_nm=0", "hidden_effects={}",
                     "hidden_effects.deflection_coupling={\"k12\":0.02}"});
  const io::Log log = Simulate(s, 1).log;
  const io::StandardColumns c(log.header);
  const int q1_cmd = log.header.Index("q1_cmd"), q2_cmd = log.header.Index("q2_cmd");
  const TruthModel truth(s);
  const double k1 = models::ComplianceAt(s.truth.joints[0], 0.15);
  // Averaged over the hold (the command still for 0.2 s or more): the encoder
  // count dithers the PID's derivative term, so single samples are not at rest.
  double measured = 0.0, expected = 0.0, coupling = 0.0;
  int held = 0, still = 0;
  for (std::size_t row = 1; row < log.Rows(); ++row) {
    const bool same = log.Value(row, q1_cmd) == log.Value(row - 1, q1_cmd) &&
                      log.Value(row, q2_cmd) == log.Value(row - 1, q2_cmd);
    still = same ? still + 1 : 0;
    if (log.Value(row, c.tip_fixed) < 0.5 || still < 300) continue;
    models::JointState<double> state;
    state.encoder_angle_rad << log.Value(row, c.q1), log.Value(row, c.q2);
    state.insertion_depth_m = 0.15;
    const Eigen::Vector2d load = Eigen::Vector2d(log.Value(row, c.tau1), log.Value(row, c.tau2)) -
                                 truth.InternalTorque(state);
    if (load.minCoeff() < 0.3) continue;  // both joints on a cannula wall
    // q1 − q1_true = delta1 + K1·tau1 + k12·tau2: the pitch load bends yaw.
    measured += log.Value(row, c.q1) - log.Value(row, c.q1_true);
    expected += s.truth.joints[0].backlash_rad + k1 * load[0] + 0.02 * load[1];
    coupling += 0.02 * load[1];
    ++held;
  }
  ASSERT_GT(held, 500);
  std::printf("coupling: %d samples, k12·tau2 %.5f rad, mean q1 - q1_true %.6f vs model %.6f rad\n",
              held, coupling / held, measured / held, expected / held);
  EXPECT_NEAR(coupling / held, 0.02 * 0.59, 0.001);
  EXPECT_NEAR(measured / held, expected / held, 2e-5);  // against a coupling bend of 0.012 rad
}

TEST(HiddenEffects, EffortDelayShiftsTheEffortAgainstTheEncoder) {
  const std::vector<std::string> base = {"experiment.duration_s=3"};
  auto with = base;
  with.push_back("sensors.effort_delay_s=0.01");  // 15 controller periods
  const io::Log off = Simulate(Load("free_motion", base), 1).log;
  const io::Log on = Simulate(Load("free_motion", with), 1).log;
  EXPECT_EQ(off.Column("q1"), on.Column("q1"));  // the arm moves the same
  const auto a = off.Column("tau1"), b = on.Column("tau1");
  for (std::size_t i = 15; i < a.size(); ++i) ASSERT_EQ(b[i], a[i - 15]) << i;
}

TEST(HiddenEffects, BiasTorqueChangesLinearlyWithDepth) {
  // The truth's default: joint 2's bias falls by 0.2419 N·m per metre of
  // insertion (the dVRK 2017 file), joint 1's is flat in depth.
  const SimulationResult& r = testing::BiasSweepRun();
  double difference[2] = {0.0, 0.0};
  int n[2] = {0, 0};
  const std::size_t half = r.holds.size() / 2;  // depth 0.09 m first, then 0.21 m
  for (std::size_t i = 0; i < half; ++i) {
    const int j = r.segments.at(r.holds[i].segment - 1).joint - 1;
    difference[j] += r.holds[half + i].effort_nm[j] - r.holds[i].effort_nm[j];
    ++n[j];
  }
  std::printf("bias depth: effort(0.21 m) - effort(0.09 m) %+.5f, %+.5f N·m (truth 0, %+.5f)\n",
              difference[0] / n[0], difference[1] / n[1], -0.2419 * 0.12);
  EXPECT_NEAR(difference[0] / n[0], 0.0, 0.002);
  EXPECT_NEAR(difference[1] / n[1], -0.2419 * 0.12, 0.002);
}

TEST(HiddenEffects, AnOffCentreClearanceShiftsTheGapNotItsWidth) {
  const SimulationResult r = ClampedJoint1({"truth.backlash_centre_rad=[0.003,0]"});
  const ClampedBeamFit fit = FitClampedBeam(r)[0];
  const double clamp = r.holds.front().true_angle_rad[0];
  const double middle = 0.5 * (fit.upper_wall.AngleAt(fit.unloaded_effort_nm) +
                               fit.lower_wall.AngleAt(fit.unloaded_effort_nm));
  std::printf("off-centre clearance: gap middle - clamp %.5f rad (truth 0.003), gap %.5f rad\n",
              middle - clamp, fit.gap_rad);
  EXPECT_NEAR(middle - clamp, 0.003, 5e-4);
  EXPECT_NEAR(fit.gap_rad, 2 * 0.008478, 0.05 * 2 * 0.008478);
}

// Not a hidden effect but the same kind of check: an unloaded shaft stays
// where it starts in its clearance, so the encoders read the tip plus that
// offset until a load moves it.
TEST(HiddenEffects, AShaftStartsWhereTheScenarioPutsIt) {
  const io::Log log = Simulate(Load("divot", {"hidden_effects={}", "experiment.depths_m=[0.15]",
                                              "experiment.directions_deg=[0]",
                                              "experiment.peak_torques_nm=[0.5]",
                                              "experiment.speeds_rad_s=[0.02]",
                                              "truth.initial_shaft_offset_rad=[0.004,-0.003]"}),
                               3)
                          .log;
  const auto q1 = log.Column("q1"), q1_true = log.Column("q1_true");
  const auto q2 = log.Column("q2"), q2_true = log.Column("q2_true");
  // The first second: free tip, arm at rest. One encoder count is 7.7 µrad.
  for (std::size_t k = 0; k < 1400; k += 100) {
    EXPECT_NEAR(q1[k] - q1_true[k], 0.004, 1e-5) << k;
    EXPECT_NEAR(q2[k] - q2_true[k], -0.003, 1e-5) << k;
  }
}

TEST(HiddenEffects, TrackerSeesTheTipWithItsOwnNoise) {
  const io::Log log = Simulate(Load("free_motion", {"experiment.duration_s=2"}), 1).log;
  const auto ref = log.Column("q1_ref"), truth = log.Column("q1_true");
  std::vector<double> error;
  for (std::size_t i = 0; i < ref.size(); ++i) error.push_back(ref[i] - truth[i]);
  std::printf("tracker: rms q1_ref - q1_true %.3g rad (sd 5e-5)\n", Rms(error));
  EXPECT_NEAR(Rms(error), 5e-5, 0.5e-5);
}

}  // namespace
}  // namespace pliant::experiments
