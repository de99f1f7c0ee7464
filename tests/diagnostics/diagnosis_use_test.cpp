// Diagnose() beyond the catalogue: an error driven by an auxiliary column no
// effect uses (found by the channel ranking), refitting with --add, a user's
// own effect joining the ranking, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnosis_support.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/effect_catalogue.h"
#include "pliant/io/input_error.h"

namespace pliant::testing {
namespace {

using estimation::Diagnose;
using estimation::Diagnosis;

// A copy of `log` with one more column.
io::Log WithColumn(const io::Log& log, const std::string& name, const std::vector<double>& column) {
  io::Log out;
  out.header = log.header;
  out.header.AddColumn(name);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    for (std::size_t c = 0; c < log.Columns(); ++c) out.values.push_back(log.Value(r, c));
    out.values.push_back(column[r]);
  }
  return out;
}

TEST(DiagnoseChannels, AnAuxiliaryColumnThatDrivesTheErrorRanksFirst) {
  // A motor temperature that oscillates (an air-conditioning cycle of 5.3 s)
  // and bends joint 1's reading by 0.8 mrad/°C: no catalogue effect uses it.
  const auto scenario = ShortDivot("{}");
  io::Log log = experiments::Simulate(scenario, 3).log;
  const auto t = log.Column("t");
  std::vector<double> temperature(t.size());
  const int q1 = log.header.Index("q1");
  for (std::size_t r = 0; r < t.size(); ++r) {
    temperature[r] = 35.0 + 2.0 * std::sin(2.0 * M_PI * t[r] / 5.3);
    log.values[r * log.Columns() + q1] += 0.8e-3 * (temperature[r] - 35.0);
  }
  log = WithColumn(log, "motor_temp_c", temperature);
  const Diagnosis d = Diagnose(log, "divot.csv", ModelOf(scenario), {});
  for (std::size_t i = 0; i < 4 && i < d.channels.size(); ++i) {
    const auto& c = d.channels[i];
    std::printf("  %-14s joint %d lag %3d explains %.3f  p %.2g  %s\n", c.name.c_str(), c.joint,
                c.lag, c.score, c.p_value, c.finding.c_str());
  }
  ASSERT_FALSE(d.channels.empty());
  const auto& first = d.channels.front();
  EXPECT_EQ(first.name, "motor_temp_c");
  EXPECT_EQ(first.joint, 1);
  EXPECT_LE(std::abs(first.lag), 2);
  EXPECT_GT(first.score, 0.6);
  EXPECT_LT(first.p_value, 1e-6);
  // Slow channels (t, segment, a joint angle that steps with the pushes)
  // explain part of any slow error; the driving column explains clearly more.
  EXPECT_GT(first.score, d.channels[1].score + 0.1);
  EXPECT_NE(first.finding.find("joint 1 reads"), std::string::npos);
  EXPECT_FALSE(d.missing_effect.has_value()) << *d.missing_effect;
}

TEST(DiagnoseAdd, RefittingWithTheMissingEffectRemovesIt) {
  const auto scenario = ShortDivot(R"({"joint_friction":{"coulomb1":0.05,"coulomb2":0.05}})");
  const io::Log log = experiments::Simulate(scenario, 5).log;
  estimation::DiagnoseOptions options;
  options.added_effects = {"joint_friction"};
  const Diagnosis d = Diagnose(log, "divot.csv", ModelOf(scenario), options);
  std::printf("  rms before %.4f mm, with joint_friction refitted %.4f mm, missing %s\n",
              d.rms_before_mm, d.rms_after_mm, d.missing_effect ? d.missing_effect->c_str() : "none");
  EXPECT_EQ(d.added_effects, options.added_effects);
  EXPECT_LE(d.rms_after_mm, 0.5 * d.rms_before_mm);
  EXPECT_FALSE(d.missing_effect.has_value());
  for (const auto& f : d.effects) EXPECT_NE(f.name, "joint_friction");
  EXPECT_LT(d.after.rms_mm, 0.5 * d.before.rms_mm);
}

// The effects a parameters file holds are part of the model the diagnosis
// compares, as in every other consumer: a log with joint friction, diagnosed
// with the friction in the file at the simulator's values, leaves no more
// than the control's error, names nothing and does not offer the friction
// again; the same file without it leaves twice that.
TEST(DiagnoseFileEffects, AnEffectTheFileHoldsIsPartOfTheModel) {
  const auto scenario = ShortDivot(R"({"joint_friction":{"coulomb1":0.05,"coulomb2":0.05}})");
  const io::Log log = experiments::Simulate(scenario, 5).log;
  models::ModelParameters with = ModelOf(scenario);
  const auto friction = estimation::EffectCatalogue::Global().Create("joint_friction");
  models::EffectParameters held;
  held.name = "joint_friction";
  for (const auto& spec : friction->Parameters()) {
    held.parameter_names.push_back(spec.name);
    held.values.push_back(spec.name.rfind("coulomb", 0) == 0 ? 0.05 : spec.default_value);
    held.sd.push_back(0.0);
  }
  with.effects.push_back(held);
  const Diagnosis d = Diagnose(log, "divot.csv", with, {});
  const Diagnosis without = Diagnose(log, "divot.csv", ModelOf(scenario), {});
  std::printf("  rms before %.4f mm with the file's friction, %.4f mm without\n", d.rms_before_mm,
              without.rms_before_mm);
  EXPECT_FALSE(d.missing_effect.has_value());
  for (const auto& f : d.effects) EXPECT_NE(f.name, "joint_friction");
  EXPECT_LT(2.0 * d.rms_before_mm, without.rms_before_mm);
  EXPECT_NE(std::find_if(d.notes.begin(), d.notes.end(),
                         [](const std::string& n) { return n.find("hold joint_friction") != std::string::npos; }),
            d.notes.end());
}

// A user's effect: a shaft bent a little at rest straightens under load
// whichever way it is pushed — a deflection even in the load, a_j·tau_j².
struct EvenBend {
  static constexpr models::EffectInfo kInfo{
      "user_even_bend", models::Channel::kDeflection,
      "a shaft bent at rest straightens under load either way: a·tau²"};
  std::vector<models::ParameterSpec> Parameters() const {
    return {{"a1", "rad/(N·m)²", 0.0, -0.02, 0.02, 0.005},
            {"a2", "rad/(N·m)²", 0.0, -0.02, 0.02, 0.005}};
  }
  template <typename T>
  models::Vec2<T> operator()(const T* a, const models::JointState<T>& s) const {
    return {a[0] * s.external_torque_nm[0] * s.external_torque_nm[0],
            a[1] * s.external_torque_nm[1] * s.external_torque_nm[1]};
  }
};

TEST(DiagnoseExtension, AUserEffectJoinsTheCandidatesAndIsFound) {
  estimation::EffectCatalogue::Global().Add<EvenBend>();
  const auto names = estimation::CandidateEffectNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "user_even_bend"), names.end());
  const auto scenario = ShortDivot(R"({"user_even_bend":{"a1":0.003,"a2":0.003}})");
  const io::Log log = experiments::Simulate(scenario, 9).log;
  const Diagnosis d = Diagnose(log, "divot.csv", ModelOf(scenario), {});
  ASSERT_FALSE(d.effects.empty());
  std::printf("  best %s: held-out reduction %.3f, rms %.4f -> %.4f mm\n",
              d.effects[0].name.c_str(), d.effects[0].score, d.rms_before_mm, d.rms_after_mm);
  EXPECT_EQ(d.effects[0].name, "user_even_bend");
  ASSERT_TRUE(d.missing_effect.has_value());
  EXPECT_EQ(*d.missing_effect, "user_even_bend");
  EXPECT_GE(d.effects[0].score, 0.5);
}

// A log as a user might record it: no segment column and no velocities (the
// diagnosis differentiates the encoders and cuts time blocks for the folds).
TEST(DiagnoseInput, ALogWithoutSegmentsOrVelocitiesIsStillDiagnosed) {
  const auto scenario = ShortDivot(R"({"joint_friction":{"coulomb1":0.05,"coulomb2":0.05}})");
  const io::Log full = experiments::Simulate(scenario, 4).log;
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "q1_ref", "q2_ref"};
  for (std::size_t r = 0; r < full.Rows(); ++r) {
    for (const auto& name : log.header.columns)
      log.values.push_back(full.Value(r, full.header.Index(name)));
  }
  const Diagnosis d = Diagnose(log, "recorded.csv", ModelOf(scenario), {});
  std::printf("  best %s: held-out reduction %.3f, rms %.4f -> %.4f mm\n",
              d.effects[0].name.c_str(), d.effects[0].score, d.rms_before_mm, d.rms_after_mm);
  EXPECT_EQ(d.reference, "q*_ref");
  EXPECT_EQ(d.missing_effect.value_or("none"), "joint_friction");
  EXPECT_GE(d.effects[0].score, 0.5);
}

TEST(DiagnoseInput, ALogWithoutAReferenceOrAnUnknownEffectIsAnInputError) {
  const auto scenario = ShortDivot("{}");
  const io::Log log = experiments::Simulate(scenario, 1).log;
  io::Log bare;  // t, q1, q2, q3, tau1, tau2 only
  bare.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    for (const auto& name : bare.header.columns)
      bare.values.push_back(log.Value(r, log.header.Index(name)));
  }
  try {
    Diagnose(bare, "bare.csv", ModelOf(scenario), {});
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), "bare.csv");
    EXPECT_NE(e.problem().find("no tip_fixed rows"), std::string::npos) << e.problem();
  }
  estimation::DiagnoseOptions options;
  options.added_effects = {"friction"};
  try {
    Diagnose(log, "divot.csv", ModelOf(scenario), options);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.problem(), "no effect named 'friction'");
    EXPECT_NE(e.fix().find("joint_friction"), std::string::npos) << e.fix();
  }
}

}  // namespace
}  // namespace pliant::testing
