// pliant identify --effect joint_inertia --effect joint_friction: the arm's
// own dynamics fitted on a log's free motion (estimation/free_motion_fit.h),
// against the simulator's arm: its plant's inertia (the scenario's
// joint.inertia_kg_m2, 0.08 kg·m²) and the free_motion scenario's friction
// (0.02 N·m·s/rad, 0.02 N·m). Neither is an input of the fit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_command.h"

namespace pliant::testing {
namespace {

namespace fs = std::filesystem;
const std::string kCli = PLIANT_CLI;
const std::string kSource = PLIANT_SOURCE_DIR;

double Parameter(const nlohmann::json& effects, const std::string& name, const char* field) {
  for (const auto& e : effects)
    for (const auto& p : e.at("parameters"))
      if (p.at("name") == name) return p.at(field).get<double>();
  ADD_FAILURE() << "no " << name;
  return NAN;
}

TEST(IdentifyFreeMotion, RecoversTheSimulatedArmsInertiaAndFriction) {
  const auto dir = FreshDirectory("identify_free_motion");
  const auto sim = RunIn(dir, kCli + " simulate " + kSource +
                                  "/experiments/scenarios/free_motion.json -o free.csv --seed 4 "
                                  "--set experiment.duration_s=20");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = RunIn(dir, kCli + " identify free.csv --effect joint_inertia "
                                   "--effect joint_friction -o arm.json --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fit = nlohmann::json::parse(r.out).at("free_motion_fit");
  const auto& effects = fit.at("effects");
  for (const auto& [name, truth] : {std::pair{"inertia1", 0.08}, std::pair{"inertia2", 0.08},
                                    std::pair{"coulomb1", 0.02}, std::pair{"coulomb2", 0.02},
                                    std::pair{"viscous1", 0.02}, std::pair{"viscous2", 0.02}}) {
    const double value = Parameter(effects, name, "value"), sd = Parameter(effects, name, "sd");
    EXPECT_LT(std::abs(value - truth), 3.0 * sd) << name << " = " << value << " ± " << sd;
    EXPECT_LT(sd, 0.25 * truth) << name << " is informed";
  }
  // The file says once what fitted them (the base is fitted twice: without
  // the effects' torque the second time).
  std::ifstream file(dir / "arm.json");
  const std::string description = nlohmann::json::parse(file).at("description");
  const auto first = description.find("fitted by");
  ASSERT_NE(first, std::string::npos) << description;
  EXPECT_EQ(description.find("fitted by", first + 1), std::string::npos) << description;
  // The file's inertia is the filter's: the motor inertia option beside it
  // would take J·θ̈ out twice, and is bad input.
  const auto twice = RunIn(dir, kCli + " filter --params arm.json free.csv --motor-inertia 0.08 -o f.csv");
  EXPECT_EQ(twice.exit_code, 2) << twice.err;
  EXPECT_NE(twice.err.find("--motor-inertia"), std::string::npos) << twice.err;
  EXPECT_NE(twice.err.find("set it to 0"), std::string::npos) << twice.err;
  EXPECT_FALSE(fs::exists(dir / "f.csv"));
}

TEST(IdentifyFreeMotion, InertiaWithoutFreeMotionIsBadInput) {
  const auto dir = FreshDirectory("identify_free_motion_none");
  const std::string real = kSource + "/data/real/";
  const auto r = RunIn(dir, kCli + " identify " + real + "jhu2017_bias_j1.csv " + real +
                                "jhu2017_clamped_j1.csv --effect joint_inertia -o x.json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("joint_inertia is fitted from free motion"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.json"));
}

}  // namespace
}  // namespace pliant::testing
