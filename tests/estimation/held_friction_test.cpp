// The held-friction effect through the catalogue: its Jacobian check away
// from a reversal, and pliant correct's use of it from a parameters file.
#include <cmath>

#include <gtest/gtest.h>

#include "filter_synthetic.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/estimation/filter.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/jacobian_check.h"
#include "pliant/models/travel_since_reversal.h"

namespace pliant::estimation {
namespace {

TEST(HeldFriction, JacobianCheckPassesAwayFromAReversal) {
  const auto effect = EffectCatalogue::Global().Create("held_friction");
  models::JointState<double> s;
  s.encoder_angle_rad << 0.31, -0.27;
  s.insertion_depth_m = 0.143;
  s.travel_since_reversal_rad << 0.003, -0.0011;
  const auto result = CheckEffectJacobians(*effect, {0.1, 0.08, 0.002}, s);
  EXPECT_TRUE(result.ok) << result.Report();
  // d tau1 / d F1 = z(0.003) = 1 − 2·exp(−1.5).
  EXPECT_NEAR(result.autodiff(0, 0), 1.0 - 2.0 * std::exp(-1.5), 1e-12);
}

TEST(HeldFriction, CorrectRemovesItFromTheEffortBeforeReadingTheLoad) {
  auto parameters = PaperPrior();
  for (auto& joint : parameters.joints) joint.backlash_rad = 0.0, joint.tau_min_nm = 0.0;
  const ComplianceCorrector paper(parameters, CorrectionModel::kPaper);
  parameters.effects = {{"held_friction",
                         {"held_friction1", "held_friction2", "presliding_travel"},
                         {0.1, 0.0, 0.002},
                         {0.0, 0.0, 0.0}}};
  const ComplianceCorrector with(parameters, CorrectionModel::kPaper);
  const Eigen::Vector3d q(0.01, 0.0, 0.15);
  const Eigen::Vector2d tau(0.5, 0.0), travel(0.02, 0.0);  // long after a reversal: z ≈ 1
  const double k1 = models::ComplianceAt(parameters.joints[0], 0.15);
  const double z = 1.0 - 2.0 * std::exp(-10.0);
  EXPECT_NEAR(with.Correct(q, tau, travel).corrected_rad[0] -
                  paper.Correct(q, tau).corrected_rad[0],
              k1 * 0.1 * z, 1e-12);
}

// The filter takes the effect's torque out of each effort as correct does:
// a filter given the effect and the efforts equals, to rounding, a filter
// without it given the efforts less the effect's torque (the catalogue's,
// at the travel since the last reversal of the same encoder angles).
TEST(HeldFriction, TheFilterTakesItOutOfTheEffortAsCorrectDoes) {
  auto parameters = models::testing::PaperParameters();
  testing::SyntheticOptions so;
  so.duration_s = 3.0;
  const auto run = testing::MakeSyntheticRun(parameters, testing::ModelLogOptions(), so);
  const models::ModelParameters plain = parameters;
  parameters.effects = {{"held_friction",
                         {"held_friction1", "held_friction2", "presliding_travel"},
                         {0.09, 0.12, 0.002},
                         {0.0, 0.0, 0.0}}};
  const ExtraEffects extra(parameters.effects);
  ComplianceFilter with(parameters, testing::ModelLogOptions());
  ComplianceFilter without(plain, testing::ModelLogOptions());
  ComplianceFilter unaware(plain, testing::ModelLogOptions());
  models::TravelSinceReversal travel;
  double largest_torque = 0.0, largest_difference = 0.0, largest_shift = 0.0;
  for (const FilterSample& sample : run.samples) {
    models::JointState<double> state;
    state.encoder_angle_rad = sample.encoder_rad;
    state.insertion_depth_m = sample.insertion_depth_m;
    state.travel_since_reversal_rad = travel.Update(sample.encoder_rad);
    const Eigen::Vector2d friction = extra.InternalTorque(state);
    FilterSample less = sample;
    less.effort_nm -= friction;
    const FilterEstimate a = with.Step(sample), b = without.Step(less);
    largest_torque = std::max(largest_torque, friction.cwiseAbs().maxCoeff());
    largest_difference =
        std::max(largest_difference, (a.corrected_rad - b.corrected_rad).cwiseAbs().maxCoeff());
    // A filter unaware of it reads the friction as load: K·F ≈ 5 mrad on joint 1.
    const FilterEstimate c = unaware.Step(sample);
    largest_shift = std::max(largest_shift, std::abs(a.corrected_rad[0] - c.corrected_rad[0]));
  }
  EXPECT_GT(largest_torque, 0.08);  // the pushes reverse: the friction is felt
  EXPECT_LT(largest_difference, 1e-12);
  EXPECT_GT(largest_shift, 0.002);
}

TEST(HeldFriction, AnEffectWithWrongParametersIsRefusedByName) {
  auto parameters = PaperPrior();
  parameters.effects = {{"held_friction", {"held_friction1"}, {0.1}, {0.0}}};
  try {
    ComplianceCorrector corrector(parameters, CorrectionModel::kPaper);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("presliding_travel"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pliant::estimation
