// The output step limit (FilterOptions::output_step_limit_counts): the
// corrected angle moves at most the limit beyond the encoder's own change per
// step, follows the estimate at exactly that rate when the estimate moves
// faster, reports the mean squared error P + d·dᵀ of the gap d it leaves, and
// never feeds back into the filter's state.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "paper_parameters.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

using models::testing::PaperParameters;

// A held tip at rest and unloaded: the filter knows the tip only to the
// clearance (±δ) until a reference says where it is.
FilterSample HeldAtRest(const models::ModelParameters& p, int k, double reference_rad) {
  FilterSample s;
  s.time_s = k / 1500.0;
  s.insertion_depth_m = 0.15;
  s.tip_fixed = true;
  s.encoder_rad << 0.1, -0.2;
  s.effort_nm << models::BiasTorqueAt(p.joints[0], 0.1, 0.15),
      models::BiasTorqueAt(p.joints[1], -0.2, 0.15);
  s.reference_rad << reference_rad, FilterSample::kMissing;
  return s;
}

TEST(OutputStepLimiter, FollowsTheEstimateAtTheLimitAndReportsTheGapsError) {
  const auto p = PaperParameters();
  FilterOptions limited_options;
  limited_options.output_step_limit_counts = 2.0;
  FilterOptions free_options;
  free_options.output_step_limit_counts = std::numeric_limits<double>::infinity();
  ComplianceFilter limited(p, limited_options), unlimited(p, free_options);
  const double count = std::sqrt(12.0) * limited_options.encoder_noise_rad;
  const double limit = 2.0 * count;  // the encoder does not move
  // 300 samples at rest, then a reference 0.004 rad (≈ 520 counts) from where
  // the filter put the tip: the estimate jumps to it in one sample.
  const double reference = 0.1 + 0.004;
  double output = 0.0;
  int steps_behind = 0;
  for (int k = 0; k < 600; ++k) {
    const FilterSample s = HeldAtRest(p, k, k < 300 ? FilterSample::kMissing : reference);
    const FilterEstimate e = limited.Step(s);
    const FilterEstimate f = unlimited.Step(s);
    // The limit is on the output only: the state is the unlimited filter's, bit for bit.
    ASSERT_EQ(limited.joint_state(0).mean, unlimited.joint_state(0).mean) << k;
    ASSERT_EQ(limited.joint_state(0).covariance, unlimited.joint_state(0).covariance) << k;
    ASSERT_EQ(e.filtered_rad, f.corrected_rad) << k;
    if (k > 0) {
      // Closed form: the output moves toward the estimate by at most the limit.
      const double step = f.corrected_rad[0] - output;
      const double expected = std::abs(step) <= limit ? f.corrected_rad[0]
                                                      : output + std::copysign(limit, step);
      ASSERT_DOUBLE_EQ(e.corrected_rad[0], expected) << k;
      ASSERT_LE(std::abs(e.corrected_rad[0] - output), limit * (1.0 + 1e-12)) << k;
    }
    const double gap = e.corrected_rad[0] - f.corrected_rad[0];
    ASSERT_DOUBLE_EQ(e.covariance_rad2(0, 0), f.covariance_rad2(0, 0) + gap * gap) << k;
    ASSERT_EQ((e.flags & kFlagOutputLimited) != 0, gap != 0.0) << k;
    // Joint 2 never had a reason to move: untouched.
    ASSERT_EQ(e.corrected_rad[1], f.corrected_rad[1]) << k;
    ASSERT_EQ(e.covariance_rad2(1, 1), f.covariance_rad2(1, 1)) << k;
    steps_behind += gap != 0.0;
    output = e.corrected_rad[0];
  }
  // The reference moved the estimate by hundreds of counts: the output took
  // about that many / 2 steps to catch up, and then sat on the estimate.
  EXPECT_GT(steps_behind, 200);
  EXPECT_LT(steps_behind, 300);
  EXPECT_NEAR(output, reference, 2.0 * std::sqrt(limited.joint_state(0).covariance(0, 0)));
}

TEST(OutputStepLimiter, AllowsTheEncodersOwnChangeAndRestartsOnARelease) {
  const auto p = PaperParameters();
  FilterOptions o;
  const double count = std::sqrt(12.0) * o.encoder_noise_rad;
  ComplianceFilter filter(p, o);
  // A free tip swept at 0.3 rad/s (26 counts a sample): the output keeps up
  // with the encoder, so it is the estimate itself.
  FilterEstimate e;
  const double end_rad = 0.1 + 0.3 * 299 / 1500.0;
  for (int k = 0; k < 300; ++k) {
    FilterSample s = HeldAtRest(p, k, FilterSample::kMissing);
    s.tip_fixed = false;
    s.encoder_rad[0] += 0.3 * k / 1500.0;
    e = filter.Step(s);
    ASSERT_EQ(e.corrected_rad, e.filtered_rad) << k;
  }
  // Held there, a reference 520 counts away moves the estimate: the output
  // is held back. Then a release (two held rows at depths 1 mm apart): the
  // new hold is another place, so the output starts again from the estimate.
  FilterSample s = HeldAtRest(p, 300, e.filtered_rad[0] + 0.004);
  s.encoder_rad[0] = end_rad;
  e = filter.Step(s);
  ASSERT_NE(e.corrected_rad[0], e.filtered_rad[0]);
  ASSERT_GT(std::abs(e.corrected_rad[0] - e.filtered_rad[0]), 50 * count);
  s = HeldAtRest(p, 301, FilterSample::kMissing);
  s.encoder_rad[0] = end_rad;
  s.insertion_depth_m += 1e-3;
  e = filter.Step(s);
  EXPECT_EQ(e.corrected_rad, e.filtered_rad);
  EXPECT_EQ(e.flags & kFlagOutputLimited, 0u);
}

TEST(FilterOptions, RefusesANonPositiveOutputStepLimit) {
  FilterOptions o;
  std::string error;
  for (double v : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    o.output_step_limit_counts = v;
    EXPECT_FALSE(o.IsValid(&error)) << v;
    EXPECT_NE(error.find("output_step_limit_counts"), std::string::npos);
  }
  o.output_step_limit_counts = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(o.IsValid(&error));
}

}  // namespace
}  // namespace pliant::estimation
