// Contact as the exception (FilterOptions::infer_contact). In free motion the
// effort holds the arm's own inertia and friction, which the bias torque does
// not model: without the tip_fixed hint the filter must not read them as a
// load and correct the tip by them (do no harm); a real contact, a load well
// beyond that level, must still be recognised and corrected.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/paper_parameters.h"
#include "../support/pushed_tip.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRate = 100.0;  // the dVRK 2.x CRTK topics' rate

struct Row {
  FilterSample sample;
  Eigen::Vector2d truth;
};

// 30 s of free motion at up to ~1 rad/s on joint 1: the effort holds
// J·q̈ + Coulomb and viscous friction (about 0.1 N·m RMS, 0.25 N·m peaks,
// the level of the real dVRK bag's unmodelled residual), and from
// contact_from_s for 3 s a load of contact_nm on joint 1, which bends the shaft.
std::vector<Row> FreeMotionWithInternalTorque(double contact_nm, double contact_from_s,
                                              unsigned seed) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Row> rows;
  const double depth = 0.15;
  for (int k = 0; k < int(30 * kRate); ++k) {
    const double t = k / kRate;
    Row r;
    r.sample.time_s = t;
    r.sample.insertion_depth_m = depth;
    const Eigen::Vector2d w(2 * kPi * 0.35, 2 * kPi * 0.22);
    const Eigen::Vector2d a(0.45, 0.3);
    r.truth << a[0] * std::sin(w[0] * t), a[1] * std::sin(w[1] * t + 0.5);
    const Eigen::Vector2d velocity(a[0] * w[0] * std::cos(w[0] * t),
                                   a[1] * w[1] * std::cos(w[1] * t + 0.5));
    const Eigen::Vector2d acceleration = -w.cwiseProduct(w).cwiseProduct(r.truth);
    const bool contact = t >= contact_from_s && t < contact_from_s + 3.0;
    for (int j = 0; j < 2; ++j) {
      const auto& jp = p.joints[j];
      const double load = (contact && j == 0) ? contact_nm : 0.0;
      const double internal = testing::ArmTorqueNm(acceleration[j], velocity[j]);
      const double bend = load != 0.0 ? jp.backlash_rad * std::copysign(1.0, load) +
                                            models::ComplianceAt(jp, depth) * load
                                      : 0.0;
      r.sample.encoder_rad[j] = r.truth[j] + bend + o.encoder_noise_rad * normal(rng);
      r.sample.effort_nm[j] = models::BiasTorqueAt(jp, r.sample.encoder_rad[j], depth) +
                              internal + load + o.effort_noise_nm * normal(rng);
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(FilterContact, FreeMotionIsNotCorrectedByTheArmsOwnTorque) {
  const auto rows = FreeMotionWithInternalTorque(0.0, 1e9, 1);
  ComplianceFilter filter(models::testing::PaperParameters());
  std::vector<double> correction;
  int within_two_sd = 0;
  for (const Row& r : rows) {
    const FilterEstimate e = filter.Step(r.sample);
    correction.push_back(e.tip_correction_mm);
    within_two_sd += e.tip_correction_mm <= 2.0 * e.tip_correction_sd_mm;
  }
  std::nth_element(correction.begin(), correction.begin() + correction.size() / 2,
                   correction.end());
  // Issue 26 item 5's acceptance on the real bag: median ≤ 0.3 mm, ≥ 95 % within 2σ.
  EXPECT_LE(correction[correction.size() / 2], 0.3);
  EXPECT_GE(within_two_sd, 0.95 * double(rows.size()));
}

TEST(FilterContact, AContactBeyondTheArmsOwnTorqueIsStillCorrected) {
  const auto rows = FreeMotionWithInternalTorque(0.8, 12.0, 2);
  ComplianceFilter filter(models::testing::PaperParameters());
  double worst = 0.0, sure = 1.0;
  for (const Row& r : rows) {
    const FilterEstimate e = filter.Step(r.sample);
    // From 0.3 s into the 3 s contact to its end.
    if (r.sample.time_s >= 12.3 && r.sample.time_s < 15.0) {
      worst = std::max(worst, std::abs(e.corrected_rad[0] - r.truth[0]));
      sure = std::min(sure, e.contact_probability[0]);
    }
  }
  // The tip slides with the arm: no pair window finds the load following a
  // bend (each costs log 2), and the level counts once per window (measured:
  // the least sure row 0.957).
  EXPECT_GT(sure, 0.95);
  // The deflection is 0.8 N·m · K + δ ≈ 59 mrad; left: the friction's share of
  // the load (≤ 0.1 N·m, 6 mrad) and the shaft's place.
  EXPECT_LT(worst, 0.008);
}

// A push without the hint: the tip rests for 0.5 s, then a load of 0.8 N·m,
// mostly on joint 1 (0.8·cos 0.3 / 0.8·sin 0.3), grows over 1 s and holds for
// 1.5 s. While it grows the encoders move by the bending alone, which is no
// free motion.
struct PushOutcome {
  double recognised_s = 1e9;               // first time both joints' p > 0.99
  Eigen::Vector2d recognised_error_rad{0, 0};       // the filter's error then
  Eigen::Vector2d recognised_deflection_rad{0, 0};  // and the encoders'
  Eigen::Vector2d hold_worst_rad{0, 0};    // from 0.5 s into the hold
  Eigen::Vector2d loaded_rms_rad{0, 0};    // from the push's start: the filter's
  Eigen::Vector2d equation2_rms_rad{0, 0};  // and equation (2)'s
};

// The arm's own torque (testing::ArmTorqueNm) on a moving motor, its angle
// tip + b + K(L)·τ noise-free.
void AddArmTorque(const models::ModelParameters& p, double depth, const Eigen::Vector2d& tip,
                  const Eigen::Vector2d& backlash, const Eigen::Vector2d& load, double rate_hz,
                  Eigen::Matrix2d* motor, FilterSample* s) {
  for (int j = 0; j < 2; ++j) {
    const double angle = tip[j] + backlash[j] + models::ComplianceAt(p.joints[j], depth) * load[j];
    const double speed = (angle - (*motor)(j, 0)) * rate_hz;
    const double acceleration = (speed - (*motor)(j, 1)) * rate_hz;
    (*motor)(j, 0) = angle, (*motor)(j, 1) = speed;
    s->effort_nm[j] += testing::ArmTorqueNm(acceleration, speed);
  }
}

// step_s > 0: the load grows in steps, each a 50 ms move and a hold (the
// clamped-beam protocol's stepping motor), step_s apart, and the motor's
// motion puts the arm's own torque into the effort (AddArmTorque).
PushOutcome Push(unsigned seed, double rate_hz = kRate, double ramp_s = 1.0, double peak_nm = 0.8,
                 double angle_rad = 0.3, double step_s = 0.0) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  ComplianceFilter filter(p);
  const ComplianceCorrector equation2(p, CorrectionModel::kPaper);
  const double depth = 0.15;
  const Eigen::Vector2d tip(0.1, -0.2),
      push(peak_nm * std::cos(angle_rad), peak_nm * std::sin(angle_rad));
  Eigen::Vector2d backlash = Eigen::Vector2d::Zero();
  Eigen::Matrix2d motor = Eigen::Matrix2d::Zero();  // columns: the motors' angle and speed
  motor.col(0) = tip;
  PushOutcome out;
  int loaded = 0;
  const double end_s = 2.0 + ramp_s;
  for (int k = 0; k < int(end_s * rate_hz); ++k) {
    const double t = k / rate_hz;
    double pushed_s = t - 0.5;
    if (step_s > 0.0 && pushed_s > 0.0) {
      const double steps = std::floor(pushed_s / step_s);
      pushed_s = step_s * (steps + std::min(1.0, (pushed_s - steps * step_s) / 0.05));
    }
    const Eigen::Vector2d load = push * std::clamp(pushed_s / ramp_s, 0.0, 1.0);
    FilterSample s =
        testing::PushedTipSample(p, o, t, depth, tip, load, 0.0, &backlash, &rng, &normal);
    if (step_s > 0.0) AddArmTorque(p, depth, tip, backlash, load, rate_hz, &motor, &s);
    const FilterEstimate e = filter.Step(s);
    if (e.contact_probability.minCoeff() > 0.99 && t < out.recognised_s) {
      out.recognised_s = t;
      out.recognised_error_rad = (e.corrected_rad - tip).cwiseAbs();
      out.recognised_deflection_rad = (s.encoder_rad - tip).cwiseAbs();
    }
    if (t >= end_s - 1.0) {
      out.hold_worst_rad = out.hold_worst_rad.cwiseMax((e.corrected_rad - tip).cwiseAbs());
    }
    if (t > 0.5) {
      const Eigen::Vector3d q(s.encoder_rad[0], s.encoder_rad[1], depth);
      const Eigen::Vector2d paper = equation2.Correct(q, s.effort_nm).corrected_rad;
      out.loaded_rms_rad += (e.corrected_rad - tip).cwiseAbs2();
      out.equation2_rms_rad += (paper - tip).cwiseAbs2();
      ++loaded;
    }
  }
  out.loaded_rms_rad = (out.loaded_rms_rad / loaded).cwiseSqrt();
  out.equation2_rms_rad = (out.equation2_rms_rad / loaded).cwiseSqrt();
  return out;
}

TEST(FilterContact, APushIsRecognisedWhileItsLoadGrowsAndCorrectedOnBothJoints) {
  // Joint 2's load, 0.24 N·m, alone is barely a contact: the tip's contact is
  // one for both joints. Measured: recognised at 0.88-0.97 s, the hold within
  // 0.2-0.3 / 0.1-0.2 mrad. With the encoder's speed as the arm's motion and a contact
  // per joint: joint 2 never recognised, the hold 8.5-8.8 / 15.7 mrad off.
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const PushOutcome r = Push(seed);
    EXPECT_LT(r.recognised_s, 1.3) << "seed " << seed;
    EXPECT_LT(r.hold_worst_rad[0], 2.5e-3) << "seed " << seed;
    EXPECT_LT(r.hold_worst_rad[1], 2.5e-3) << "seed " << seed;
  }
}

// A light push along joint 1 alone (0.35 N·m, the lightest of the family
// studies): joint 2's residual stays at its noise, and the contact's evidence
// must not charge it for that (ContactLogDensity: a load of any direction;
// docs/decisions/contact-scale-free-load.md). Measured, seeds 1-3:
// recognised at 1.27-1.45 s, the hold within 1.15-1.19 mrad (with each
// joint's slab N(0, σ_c²): 1.28-1.45 s, 0.90-1.06 mrad; here the paper's
// instrument and default noise, where the still joint's charge did not
// decide; on the family study's light pushes it did).
TEST(FilterContact, ALightPushAlongOneJointIsRecognised) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const PushOutcome r = Push(seed, kRate, 1.0, 0.35, 0.0);
    EXPECT_LT(r.recognised_s, 2.5) << "seed " << seed;
    EXPECT_LT(r.hold_worst_rad[0], 1.5e-3) << "seed " << seed;
  }
}

// The same push at 100 and 1500 Hz: a load's level, like the bias table's
// error, holds over many rows, so the rows of one pair window are one look at
// it; counted per row, the 1500 Hz log would believe a contact 15 times
// sooner on the same evidence. The hold's error is what the arm's learned
// torque took of the load: taught only once the chain could say the rows
// were free, little. Measured (seeds 1-2): recognised at 0.88-0.97 s /
// 0.93 s, the hold within 0.2-0.3 / 0.2 mrad; taught at once, the arm's
// Coulomb term took 0.09 N·m of the push and the hold was 1.4-1.5 / 3.8-4.0
// mrad off. Still missed: the onset. Until the contact is believed (the
// clearance's crossing looks like a free arm's motion) joint 1 is not
// corrected, and over the push its error is 7.0-7.4 mrad RMS against
// equation (2)'s 2.3; joint 2's, 2.2-2.9 against 5.5-5.6.
TEST(FilterContact, APushIsRecognisedAtTheSameLoadWhateverTheSampleRate) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const PushOutcome slow = Push(seed, 100.0), fast = Push(seed, 1500.0);
    EXPECT_NEAR(fast.recognised_s, slow.recognised_s, 0.2) << "seed " << seed;
    for (const PushOutcome& r : {slow, fast}) {
      EXPECT_LT(r.hold_worst_rad.maxCoeff(), 1.5e-3) << "seed " << seed;
      EXPECT_LT(r.loaded_rms_rad[1], r.equation2_rms_rad[1]) << "seed " << seed;
    }
  }
}

// The same load over 8 s (0.1 N·m/s): a 50 ms window sees 0.3 mrad of bend on
// joint 1, under a pair's effort noise, so a window lasts until the encoder
// has moved by four of its standard deviations as a bend (0.6 s here).
// Measured (seeds 1-2): recognised at 3.5-4.1 s (a load of 0.30-0.36 N·m),
// the hold within 2.2 / 0.5-0.6 mrad (the arm's torque learned some of
// the unrecognised load: its lesson waits 0.5 s only). Short of equation (2)
// on joint 1 (9.3-9.4 mrad RMS over the push against 3.3-3.4), better on
// joint 2 (2.9 against 7.9-8.0).
TEST(FilterContact, ASlowPushIsRecognisedByItsBend) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const PushOutcome r = Push(seed, 100.0, 8.0);
    EXPECT_LT(r.recognised_s, 5.0) << "seed " << seed;
    EXPECT_LT(r.hold_worst_rad.maxCoeff(), 3.5e-3) << "seed " << seed;
    EXPECT_LT(r.loaded_rms_rad[1], r.equation2_rms_rad[1]) << "seed " << seed;
  }
}

// The same slow load in steps 0.31 s apart at 1.5 kHz with the arm's own
// torque, as the full-rate clamped beam's motor makes it: a pair window must
// span steps, not one step or one hold, whose pair the arm torque's doubt
// over the change of motion (its Coulomb term switching) buries
// (docs/decisions/contact-pair-windows.md, WindowTravel). Measured (seeds
// 1-2): recognised at 1.56 s, the hold within 5.1-5.4 / 1.1-1.2 mrad, joint 1
// 5.7-5.9 mrad RMS over the push against equation (2)'s 10.4 (which carries
// the arm's torque), joint 2 1.7 against 8.1. With windows that close at
// the means' noise alone: recognised at 2.7-3.2 s, the hold 7.6-9.0 mrad
// off, joint 1 9.7-11.9.
TEST(FilterContact, ASteppedSlowPushIsRecognisedByItsBend) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const PushOutcome r = Push(seed, 1500.0, 8.0, 0.8, 0.3, 0.31);
    EXPECT_LT(r.recognised_s, 2.0) << "seed " << seed;
    EXPECT_LT(r.hold_worst_rad.maxCoeff(), 6.5e-3) << "seed " << seed;
    EXPECT_LT(r.loaded_rms_rad[0], 0.7 * r.equation2_rms_rad[0]) << "seed " << seed;
    EXPECT_LT(r.loaded_rms_rad[1], r.equation2_rms_rad[1]) << "seed " << seed;
  }
}

// A contact believed late brings the load and the tip its branch has
// followed since the push began (filter_impl.h, branch_gap), not the free
// tip's: the state is the mixture of the two, and the contact's is kept.
// Measured (seeds 1-3, 100 / 1500 Hz): when both joints are first 99 %
// sure, joint 1 is 9.0-9.9 / 11.3 mrad off of a 25.7 / 24.4 mrad
// deflection (the shaft's offset comes over the next rows); with one
// Gaussian collapsed after each effort (GPB1) 12.8-22.2 / 29.0-29.1 mrad
// off: uncorrected at 1500 Hz.
TEST(FilterContact, AContactBelievedLateBringsTheLoadItsBranchFollowed) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    for (double rate_hz : {100.0, 1500.0}) {
      const PushOutcome r = Push(seed, rate_hz);
      EXPECT_LT(r.recognised_error_rad[0], 0.48 * r.recognised_deflection_rad[0])
          << "seed " << seed << ", " << rate_hz << " Hz";
    }
  }
}

}  // namespace
}  // namespace pliant::estimation
