// The clamped-beam protocol's legs, driven with chosen hold efforts: a leg
// ends when the load in its own direction passes the limit, so a reversal that
// starts with the effort still beyond the limit the other way is not cut short.
#include <gtest/gtest.h>

#include "protocols.h"
#include "simulation_support.h"

namespace pliant::experiments::testing {
namespace {

struct Driven {
  int phases = 0;
  double final_command_rad = 0.0;
};

// Feeds the protocol one hold effort (joint 1) per stepping phase.
Driven Drive(detail::Protocol& protocol, const std::vector<double>& efforts_nm) {
  detail::Phase phase;
  HoldRecord hold;
  Driven d;
  EXPECT_TRUE(protocol.Next(nullptr, &phase));  // transit to the clamp pose
  EXPECT_TRUE(protocol.Next(nullptr, &phase));  // clamp, unloaded reference hold
  for (double effort : efforts_nm) {
    hold.effort_nm = Eigen::Vector2d(effort, 0.0);
    if (!protocol.Next(&hold, &phase)) break;
    if (!phase.tip_fixed) break;  // released: the run is over
    d.final_command_rad = phase.command(phase.duration_s)[0];
    ++d.phases;
  }
  return d;
}

TEST(ClampedBeamProtocol, AReversalStartingBeyondTheLimitIsNotCutShort) {
  const Scenario s = Load("clamped_beam", {"experiment.depths_m=[0.15]", "experiment.joints=[1]",
                                           "experiment.effort_limit_nm=1.0"});
  const auto protocol = detail::MakeClampedBeam(s, 1.0 / 1500.0);
  const double step_rad = s.clamped_beam.tip_step_m / 0.15;
  // Each effort is the hold at the present command (in steps from the start):
  // leg 1 (+) reads 0, 0.5, 1.1 N·m at 0, +1, +2 and reverses; the first hold
  // of leg 2 (−), at +1, still reads 1.05 N·m the other way (it must go on:
  // the old |effort| test ended leg 2 here and the run after one more step);
  // leg 2 passes −1 N·m at −3; leg 3 (+) stops once past the start, at +1.
  const std::vector<double> efforts = {0.0, 0.5, 1.1,                // leg 1
                                       1.05, 0.4, -0.3, -0.8, -1.2,  // leg 2
                                       -0.9, -0.5, -0.1, 0.0, 0.0};  // leg 3
  const Driven d = Drive(*protocol, efforts);
  const auto& segments = protocol->segments();
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(segments[0].direction, +1);
  EXPECT_EQ(segments[1].direction, -1);
  EXPECT_EQ(segments[2].direction, +1);
  // Phases: +1, +2 (leg 1); +1, 0, −1, −2, −3 (leg 2); −2, −1, 0, +1 (leg 3).
  EXPECT_EQ(d.phases, 11);
  EXPECT_NEAR(d.final_command_rad, step_rad, 1e-12);
}

}  // namespace
}  // namespace pliant::experiments::testing
