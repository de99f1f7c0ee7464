// Closed-form checks of compliance.
#include "pliant/models/effects/compliance.h"

#include <gtest/gtest.h>

#include "loaded_state.h"

namespace pliant::models {
namespace {

using testing::Loaded;

TEST(ComplianceEffect, IsKTimesTheExternalTorque) {
  const ComplianceEffect compliance;  // the paper's equations (3) and (4)
  const std::vector<double> c = {639.16, -432.35, 136.32, 3.12, 3163.17, -1969.15, 448.92, -6.0};
  const auto bend = compliance(c.data(), Loaded(0.5, -1.0));
  EXPECT_NEAR(bend[0], 0.5 / 15.99729, 1e-12);
  EXPECT_NEAR(bend[1], -1.0 / 27.70782375, 1e-12);
  // Below the calibrated range the depth is clamped, never evaluated where 1/K2 < 0.
  const auto shallow = compliance(c.data(), Loaded(0.5, -1.0, 0.01));
  EXPECT_NEAR(shallow[1], -1.0 / 20.75863593, 1e-12);
}

}  // namespace
}  // namespace pliant::models
