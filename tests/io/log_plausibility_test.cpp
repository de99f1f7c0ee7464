// Whole-log physics checks (log_plausibility.h): each kind of implausible log
// refused or warned with its message, and plausible ones (radians, seconds,
// the compliance of a real instrument) passing.
#include "pliant/io/log_plausibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "pliant/io/input_error.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

using testing::TempDirectory;

constexpr double kDegree = M_PI / 180.0;

// A clamped tip at 0.15 m: 4 holds, in each the effort ramps -0.5 … 0.5 N·m
// and the encoder follows by K·tau (K = 0.05 rad/(N·m)), in units of `unit`
// per rad. Rows every `dt` s.
std::string HeldLog(double unit, double dt = 0.01, double k = 0.05) {
  std::ostringstream out;
  out << "t,q1,q2,q3,tau1,tau2,tip_fixed,segment\n";
  int row = 0;
  for (int hold = 0; hold < 4; ++hold) {
    for (int i = 0; i <= 20; ++i, ++row) {
      const double tau = -0.5 + 0.05 * i;
      const double q1 = (0.01 * hold + k * tau) * unit;
      const double q2 = (-0.002 * hold + 0.6 * k * tau) * unit;
      out << row * dt << "," << q1 << "," << q2 << ",0.15," << tau << "," << tau << ",1," << hold
          << "\n";
    }
  }
  return out.str();
}

// Free motion with velocity columns: q = a·sin(t) in `q_unit` per rad,
// v = a·cos(t) in rad/s, t in `t_unit` per second.
std::string MovingLog(double amplitude, double q_unit, double t_unit) {
  std::ostringstream out;
  out.precision(12);
  out << "t,q1,q2,q3,tau1,tau2,v1,v2\n";
  for (int i = 0; i < 300; ++i) {
    const double t = 0.01 * i;
    out << t * t_unit << "," << amplitude * std::sin(t) * q_unit << ","
        << 0.5 * amplitude * std::sin(t) * q_unit << ",0.1,0,0," << amplitude * std::cos(t) << ","
        << 0.5 * amplitude * std::cos(t) << "\n";
  }
  return out.str();
}

std::string ErrorOf(const std::string& path) {
  try {
    CheckLogPlausibility(path);
  } catch (const InputError& e) {
    return std::string(e.what()).substr(path.size());
  }
  return "no error";
}

TEST(LogPlausibility, RadiansAndSecondsPass) {
  TempDirectory dir;
  EXPECT_EQ(ErrorOf(dir.Write("held.csv", HeldLog(1.0))), "no error");
  EXPECT_EQ(ErrorOf(dir.Write("moving.csv", MovingLog(0.2, 1.0, 1.0))), "no error");
  EXPECT_TRUE(CheckLogPlausibility(dir.File("moving.csv")).warnings.empty());
  // The span for options that must lie within the log.
  EXPECT_NEAR(CheckLogPlausibility(dir.File("moving.csv")).DurationS(), 2.99, 1e-12);
}

TEST(LogPlausibility, AHeldTipFiftySevenTimesTooCompliantIsDegrees) {
  TempDirectory dir;
  // Scaled so that every angle stays under 1.5° (inside both joints' range in
  // rad): only the compliance can tell.
  const std::string message = ErrorOf(dir.Write("deg.csv", HeldLog(1.0 / kDegree / 2.0)));
  // K = 0.05 rad/(N·m) read in degrees and halved: 0.05·57.3/2 = 1.43.
  EXPECT_EQ(message.substr(0, 86),
            ": joint 1: on the held-tip rows (tip_fixed = 1) q1 moves by 1.43 per N·m of effort (m");
  EXPECT_NE(message.find("this looks like degrees; convert q1, q2"), std::string::npos);
  // The most compliant instrument (0.1 rad/(N·m)) with backlash passes.
  EXPECT_EQ(ErrorOf(dir.Write("soft.csv", HeldLog(1.0, 0.01, 0.1))), "no error");
}

TEST(LogPlausibility, AnAngleBeyondTheJointsRangeIsDegrees) {
  TempDirectory dir;
  // 0.04 rad logged as 2.3°: beyond the yaw's ±1.588 rad yet within ±2π (the
  // reader's own limit).
  const std::string path = dir.Write("deg.csv", "t,q1,q2,q3,tau1,tau2\n0,1,0,0.1,0,0\n"
                                                "0.1,2.3,0,0.1,0,0\n");
  EXPECT_EQ(ErrorOf(path),
            ":3:2: q1 = 2.3 rad is beyond the PSM's yaw range ±1.588 rad (dVRK configuration "
            "files) \u2014 this looks like degrees; convert q1, q2 (and their _cmd, _ref and _true "
            "columns, and v1, v2) to radians (multiply by π/180)");
}

TEST(LogPlausibility, VelocitiesTellDegreesAndMilliseconds) {
  TempDirectory dir;
  // 0.02 rad is 1.15°: inside the yaw's range either way; only v tells.
  const std::string degrees = ErrorOf(dir.Write("deg.csv", MovingLog(0.02, 1.0 / kDegree, 1.0)));
  EXPECT_EQ(degrees, ": q1 changes 57.3 times as fast as v1 says (Δq/Δt against v1 over the log) "
                     "while both should be in rad and rad/s; π/180 = 1/57.3 \u2014 this looks like "
                     "degrees; convert q1, q2 (and their _cmd, _ref and _true columns, and v1, v2) "
                     "to radians (multiply by π/180)");
  const std::string ms = ErrorOf(dir.Write("ms.csv", MovingLog(0.2, 1.0, 1000.0)));
  EXPECT_EQ(ms, ": q1 changes only 0.001 times as fast as v1 says (Δq/Δt against v1 over the "
                "log): t looks like milliseconds \u2014 give t in seconds (divide it by 1000)");
}

TEST(LogPlausibility, SlowRowsAndLongGapsAreWarnings) {
  TempDirectory dir;
  const auto slow = CheckLogPlausibility(dir.Write("slow.csv", HeldLog(1.0, 0.667)));
  ASSERT_EQ(slow.warnings.size(), 1u);
  EXPECT_EQ(slow.warnings[0], dir.File("slow.csv") +
                                  ": rows come every 0.667 s (median): if t is in milliseconds, "
                                  "divide it by 1000; if the rows are held poses without time, "
                                  "add the line '# timing: quasi-static'");
  const auto quasi = CheckLogPlausibility(
      dir.Write("quasi.csv", "# timing: quasi-static\n" + HeldLog(1.0, 1.0)));
  EXPECT_TRUE(quasi.warnings.empty());
  std::string gap = MovingLog(0.2, 1.0, 1.0);
  gap += "3603,0,0,0.1,0,0,0,0\n";
  const auto joined = CheckLogPlausibility(dir.Write("gap.csv", gap));
  ASSERT_EQ(joined.warnings.size(), 1u);
  EXPECT_EQ(joined.warnings[0], dir.File("gap.csv") +
                                    ":302: t jumps by 3600 s (the median step is 0.01 s): two "
                                    "recordings joined? Split the log, or give each part its own "
                                    "segment");
}

}  // namespace
}  // namespace pliant::io
