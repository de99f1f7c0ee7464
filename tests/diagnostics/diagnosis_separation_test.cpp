// The experiment that separates two candidates, computed from their
// predictions: against closed forms on hand-made terms.
#include <gtest/gtest.h>

#include "../../estimation/src/diagnosis_internal.h"
#include "diagnosis_support.h"

namespace pliant::estimation::diagnosis {
namespace {

// One compared sample at 0.15 m, t seconds in, 100 mm per rad on the joints
// it uses.
Problem OneSample(double time_s, bool joint1 = true, bool joint2 = true) {
  Problem problem;
  problem.joint_recorded[0] = joint1, problem.joint_recorded[1] = joint2;
  Sample s;
  s.state.insertion_depth_m = 0.15;
  s.state.time_s = time_s;
  s.used = {joint1, joint2};
  s.mm_per_rad = {joint1 ? 100.0 : 0.0, joint2 ? 100.0 : 0.0};
  problem.samples = {s};
  return problem;
}

Term Fitted(const std::string& name, std::vector<double> parameters) {
  std::shared_ptr<const EffectModel> effect = EffectCatalogue::Global().Create(name);
  return {effect, std::move(parameters), name, {}, {}};
}

// k12 = 5 mrad/(N·m) moves joint 1 only when joint 2 is loaded; the other
// candidate (gamma 0) predicts nothing. The largest gap against a hold of
// joint 1 at +1 N·m is a hold of joint 2 at the largest load tried, 2 N·m:
// 0.005 · 2 rad × 100 mm/rad = 1 mm.
TEST(SeparatingExperiment, NamesTheConditionWhereThePredictionsDifferMost) {
  const BaseModel model(testing::ModelOf(testing::ShortDivot("{}")));
  const Problem problem = OneSample(20.0);
  const Term coupling = Fitted("deflection_coupling", {0.005, 0.0});
  const Term cubic = Fitted("load_dependent_compliance", {0.0, 0.0, 0.0, 0.0});
  const std::string text = SeparatingExperiment(problem, model, {}, coupling, cubic);
  EXPECT_NE(text.find("joint 2 to -2.0 N·m"), std::string::npos) << text;
  EXPECT_NE(text.find("deflection_coupling predicts 1.000 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("load_dependent_compliance 0.000 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("they differ by 1.000 mm"), std::string::npos) << text;
}

// A log of poses with joint 2 alone recorded (a real one-joint clamp): the
// experiment loads joint 2, holds, and names no time (its t is a pose index).
TEST(SeparatingExperiment, OnALogOfPosesItHoldsARecordedJointAndNamesNoTime) {
  const BaseModel model(testing::ModelOf(testing::ShortDivot("{}")));
  Problem problem = OneSample(300.0, false, true);
  problem.quasi_static = true;
  const Term cubic = Fitted("load_dependent_compliance", {0.0, 0.056, 0.0, 0.0});
  const Term none = Fitted("load_dependent_compliance", {0.0, 0.0, 0.0, 0.0});
  const std::string text = SeparatingExperiment(problem, model, {}, cubic, none);
  EXPECT_EQ(text.rfind("hold joint 2 to ", 0), 0u) << text;
  EXPECT_EQ(text.find("into the log"), std::string::npos) << text;
  EXPECT_EQ(text.find("joint 1"), std::string::npos) << text;
}

// An effort drift (r·(1 − e^(−kt))/k: r = 0.0025 N·m/s, k = 1/(20 s), so
// settling at 0.05 N·m) against no effect:
// the largest gap is the latest time tried, where joint 1's offset has
// settled: relative to mid-log (t = 10 s) the drift changes joint 1's
// deflection by K1(L)·0.05·e^(−0.5), at the depth of the largest K.
TEST(SeparatingExperiment, ADriftIsSeparatedByHoldingLonger) {
  const BaseModel model(testing::ModelOf(testing::ShortDivot("{}")));
  const Problem problem = OneSample(20.0);
  const Term drift = Fitted("effort_drift", {0.0025, 0.0, 0.05});
  const Term none = Fitted("effort_drift", {0.0, 0.0, 0.05});
  const std::string text = SeparatingExperiment(problem, model, {}, drift, none);
  EXPECT_NE(text.find("600 s into the log"), std::string::npos) << text;
}

}  // namespace
}  // namespace pliant::estimation::diagnosis
