#pragma once
// The error a corrected log leaves where it matters for a load effect, and
// the check that a parameters file with the effect lowers it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pliant/io/log_reader.h"
#include "run_command.h"

namespace pliant::testing {

// RMS (rad) of joint j's corrected angle against the simulated truth over
// the rows where that joint's effort departs from its median by more than
// 0.3 N·m: the joint pushed past its clearance, the rows the diagnosis scores.
// (On the rows where the joint rests inside its clearance while the other
// is pushed, the coupling as the catalogue writes it moves the corrected
// angle and the simulated tip does not follow: docs/diagnose.md.)
inline double LoadedRmsError(const std::filesystem::path& corrected, int joint) {
  const io::Log log = io::ReadLog(corrected.string());
  const auto& h = log.header;
  const std::string j = std::to_string(joint);
  const int tau = h.Index("tau" + j), corr = h.Index("q" + j + "_corr"), truth = h.Index("q" + j + "_true");
  if (tau < 0 || corr < 0 || truth < 0) return NAN;
  std::vector<double> effort;
  for (std::size_t r = 0; r < log.Rows(); ++r) effort.push_back(log.Value(r, tau));
  std::nth_element(effort.begin(), effort.begin() + long(effort.size() / 2), effort.end());
  const double median = effort[effort.size() / 2];
  double sum = 0.0;
  long n = 0;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (std::abs(log.Value(r, tau) - median) <= 0.3) continue;
    const double e = log.Value(r, corr) - log.Value(r, truth);
    sum += e * e, ++n;
  }
  return n > 100 ? std::sqrt(sum / double(n)) : NAN;
}

// Runs `pliant COMMAND --params P other.csv` in dir with the parameters
// before and after (files) and expects each joint's LoadedRmsError to fall
// below `factor` × before; prints both.
inline void ExpectLoadedErrorFalls(const std::filesystem::path& dir, const std::string& cli,
                                   const std::string& command, const std::string& before_params,
                                   const std::string& after_params, double factor) {
  const std::string files[2] = {before_params, after_params};
  for (int k = 0; k < 2; ++k) {
    const auto r = RunIn(dir, cli + " " + command + " --params " + files[k] + " other.csv -o " +
                                  command + std::to_string(k) + ".csv");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (int joint : {1, 2}) {
    const double before = LoadedRmsError(dir / (command + "0.csv"), joint);
    const double after = LoadedRmsError(dir / (command + "1.csv"), joint);
    std::printf("%s, joint %d loaded-row RMS error: %.3f -> %.3f mrad\n", command.c_str(), joint,
                1e3 * before, 1e3 * after);
    EXPECT_LT(after, factor * before) << command << ", joint " << joint;
  }
}

}  // namespace pliant::testing
