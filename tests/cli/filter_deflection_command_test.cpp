// `pliant filter` applies the parameters file's deflection effects: a divot
// log simulated with a deflection coupling (the shipped
// data/divot_hidden_effect.csv's, k12 6 and k21 4 mrad per N·m), filtered
// with data/paper.json and with the same file holding the effect at its
// true value, against the simulated truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/parameters_json.h"
#include "run_command.h"

namespace pliant::testing {
namespace {

namespace fs = std::filesystem;
const std::string kParams = std::string(PLIANT_SOURCE_DIR) + "/data/paper.json";
const std::string kCli = PLIANT_CLI;

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Joint j's corrected-angle error (rad) against the truth on the rows where
// the other joint's effort departs from its median by more than 0.3 N·m: the
// rows where the coupling moves joint j's encoder by 1.2 mrad or more.
std::vector<double> CoupledRowErrors(const fs::path& filtered, int joint) {
  const io::Log log = io::ReadLog(filtered.string());
  const auto& h = log.header;
  const std::string j = std::to_string(joint), other = std::to_string(3 - joint);
  const int tau = h.Index("tau" + other), corr = h.Index("q" + j + "_corr"),
            truth = h.Index("q" + j + "_true");
  if (tau < 0 || corr < 0 || truth < 0) return {};
  std::vector<double> effort;
  for (std::size_t r = 0; r < log.Rows(); ++r) effort.push_back(log.Value(r, tau));
  const double median = Median(effort);
  std::vector<double> errors;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (std::abs(log.Value(r, tau) - median) > 0.3) {
      errors.push_back(log.Value(r, corr) - log.Value(r, truth));
    }
  }
  return errors;
}

double Rms(const std::vector<double>& e, double about = 0.0) {
  double sum = 0.0;
  for (double x : e) sum += (x - about) * (x - about);
  return std::sqrt(sum / double(e.size()));
}

TEST(FilterDeflectionCommand, TheFilesCouplingTakesTheOtherJointsLoadOutOfTheEncoder) {
  const auto dir = FreshDirectory("filter_deflection");
  const auto RunIn = [](const fs::path& in, const std::string& command) {
    return RunCommand("cd '" + in.string() + "' && " + command, in);
  };
  auto with = io::ReadParameters(kParams);
  with.effects.push_back({"deflection_coupling", {"k12", "k21"}, {0.006, 0.004}, {0.0, 0.0}});
  io::WriteParameters((dir / "with.json").string(), with);
  const std::string simulate = kCli + " simulate " + PLIANT_SOURCE_DIR + "/experiments/scenarios/divot.json" +
                               " --seed 5 --set log.every_n_periods=30" +
                               " --set experiment.depths_m=[0.13] --set 'hidden_effects=";
  ASSERT_EQ(RunIn(dir, simulate + R"({"deflection_coupling":{"k12":0.006,"k21":0.004}}' -o coupled.csv)")
                .exit_code, 0);
  ASSERT_EQ(RunIn(dir, simulate + "{}' -o clean.csv").exit_code, 0);
  for (const std::string run : {"clean.csv paper", "coupled.csv paper", "coupled.csv with"}) {
    const std::string log = run.substr(0, run.find(' ')), params = run.substr(run.find(' ') + 1);
    const auto f = RunIn(dir, kCli + " filter --params " +
                                  (params == "paper" ? kParams : std::string("with.json")) + " " +
                                  log + " -o " + params + "_" + log);
    ASSERT_EQ(f.exit_code, 0) << f.err;
  }
  // Measured (mrad, RMS; in brackets about the median error): joint 1
  // 1.453 (0.297) -> 1.166 (0.030), the log without the effect 1.159 (0.027);
  // joint 2 0.193 (0.193) -> 0.042 (0.027), without 0.017 (0.017). Joint 1's
  // median error of 1.15 mrad is the filter's on this log with paper.json
  // with or without the effect (docs/validation-unlike-defaults.md, "still short").
  for (int joint : {1, 2}) {
    SCOPED_TRACE("joint " + std::to_string(joint));
    const auto clean = CoupledRowErrors(dir / "paper_clean.csv", joint);
    const auto before = CoupledRowErrors(dir / "paper_coupled.csv", joint);
    const auto after = CoupledRowErrors(dir / "with_coupled.csv", joint);
    ASSERT_GT(before.size(), 1000u);
    ASSERT_EQ(after.size(), before.size());
    EXPECT_LT(Rms(after), (joint == 1 ? 0.85 : 0.3) * Rms(before));
    EXPECT_LT(Rms(after), Rms(clean) + 0.03e-3);
    // What follows the other joint's load (the error about its median) is gone.
    EXPECT_LT(Rms(after, Median(after)), 0.2 * Rms(before, Median(before)));
    EXPECT_LT(Rms(after, Median(after)), Rms(clean, Median(clean)) + 0.015e-3);
  }
}

}  // namespace
}  // namespace pliant::testing
