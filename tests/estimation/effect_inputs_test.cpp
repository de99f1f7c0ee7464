// What the file's effects read of each streamed row (effect_inputs.h): the
// same channels the identification fits them on, in closed form.
#include "pliant/estimation/effect_inputs.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "pliant/estimation/compliance_correction.h"
#include "pliant/models/paper_parameters.h"

namespace pliant::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An effort linear in time, τ = 0.2 + 0.5·t and −0.1 − 2·t, has the rates 0.5
// and −2 N·m/s from its third row on; the velocity is the log's where it has
// one, else the encoders' backward difference.
TEST(EffectInputs, RatesAndVelocitiesInClosedForm) {
  EffectInputs inputs;
  const double dt = 1.0 / 1500.0;
  for (int k = 0; k < 300; ++k) {
    const double t = 1.0e4 + k * dt;  // a clock far from 0: the sums are anchored
    const double s = k * dt;
    const Eigen::Vector3d q(0.01 + 0.3 * s, -0.02, 0.15);
    const auto& state = inputs.Update(t, q, {0.2 + 0.5 * s, -0.1 - 2.0 * s}, {kNaN, 0.04});
    EXPECT_EQ(state.time_s, t);
    if (k < 2) continue;
    EXPECT_NEAR(state.effort_rate_nm_s[0], 0.5, 1e-5) << k;
    EXPECT_NEAR(state.effort_rate_nm_s[1], -2.0, 1e-5) << k;
    EXPECT_NEAR(state.velocity_rad_s[0], 0.3, 1e-6) << k;
    EXPECT_EQ(state.velocity_rad_s[1], 0.04);
  }
}

// The acceleration is the velocity's rate over the same window: the log's
// v1 = 0.3 + 2·s gives 2 rad/s² from the third row; q2 = 0.75·s² without a
// velocity column gives backward differences 1.5·s − const, whose rate is 1.5
// once the first row (no difference yet: 0) has left the 0.1 s window.
// The centred rates of a whole log read the same line half a window later.
TEST(EffectInputs, AccelerationIsTheVelocitysRate) {
  EffectInputs inputs;
  const double dt = 1.0 / 1000.0;
  for (int k = 0; k < 300; ++k) {
    const double s = k * dt;
    const auto& state = inputs.Update(5.0 + s, {0.1, 0.75 * s * s, 0.15}, {0.0, 0.0},
                                      {0.3 + 2.0 * s, kNaN});
    if (k < 3) continue;
    EXPECT_NEAR(state.acceleration_rad_s2[0], 2.0, 1e-9) << k;
    if (k > 101) EXPECT_NEAR(state.acceleration_rad_s2[1], 1.5, 1e-6) << k;
  }
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1"};
  for (int k = 0; k < 2000; ++k) {
    const double t = k * 0.001;  // v1 = sin(2πt): a = 2π cos(2πt)
    const std::vector<double> row = {t, 0.0, 0.0, 0.15, 0.0, 0.0, std::sin(2 * M_PI * t)};
    log.values.insert(log.values.end(), row.begin(), row.end());
  }
  const auto centred = CentredAccelerations(log);
  // A 0.1 s line through a 1 Hz sine: slope 2π·cos(2πt)·(1 − (2π·0.1)²/40 …),
  // centred within a row (1 ms: 4π²·0.001 = 0.04 rad/s²).
  for (int k = 100; k < 1900; k += 37) {
    EXPECT_NEAR(centred[std::size_t(k)][0], 2 * M_PI * std::cos(2 * M_PI * k * 0.001), 0.07) << k;
    EXPECT_EQ(centred[std::size_t(k)][1], 0.0);
  }
}

// A row 0.5 s after the last (a pose log without its mark, a time gap) and
// every row of a quasi-static log: no velocity, no rate.
TEST(EffectInputs, PosesAndGapsHaveNoMotion) {
  EffectInputs inputs;
  inputs.Update(0.0, {0.0, 0.0, 0.15}, {0.0, 0.0}, {kNaN, kNaN});
  const auto& after_gap = inputs.Update(0.5, {0.1, 0.0, 0.15}, {1.0, 0.0}, {kNaN, kNaN});
  EXPECT_EQ(after_gap.velocity_rad_s[0], 0.0);
  EXPECT_EQ(after_gap.effort_rate_nm_s[0], 0.0);
  // After the gap the rate is the new rows' alone: 3 N·m/s from their third.
  for (int k = 1; k < 6; ++k) {
    const double t = 0.5 + 0.01 * k;
    const auto& s = inputs.Update(t, {0.1, 0.0, 0.15}, {1.0 + 3.0 * (t - 0.5), 0.0}, {kNaN, kNaN});
    if (k >= 2) EXPECT_NEAR(s.effort_rate_nm_s[0], 3.0, 1e-9) << k;
  }
  EffectInputs poses(true);
  for (int k = 0; k < 5; ++k) {
    const auto& s = poses.Update(0.001 * k, {0.1 * k, 0.0, 0.15}, {0.3 * k, 0.0}, {1.0, 1.0});
    EXPECT_EQ(s.velocity_rad_s[0], 0.0);
    EXPECT_EQ(s.effort_rate_nm_s[0], 0.0);
  }
}

// A one-joint log (no value in q2, tau2) read from its rows as every consumer reads
// them: joint 1's rate is 0.5 N·m/s as if joint 2 were recorded, joint 2's 0;
// a row with no effort at all starts the window again.
TEST(EffectInputs, AOneJointLogKeepsItsJointsRate) {
  io::LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  const io::StandardColumns columns(header);
  EffectInputs inputs;
  for (int k = 0; k < 10; ++k) {
    const double t = 0.01 * k;
    const double row[6] = {t, 0.02 * t, kNaN, 0.15, k == 5 ? kNaN : 0.2 + 0.5 * t, kNaN};
    const auto& state = inputs.Update(columns, row);
    EXPECT_EQ(state.effort_rate_nm_s[1], 0.0) << k;
    // Three rows make a line: rows 2–4, then 8 on after the empty row 5.
    const bool line = (k >= 2 && k < 5) || k >= 8;
    if (line) EXPECT_NEAR(state.effort_rate_nm_s[0], 0.5, 1e-9) << k;
    if (!line) EXPECT_EQ(state.effort_rate_nm_s[0], 0.0) << k;
    if (k >= 1) EXPECT_NEAR(state.velocity_rad_s[0], 0.02, 1e-9) << k;
  }
}

// τ1 = 0.3·t², τ2 = −t² + 0.1·t at 100 Hz over two stretches, 0–2 s and
// 3–4 s (a gap of 1 s between): rates 0.6·t and −2·t + 0.1 at the mean time
// of the rows each line reads.
io::Log QuadraticEfforts() {
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  for (int k = 0; k <= 400; ++k) {
    if (k > 200 && k < 300) continue;
    const double t = 0.01 * k;
    log.values.insert(log.values.end(), {t, 0.1, -0.2, 0.15, 0.3 * t * t, -t * t + 0.1 * t});
  }
  return log;
}

Eigen::Vector2d RateAt(double mean_time_s) {
  return Eigen::Vector2d(0.6 * mean_time_s, -2.0 * mean_time_s + 0.1);
}

// The effort's rate a fit reads (CentredEffortRates) is the stream's trailing
// line read half a window later, against the closed form of a quadratic
// effort, whose least-squares slope over evenly spaced rows is the derivative
// at their mean time.
TEST(CentredEffortRates, TheTrailingLineReadHalfAWindowLater) {
  const io::Log log = QuadraticEfforts();
  ASSERT_EQ(log.Rows(), 302u);
  const io::StandardColumns c(log.header);
  // 0.105 s: 11 rows (±5), with no row on the window's edge.
  const double window_s = 0.105;
  const auto centred = CentredEffortRates(log, window_s);
  EffectInputs stream(false, 0.1, window_s);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const double t = log.Value(r, c.t);
    const Eigen::Vector2d trailing =
        stream.Update(c, &log.values[r * log.Columns()]).effort_rate_nm_s;
    // Rows whose centred / trailing window lies whole inside their stretch.
    if ((t > 0.045 && t < 1.955) || (t > 3.045 && t < 3.955))
      EXPECT_NEAR((centred[r] - RateAt(t)).norm(), 0.0, 1e-9) << t;
    if (t > 0.095 && (t < 2.005 || t > 3.095))
      EXPECT_NEAR((trailing - RateAt(t - 0.05)).norm(), 0.0, 1e-9) << t;
  }
  // The rows beside the gap read their own stretch only: 2.0 s the line
  // through 1.90–2.00 s, 3.0 s the line through 3.00–3.05 s.
  EXPECT_NEAR((centred[200] - RateAt(1.95)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((centred[201] - RateAt(3.025)).norm(), 0.0, 1e-9);
  // A quasi-static log's t is a pose index: no rate.
  io::Log poses = log;
  poses.header.metadata.emplace_back(io::LogHeader::kTimingKey, io::LogHeader::kQuasiStatic);
  for (const Eigen::Vector2d& rate : CentredEffortRates(poses, window_s)) EXPECT_EQ(rate.norm(), 0.0);
}

models::ModelParameters WithFriction() {
  models::ModelParameters p = models::PaperParameters();
  models::EffectParameters friction;
  friction.name = "joint_friction";
  friction.parameter_names = {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"};
  friction.values = {0.1, 0.2, 0.05, 0.03, 0.02};
  friction.sd = {0.0, 0.0, 0.0, 0.0, 0.0};
  p.effects.push_back(friction);
  return p;
}

// pliant correct reads the external torque with the joint's friction at the
// row's velocity taken out: τ − τ0 − (b·v + F·tanh(v/v_s)).
TEST(EffectInputs, TheCorrectorTakesTheFrictionAtTheRowsVelocity) {
  const auto p = WithFriction();
  const ComplianceCorrector with(p, CorrectionModel::kDeadZone);
  const ComplianceCorrector without(models::PaperParameters(), CorrectionModel::kDeadZone);
  EffectInputs inputs;
  const auto& state = inputs.Update(0.0, {0.1, -0.1, 0.15}, {0.8, -0.6}, {0.05, -0.01});
  const auto a = with.Correct(state, {0.8, -0.6});
  const auto b = without.Correct(state, {0.8, -0.6});
  EXPECT_NEAR(b.external_torque_nm[0] - a.external_torque_nm[0],
              0.1 * 0.05 + 0.05 * std::tanh(0.05 / 0.02), 1e-12);
  EXPECT_NEAR(b.external_torque_nm[1] - a.external_torque_nm[1],
              0.2 * -0.01 + 0.03 * std::tanh(-0.01 / 0.02), 1e-12);
}

// The identification's second pass reads the efforts without the effects.
TEST(EffectInputs, WithoutInternalTorqueTakesTheEffectOutOfEachRow) {
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2"};
  log.values = {0.0,   0.1, -0.1, 0.15, 0.8, -0.6, 0.05, -0.01,
                0.001, 0.1, -0.1, 0.15, 0.8, -0.6, 0.0,  0.0};
  const io::Log out = WithoutInternalTorque(log, WithFriction());
  EXPECT_NEAR(out.Value(0, 4), 0.8 - 0.1 * 0.05 - 0.05 * std::tanh(2.5), 1e-12);
  EXPECT_NEAR(out.Value(0, 5), -0.6 + 0.2 * 0.01 + 0.03 * std::tanh(0.5), 1e-12);
  EXPECT_EQ(out.Value(1, 4), 0.8);  // at rest the friction is 0
  EXPECT_EQ(out.Value(0, 1), 0.1);  // nothing else changes
}

}  // namespace
}  // namespace pliant::estimation
