// A take-up that absorbed a stiffening. The parameters an identification
// would give on a log whose compliance stiffens under load: the clearance taken
// up over a wide load, δ wider and K lower than the truth's — the best such
// curve through the truth's load-deflection curve. The diagnosis compares only
// loads beyond that take-up and, without the probe, names nothing; the probe
// compares the loads inside it and names the stiffening. Given the same wide
// take-up on a log with nothing hidden, the probe stays quiet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include <Eigen/Dense>

#include "diagnosis_support.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/effect_fit.h"
#include "pliant/models/smooth.h"

namespace pliant::testing {
namespace {

constexpr double kWideTakeUpNm = 0.6;  // 6 / 3 × the paper's tau_min (0.1 / 0.2 N·m)

// The second generator's stiffening (experiments/second_generator): K/(1 + 0.35|τ|).
constexpr double kStiffeningPerNm = 0.35;
// Its clearance taken up along δ·tanh(τ/0.06 N·m).
constexpr double kTanhTakeUpNm = 0.06;

// Deflection (rad) of a joint at load tau: the clearance and its compliance
// law at depth L, stiffening or not.
double Deflection(const models::JointParameters& joint, double depth_m, double tau,
                  bool stiffening) {
  const double k = models::ComplianceAt(joint, depth_m);
  return joint.backlash_rad * std::tanh(tau / kTanhTakeUpNm) +
         k * tau / (stiffening ? 1.0 + kStiffeningPerNm * std::abs(tau) : 1.0);
}

// The truth's joints with the clearance taken up over kWideTakeUpNm: δ' and
// K's scale c the least-squares fit of δ'·S(τ/w') + c·K·τ to the truth's
// curve over 0 … `reach` N·m at the middle depth (what an identification on
// clamps to `reach` does with a law that lacks the curve's bend).
using Curve = std::function<double(const models::JointParameters&, double tau)>;

models::ModelParameters Absorbed(const models::ModelParameters& truth, const Curve& curve,
                                 double reach) {
  models::ModelParameters p = truth;
  for (int j = 0; j < 2; ++j) {
    auto& joint = p.joints[j];
    const double k = models::ComplianceAt(joint, 0.15);
    Eigen::MatrixXd x(100, 2);
    Eigen::VectorXd y(100);
    for (int i = 0; i < 100; ++i) {
      const double tau = reach * (i + 1) / 100.0;
      x(i, 0) = models::SmoothSaturation(tau / kWideTakeUpNm);
      x(i, 1) = k * tau;
      y(i) = curve(truth.joints[j], tau);
    }
    const Eigen::Vector2d fit = x.colPivHouseholderQr().solve(y);
    joint.backlash_rad = fit[0];
    joint.deadzone_width_nm = kWideTakeUpNm;
    models::ScaleCompliance(joint.compliance, fit[1]);
  }
  return p;
}

// The simulator's held-tip pushes with the encoders rewritten to the second
// generator's physics: q = q_ref + Deflection(τ_ext) where the tracker sees
// the tip, τ_ext the measured effort less the model's bias, plus 0.2 mrad of
// encoder-side noise (the tracker's own noise cancels in q − q_ref).
io::Log WithDeflection(io::Log log, const models::ModelParameters& truth, bool stiffening) {
  const io::StandardColumns c(log.header);
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 2e-4);
  const int q[2] = {c.q1, c.q2}, tau[2] = {c.tau1, c.tau2}, ref[2] = {c.q1_ref, c.q2_ref};
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    double* row = &log.values[r * log.Columns()];
    if (!std::isfinite(row[ref[0]]) || !std::isfinite(row[ref[1]])) continue;
    const double depth = row[c.q3];
    for (int j = 0; j < 2; ++j) {
      const double load = row[tau[j]] - models::BiasTorqueAt(truth.joints[j], row[q[j]], depth);
      row[q[j]] = row[ref[j]] + Deflection(truth.joints[j], depth, load, stiffening) + noise(random);
    }
  }
  return log;
}

const std::string* ProbeNote(const estimation::Diagnosis& d) {
  for (const auto& note : d.notes) {
    std::printf("  note: %s\n", note.c_str());
    if (note.find("beyond e × tau_min") != std::string::npos) return &note;
  }
  return nullptr;
}

void ExpectAbsorbed(const models::ModelParameters& absorbed, const models::ModelParameters& truth) {
  for (int j = 0; j < 2; ++j) {
    const auto& t = truth.joints[j];
    const double k_ratio =
        models::ComplianceAt(absorbed.joints[j], 0.15) / models::ComplianceAt(t, 0.15);
    std::printf("  joint %d: δ %.2f mrad (truth %.2f), K × %.3f at 0.15 m, take-up %.2f N·m\n",
                j + 1, 1e3 * absorbed.joints[j].backlash_rad, 1e3 * t.backlash_rad, k_ratio,
                absorbed.joints[j].deadzone_width_nm);
    // What an identification absorbs a stiffening into: δ wider, K lower.
    EXPECT_GT(absorbed.joints[j].backlash_rad, t.backlash_rad + 1e-3);
    EXPECT_LT(k_ratio, 0.95);
  }
}

// The second generator's curve at the middle depth, stiffening or not.
Curve Generators(bool stiffening) {
  return [stiffening](const models::JointParameters& joint, double tau) {
    return Deflection(joint, 0.15, tau, stiffening);
  };
}

// The simulator's own: a dead zone over the paper's widths, γ·τ³ (rad/(N·m)³).
constexpr double kGamma = -0.006;
constexpr const char* kCubic = R"({"load_dependent_compliance":{"gamma1":-0.1,"gamma2":-0.17}})";
double Cubic(const models::JointParameters& joint, double tau) {
  const double w = std::max(joint.deadzone_width_nm, joint.tau_min_nm);
  return joint.backlash_rad * models::SmoothSaturation(tau / w) +
         models::ComplianceAt(joint, 0.15) * tau + kGamma * tau * tau * tau;
}

// Three depths, eight directions: 24 pushes of the held tip to 1 N·m, the
// encoders rewritten to the second generator's stiffening, and the parameters
// that absorbed it.
struct StiffeningCase {
  models::ModelParameters truth, absorbed;
  io::Log log;
};
StiffeningCase Stiffening() {
  const auto scenario = ShortDivot("{}", {"experiment.depths_m=[0.10,0.15,0.20]",
                                          "experiment.directions_deg=[0,45,90,135,180,225,270,315]"});
  StiffeningCase c;
  c.truth = ModelOf(scenario);
  c.log = WithDeflection(experiments::Simulate(scenario, 7).log, c.truth, true);
  c.absorbed = Absorbed(c.truth, Generators(true), 1.0);
  return c;
}

TEST(DiagnoseTakeUp, AStiffeningAbsorbedAsAWideTakeUpIsNamed) {
  const StiffeningCase c = Stiffening();
  const models::ModelParameters& truth = c.truth;
  const io::Log& log = c.log;
  const models::ModelParameters& absorbed = c.absorbed;
  ExpectAbsorbed(absorbed, truth);
  estimation::DiagnoseOptions without;
  without.probe_wide_take_up = false;
  const auto before = estimation::Diagnose(log, "divot.csv", absorbed, without);
  std::printf("  without the probe: missing %s\n",
              before.missing_effect ? before.missing_effect->c_str() : "none");
  EXPECT_NE(before.missing_effect.value_or(""), "load_dependent_compliance");

  const auto d = estimation::Diagnose(log, "divot.csv", absorbed, {});
  const std::string* note = ProbeNote(d);
  ASSERT_NE(note, nullptr);
  EXPECT_NE(note->find("load_dependent_compliance absorbed"), std::string::npos);
  ASSERT_TRUE(d.missing_effect.has_value());
  EXPECT_EQ(*d.missing_effect, "load_dependent_compliance");
  ASSERT_FALSE(d.effects.empty());
  const auto& found = d.effects.front();
  EXPECT_EQ(found.name, "load_dependent_compliance");
  EXPECT_GE(found.score, 0.15);
  EXPECT_LT(found.p_value, 0.05);
  // The bend of the stiffening's sign: K is refitted up with it, so the
  // effect's slope at half a N·m, 2β|τ| + 3γτ², is negative.
  ASSERT_EQ(found.parameters.size(), 4u);
  for (int j = 0; j < 2; ++j)
    EXPECT_LT(2.0 * found.parameters[2 + j] * 0.5 + 3.0 * found.parameters[j] * 0.25, 0.0) << j;
  EXPECT_EQ(d.selected.front(), "load_dependent_compliance");
}

// Added (`--add`), the stiffening is fitted as the probe compares it: with the
// take-up refitted from a clearance's, on the loads from twice tau_min. The
// held-out error falls by more than half, and the parameters written take
// the clearance up over a clearance's width again (under 0.6 / e N·m).
TEST(DiagnoseTakeUp, AddedOnAWideTakeUpTheStiffeningIsFittedWithTheTakeUpRefitted) {
  const StiffeningCase c = Stiffening();
  const models::ModelParameters& truth = c.truth;
  const io::Log& log = c.log;
  const models::ModelParameters& absorbed = c.absorbed;
  estimation::DiagnoseOptions options;
  options.added_effects = {"load_dependent_compliance"};
  const auto d = estimation::Diagnose(log, "divot.csv", absorbed, options);
  std::printf("  held out %.4f -> %.4f mm\n", d.rms_before_mm, d.rms_after_mm);
  EXPECT_LT(d.rms_after_mm, 0.5 * d.rms_before_mm);
  ASSERT_TRUE(d.recalibration.has_value());
  ASSERT_EQ(d.recalibration->parameters.size(), 8u);  // scale, δ, tilt, width per joint
  const auto written = estimation::WithDiagnosedEffects(absorbed, d, "divot.csv");
  for (int j = 0; j < 2; ++j) {
    std::printf("  joint %d: width %.3f N·m, δ %.2f mrad (truth %.2f)\n", j + 1,
                written.joints[j].deadzone_width_nm, 1e3 * written.joints[j].backlash_rad,
                1e3 * truth.joints[j].backlash_rad);
    EXPECT_LT(written.joints[j].deadzone_width_nm, kWideTakeUpNm / std::exp(1.0)) << j;
  }
}

// Twelve pushes are too few to tell: the diagnosis says so and names the push
// that would, from both fitted curves; what the wide take-up made look
// missing on the loads beyond it (backlash_depth) is no longer called so.
// `pliant identify --effect` fits it the same way on the held-tip rows: the
// error falls by more than half from the parameters as given, and the width
// is a clearance's again.
TEST(DiagnoseTakeUp, IdentifiedWithTheEffectTheTakeUpIsRefittedAsWhenAdded) {
  const StiffeningCase c = Stiffening();
  const auto fit = estimation::FitEffectsOnLogs({{&c.log, "divot.csv"}}, c.absorbed,
                                                {"load_dependent_compliance"}, {});
  std::printf("  held out %.4f as given, %.4f with the effect\n", fit.rms_given_mm,
              fit.rms_with_effects_mm);
  EXPECT_LT(fit.rms_with_effects_mm, 0.5 * fit.rms_given_mm);
  ASSERT_TRUE(fit.fitted.recalibration.has_value());
  const auto written = estimation::WithFittedEffects(c.absorbed, fit.fitted, "identify");
  for (int j = 0; j < 2; ++j)
    EXPECT_LT(written.joints[j].deadzone_width_nm, kWideTakeUpNm / std::exp(1.0)) << j;
}

// Four pushes (two directions, two depths): every held-out segment gains
// from the stiffening the take-up absorbed, so it is named. Asked for a
// significance these few segments cannot reach, the probe says instead that
// the log cannot tell, and names the push that would.
TEST(DiagnoseTakeUp, OnAShortLogItNamesTheStiffeningOrSaysItCannotTellAndNamesThePush) {
  const auto scenario = ShortDivot(kCubic, {"experiment.directions_deg=[0,90]"});
  const io::Log log = experiments::Simulate(scenario, 7).log;
  const models::ModelParameters absorbed = Absorbed(ModelOf(scenario), Cubic, 1.0);
  ExpectAbsorbed(absorbed, ModelOf(scenario));
  const auto named = estimation::Diagnose(log, "divot.csv", absorbed, {});
  EXPECT_EQ(named.missing_effect.value_or("none"), "load_dependent_compliance");
  ASSERT_NE(ProbeNote(named), nullptr);
  EXPECT_NE(ProbeNote(named)->find("load_dependent_compliance absorbed, and it is called missing"),
            std::string::npos);
  estimation::DiagnoseOptions strict;
  strict.family_significance = 1e-12;
  const auto d = estimation::Diagnose(log, "divot.csv", absorbed, strict);
  const std::string* note = ProbeNote(d);
  ASSERT_NE(note, nullptr);
  EXPECT_NE(note->find("this log cannot tell the take-up as refitted from "
                       "load_dependent_compliance; push joint"),
            std::string::npos);
  EXPECT_NE(note->find("predict deflections"), std::string::npos);
  EXPECT_FALSE(d.missing_effect.has_value()) << *d.missing_effect;
}

TEST(DiagnoseTakeUp, AWideTakeUpGivenOnALogWithNothingHiddenNamesNothing) {
  const auto scenario = ShortDivot("{}");
  const io::Log log = experiments::Simulate(scenario, 7).log;
  const models::ModelParameters wide = Absorbed(ModelOf(scenario), Generators(false), 1.0);
  const auto d = estimation::Diagnose(log, "divot.csv", wide, {});
  const std::string* note = ProbeNote(d);
  ASSERT_NE(note, nullptr);  // the probe ran, and said what it compared
  EXPECT_NE(note->find("no candidate adds to the take-up as refitted"), std::string::npos);
  EXPECT_FALSE(d.missing_effect.has_value()) << *d.missing_effect;
  for (const auto& f : d.effects) EXPECT_FALSE(f.missing) << f.name;
}

}  // namespace
}  // namespace pliant::testing
