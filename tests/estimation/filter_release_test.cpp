// A log of hold means (the clamped beam's) skips the transit between clamps:
// two tip-fixed rows at different depths mean the tip was released, the arm
// moved with it free, and it was held again. The filter must then forget
// which wall the shaft sat on, as a free tip does when the arm moves.
#include <cmath>

#include <gtest/gtest.h>

#include "paper_parameters.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation {
namespace {

using models::testing::PaperParameters;

// Joint 1's hold: encoder = tip + b + K(L)·tau, effort = tau0(q, L) + tau.
FilterSample Hold(const models::ModelParameters& p, double t, double depth_m, double tip_rad,
                  double backlash_rad, double load_nm) {
  FilterSample s;
  s.time_s = t;
  s.insertion_depth_m = depth_m;
  s.tip_fixed = true;
  const double q = tip_rad + backlash_rad + models::ComplianceAt(p.joints[0], depth_m) * load_nm;
  s.encoder_rad << q, -0.2;
  s.effort_nm << models::BiasTorqueAt(p.joints[0], q, depth_m) + load_nm,
      models::BiasTorqueAt(p.joints[1], -0.2, depth_m);
  return s;
}

TEST(ComplianceFilter, AReleaseBetweenHoldsForgetsTheWallTheShaftSatOn) {
  const auto p = PaperParameters();
  const double delta = p.joints[0].backlash_rad;
  FilterOptions o;  // the instrument is the parameters' own: no clearance or bias-offset doubt
  o.backlash_sd_rad.setZero();
  o.effort_offset_sd_nm.setZero();
  o.infer_contact = false;  // the free tip carries a load on every sample: all of it is load
  o.time_gap_s = 1.0;  // rows 0.9 s apart are consecutive hold means here, not gaps
  ComplianceFilter filter(p, o);
  // Clamped at 0.15 m, pushed to +1 N·m and eased back to 0.3 N·m: the shaft
  // sits on its + wall, b = +δ, and the tip is pinned.
  FilterEstimate e;
  double t = 0.0;
  for (double load : {0.0, 0.5, 1.0, 1.0, 0.6, 0.3}) {
    e = filter.Step(Hold(p, t += 0.9, 0.15, 0.0, delta, load));
  }
  ASSERT_NEAR(e.backlash_offset_rad[0], delta, 0.05 * delta);
  const double held_sd = std::sqrt(e.covariance_rad2(0, 0));
  ASSERT_LT(held_sd, 0.25 * delta);
  ASSERT_LT(std::abs(e.corrected_rad[0]), 2.0 * held_sd);
  // Released, the arm goes back to the clamp angle at 0.16 m and holds the
  // tip there, unloaded; the shaft floated off its wall (b = 0 here, but the
  // filter cannot know where: anywhere in ±δ).
  e = filter.Step(Hold(p, t += 0.9, 0.16, 0.0, 0.0, 0.0));
  EXPECT_NEAR(e.backlash_offset_rad[0], 0.0, 0.05 * delta);
  const double sd = std::sqrt(e.covariance_rad2(0, 0));
  // The uniform on ±δ (σ_δ = 0), and a little of what the tip was not sure of.
  EXPECT_GT(sd, delta / std::sqrt(3.0));
  EXPECT_LT(sd, std::hypot(delta / std::sqrt(3.0), held_sd) * 1.05);
  EXPECT_LT(std::abs(e.corrected_rad[0]), 2.0 * sd);
  // Held without a release (same depth), the wall is remembered: b stays +δ.
  ComplianceFilter held(p, o);
  t = 0.0;
  for (double load : {0.0, 0.5, 1.0, 1.0, 0.6, 0.3}) {
    held.Step(Hold(p, t += 0.9, 0.15, 0.0, delta, load));
  }
  e = held.Step(Hold(p, t += 0.9, 0.15, 0.0, delta, 0.0));
  EXPECT_NEAR(e.backlash_offset_rad[0], delta, 0.05 * delta);
}

}  // namespace
}  // namespace pliant::estimation
