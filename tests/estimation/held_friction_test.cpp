// The held-friction effect through the catalogue: its Jacobian check away
// from a reversal, and pliant correct's use of it from a parameters file.
#include <cmath>

#include <gtest/gtest.h>

#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/identification.h"
#include "pliant/estimation/jacobian_check.h"

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
