#pragma once
// The take-up width of the dead zone, profiled (docs/identification-method.md,
// docs/decisions/0010-identification-profiled-take-up-width.md).
//
// Levenberg–Marquardt with log w free crawls where a hard contact drives w to
// its floor (the smooth dead zone becomes a step). With w held, each solve is
// the smooth problem it always was; w is found by an outer 1-D minimisation of
// the solved cost over log w_j in [floor_j, upper_j], joint by joint: the two
// joints share no unknown (each has its own law, δ, w, bias, tips and external
// torques), so the cost separates and one search per joint finds the joint
// optimum.

#include <array>
#include <functional>
#include <string>

#include <ceres/solver.h>

namespace pliant::estimation::detail {

struct WidthSearch {
  /// Solves with both log widths held at the argument (warm started) and
  /// returns Ceres' summary: its final_cost is the profiled cost.
  std::function<ceres::Solver::Summary(const std::array<double, 2>&)> solve_at;
  /// ∂cost/∂log w_j at the last solve: the profile's slope (the other
  /// unknowns are at their optimum, so their share of the derivative is nil).
  std::function<std::array<double, 2>()> slope;
  std::array<double, 2> lower{}, upper{};  ///< log N·m; lower is the floor
  std::array<bool, 2> search{};            ///< false: the joint stays at its floor
};

struct WidthProfile {
  std::array<double, 2> log_width{};  ///< the minimiser per joint (log N·m)
  std::array<bool, 2> at_floor{};     ///< the profile rises from the floor
  int solves = 0;                     ///< inner solves, over both searches
  int iterations = 0;                 ///< their Levenberg–Marquardt iterations
  int not_converged = 0;              ///< inner solves that ended short of CONVERGENCE
};

/// One solve at the floors; a joint whose profile slope there is >= 0 ends
/// there (a hard contact: the profile rises from the resolution limit); the
/// others by Brent's method (boost::math::tools::brent_find_minima) over
/// (floor, upper] to a tolerance of about 1 % in w, at most 40 costs per
/// joint. Throws std::runtime_error when a solve is not usable.
WidthProfile ProfileWidths(const WidthSearch& problem);

/// One line for the fit's report: the widths, floors and solver counts.
std::string Describe(const WidthProfile& profile, const WidthSearch& problem);

}  // namespace pliant::estimation::detail
