// pliant identify --effect NAME: a catalogue effect fitted with its σ into
// the parameters file, and `pliant correct` with that file closer to the
// truth on a log the identification never saw (docs/identification.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "loaded_rms_error.h"
#include "pliant/io/parameters_json.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

namespace fs = std::filesystem;
const std::string kCli = PLIANT_CLI;
const std::string kMyPliant = PLIANT_MY_PLIANT;
const std::string kSource = PLIANT_SOURCE_DIR;
const std::string kSweep = kSource + "/data/bias_sweep.csv";
// Hides deflection_coupling k12 = 0.006, k21 = 0.004 rad/(N·m) (data/README.md).
const std::string kHiddenLog = kSource + "/data/divot_hidden_effect.csv";

const models::EffectParameters* Find(const models::ModelParameters& p, const std::string& name) {
  for (const auto& e : p.effects) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

int CountName(const models::ModelParameters& p, const std::string& name) {
  int n = 0;
  if (p.covariance) {
    for (const auto& c : p.covariance->names) n += c == name ? 1 : 0;
  }
  return n;
}

// The fitted value lies within 3σ of the truth, and σ is neither zero nor a
// tenth of the value (a σ that small would make any bias look significant;
// one that large would say nothing).
void ExpectWithinSigma(const models::EffectParameters& e, std::size_t k, double truth) {
  ASSERT_GT(e.values.size(), k);
  const double value = e.values[k], sd = e.sd[k];
  EXPECT_GT(sd, 1e-3 * std::abs(truth)) << e.parameter_names[k];
  EXPECT_LT(sd, 0.1 * std::abs(truth)) << e.parameter_names[k];
  EXPECT_LT(std::abs(value - truth), 3.0 * sd)
      << e.parameter_names[k] << " = " << value << " ± " << sd << ", truth " << truth;
}

TEST(IdentifyEffect, RecoversTheHiddenCouplingAndCorrectsANewLogBetter) {
  const auto dir = FreshDirectory("identify_effect_loop");
  const auto base = RunIn(dir, kCli + " identify " + kSweep + " " + kHiddenLog + " -o base.json");
  ASSERT_EQ(base.exit_code, 0) << base.err;
  const auto with = RunIn(dir, kCli + " identify " + kSweep + " " + kHiddenLog +
                                   " --effect deflection_coupling -o with.json");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_NE(with.out.find("deflection_coupling: k12 = "), std::string::npos) << with.out;
  EXPECT_NE(with.out.find("with the effects"), std::string::npos) << with.out;
  EXPECT_EQ(with.out.find("do not inform it"), std::string::npos) << with.out;

  const auto written = io::ReadParameters((dir / "with.json").string());
  const auto* coupling = Find(written, "deflection_coupling");
  ASSERT_NE(coupling, nullptr);
  // Measured: k12 = 0.005973 ± 5.8e-05, k21 = 0.004012 ± 2.8e-05.
  ExpectWithinSigma(*coupling, 0, 0.006);
  ExpectWithinSigma(*coupling, 1, 0.004);
  // The covariance carries the effect's parameters, their variance its σ.
  ASSERT_TRUE(written.covariance);
  const auto& c = *written.covariance;
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string name = "deflection_coupling." + coupling->parameter_names[k];
    ASSERT_EQ(CountName(written, name), 1) << name;
    const auto i = std::find(c.names.begin(), c.names.end(), name) - c.names.begin();
    EXPECT_NEAR(std::sqrt(c.matrix(i, i)), coupling->sd[k], 1e-12 + 1e-9 * coupling->sd[k]);
  }
  EXPECT_TRUE(io::ReadParameters((dir / "base.json").string()).effects.empty());

  // Another log with the same instrument and effect, another seed and depth.
  const auto sim = RunIn(
      dir, kCli + " simulate " + kSource + "/experiments/scenarios/divot.json -o other.csv" +
               " --seed 5 --set log.every_n_periods=30 --set experiment.depths_m=[0.13]" +
               " --set 'hidden_effects={\"deflection_coupling\":{\"k12\":0.006,\"k21\":0.004}}'");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  // Measured: correct joint 1 2.379 -> 0.928, joint 2 1.797 -> 0.530 mrad;
  // the filter, which evaluates the file's deflection effect in its encoder
  // model, joint 1 0.413 -> 0.198, joint 2 0.225 -> 0.040 mrad.
  ExpectLoadedErrorFalls(dir, kCli, "correct", "base.json", "with.json", 0.7);
  ExpectLoadedErrorFalls(dir, kCli, "filter", "base.json", "with.json", 0.7);
}

// The real JHU clamps hold one row per pose: no joint moves while the tip is
// held, so nothing in them informs a friction. The file keeps its prior, and
// the output says so and where it can be fitted (real data:
// data/real/README.md).
TEST(IdentifyEffect, AnEffectTheLogCannotInformIsSaidToStayAtItsPrior) {
  const auto dir = FreshDirectory("identify_effect_uninformed");
  const std::string real = kSource + "/data/real/";
  const auto run = RunIn(dir, kCli + " identify " + real + "jhu2017_bias_j1.csv " + real +
                                  "jhu2017_clamped_j1.csv --effect joint_friction -o p.json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string text = run.out + run.err;
  EXPECT_NE(text.find("joint_friction: the held rows here do not inform it"), std::string::npos)
      << text;
  EXPECT_NE(text.find("--add joint_friction --write-params"), std::string::npos) << text;
  const auto written = io::ReadParameters((dir / "p.json").string());
  const auto* friction = Find(written, "joint_friction");
  ASSERT_NE(friction, nullptr);
  const auto& names = friction->parameter_names;
  const auto k = std::find(names.begin(), names.end(), "coulomb1") - names.begin();
  ASSERT_LT(std::size_t(k), names.size());
  EXPECT_NEAR(friction->values[k], 0.0, 1e-9);  // at its prior's 0
  EXPECT_GT(friction->sd[k], 0.05 / std::sqrt(2.0));
}

TEST(IdentifyEffect, AnUnknownNameExitsTwoAndWritesNothing) {
  const auto dir = FreshDirectory("identify_effect_unknown");
  std::ofstream(dir / "keep.json") << "keep me\n";
  const auto r = RunIn(dir, kCli + " identify " + kSweep + " " + kHiddenLog +
                                " --effect deflection_couplin -o keep.json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("pliant identify: --effect deflection_couplin: not in the catalogue — "
                        "one of: ", 0),
            0u)
      << r.err;
  EXPECT_NE(r.err.find("deflection_coupling"), std::string::npos) << "lists the known names";
  EXPECT_EQ(ReadText(dir / "keep.json"), "keep me\n");
  // The base model's own effects are not extra effects.
  const auto base = RunIn(dir, kCli + " identify " + kSweep + " --effect compliance -o x.json");
  EXPECT_EQ(base.exit_code, 2) << base.err;
  const auto twice = RunIn(dir, kCli + " identify " + kSweep +
                                    " --effect joint_friction --effect joint_friction -o x.json");
  EXPECT_EQ(twice.exit_code, 2) << twice.err;
  EXPECT_NE(twice.err.find("--effect joint_friction: is given twice"), std::string::npos) << twice.err;
  EXPECT_FALSE(fs::exists(dir / "x.json"));
}

TEST(IdentifyEffect, NoHeldTipToFitOnIsBadInput) {
  const auto dir = FreshDirectory("identify_effect_no_tip");
  const auto r = RunIn(dir, kCli + " identify " + kSweep + " --effect joint_friction -o x.json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("no log holds the tip"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.json"));
}

// A prior that already carries the effect (from an earlier identify or
// diagnose --write-params): refitted in place, not listed twice.
TEST(IdentifyEffect, AnEffectInThePriorIsRefittedNotDuplicated) {
  const auto dir = FreshDirectory("identify_effect_prior");
  const std::string logs = " " + kSweep + " " + kHiddenLog;
  ASSERT_EQ(RunIn(dir, kCli + " identify" + logs + " --effect deflection_coupling -o first.json")
                .exit_code, 0);
  const auto again = RunIn(dir, kCli + " identify" + logs +
                                    " --prior first.json --effect deflection_coupling -o again.json");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto p = io::ReadParameters((dir / "again.json").string());
  ASSERT_EQ(p.effects.size(), 1u);
  EXPECT_EQ(CountName(p, "deflection_coupling.k12"), 1);
  ExpectWithinSigma(p.effects[0], 0, 0.006);
}

// examples/my_effect: a user's effect, registered in its own pliant, is
// identified like a built-in one; the plain pliant does not know it.
TEST(IdentifyEffect, AUsersOwnEffectIsIdentified) {
  const auto dir = FreshDirectory("identify_effect_user");
  const auto sim = RunIn(
      dir, kMyPliant + " simulate " + kSource + "/experiments/scenarios/divot.json -o one_sided.csv" +
               " --seed 3 --set log.every_n_periods=30 --set experiment.depths_m=[0.15]" +
               " --set experiment.peak_torques_nm=[1.0]" +
               " --set 'hidden_effects={\"one_sided_compliance\":{\"c1\":0.01,\"c2\":0.01}}'");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = RunIn(dir, kMyPliant + " identify " + kSweep +
                                " one_sided.csv --effect one_sided_compliance -o mine.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto p = io::ReadParameters((dir / "mine.json").string());
  const auto* mine = Find(p, "one_sided_compliance");
  ASSERT_NE(mine, nullptr);
  ExpectWithinSigma(*mine, 0, 0.01);
  ExpectWithinSigma(*mine, 1, 0.01);
  const auto plain = RunIn(dir, kCli + " identify " + kSweep +
                                    " one_sided.csv --effect one_sided_compliance -o plain.json");
  EXPECT_EQ(plain.exit_code, 2) << plain.err;
  EXPECT_FALSE(fs::exists(dir / "plain.json"));
}

}  // namespace
}  // namespace pliant::testing

namespace pliant::testing {
namespace {

// The real JHU 2017 joint 1 sweep and clamps (data/real/README.md): the
// quasi-static identification fits the clamps' held friction. An effect on
// the effort named with --effect sends the base through a second fit on the
// efforts without that effect; the held friction is the base's own and stays
// (it was taken out of the efforts with the named effect, and the second fit
// found none: 0.0001 against 0.09 N·m).
TEST(IdentifyEffect, TheSecondPassKeepsTheBasesOwnEffects) {
  const auto dir = FreshDirectory("identify_effect_second_pass");
  const std::string logs = " " + kSource + "/data/real/jhu2017_bias_j1.csv " + kSource +
                           "/data/real/jhu2017_clamped_j1.csv";
  ASSERT_EQ(RunIn(dir, kCli + " identify --quiet" + logs + " -o base.json").exit_code, 0);
  const auto r = RunIn(dir, kCli + " identify --quiet" + logs +
                                " --effect bias_torque_depth -o with.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto base = io::ReadParameters((dir / "base.json").string());
  const auto with = io::ReadParameters((dir / "with.json").string());
  const auto* held_base = Find(base, "held_friction");
  const auto* held_with = Find(with, "held_friction");
  ASSERT_NE(held_base, nullptr);
  ASSERT_NE(held_with, nullptr);
  ASSERT_NE(Find(with, "bias_torque_depth"), nullptr);
  ASSERT_GT(held_base->values[0], 0.05);
  EXPECT_NEAR(held_with->values[0], held_base->values[0], 0.25 * held_base->values[0]);
}

}  // namespace
}  // namespace pliant::testing
