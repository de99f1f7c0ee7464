#include "joint_smoother_width.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include <boost/math/tools/minima.hpp>

namespace pliant::estimation::detail {
namespace {

double CountedCost(const WidthSearch& problem, const std::array<double, 2>& log_width,
                   WidthProfile* out) {
  const ceres::Solver::Summary summary = problem.solve_at(log_width);
  if (!summary.IsSolutionUsable())
    throw std::runtime_error("the joint smoother failed: " + summary.message);
  ++out->solves;
  out->iterations += int(summary.iterations.size()) - 1;
  if (summary.termination_type != ceres::CONVERGENCE) ++out->not_converged;
  return summary.final_cost;
}

}  // namespace

WidthProfile ProfileWidths(const WidthSearch& problem) {
  WidthProfile out;
  out.log_width = problem.lower;
  CountedCost(problem, out.log_width, &out);
  const std::array<double, 2> slope = problem.slope();
  for (int j = 0; j < 2; ++j) {
    out.at_floor[j] = !problem.search[j] || slope[j] >= 0.0 || !(problem.upper[j] > problem.lower[j]);
    if (out.at_floor[j]) continue;
    // Brent's tolerance is relative to |x|: searched as log(w / floor) >= 0,
    // it is about 1 % of w at a take-up a few times the floor.
    std::uintmax_t evaluations = 40;
    const auto best = boost::math::tools::brent_find_minima(
        [&](double x) {
          std::array<double, 2> at = out.log_width;
          at[j] = problem.lower[j] + x;
          return CountedCost(problem, at, &out);
        },
        0.0, problem.upper[j] - problem.lower[j], 10, evaluations);
    out.log_width[j] = problem.lower[j] + best.first;
  }
  return out;
}

std::string Describe(const WidthProfile& profile, const WidthSearch& problem) {
  std::string line = "  take-up width (profiled, Brent over log w):";
  for (int j = 0; j < 2; ++j) {
    char part[160];
    std::snprintf(part, sizeof part, " w%d = %.4g N·m%s", j + 1, std::exp(profile.log_width[j]),
                  profile.at_floor[j] ? " (at its floor)" : "");
    line += part;
  }
  char tail[160];
  std::snprintf(tail, sizeof tail, "; %d solves, %d iterations, %d short of convergence\n",
                profile.solves, profile.iterations, profile.not_converged);
  return line + tail;
}

}  // namespace pliant::estimation::detail
