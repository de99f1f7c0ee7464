#include "pliant/estimation/joint_smoother.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include <ceres/ceres.h>
#include <ceres/normal_prior.h>

#include "clustered_sandwich.h"
#include "consider_covariance.h"
#include "identification_common.h"
#include "identification_consider.h"
#include "identification_costs.h"
#include "joint_smoother_sandwich.h"
#include "joint_smoother_problem.h"
#include "joint_smoother_setup.h"
#include "joint_smoother_width.h"

namespace pliant::estimation {
namespace {

using detail::SmootherPrior;
using detail::SmootherState;
using detail::SmootherProblem;

using Noise = detail::SmootherNoise;

// Median number of rows averaged into a held-tip sample.
double TypicalRows(const IdentificationData& data) {
  std::vector<int> rows;
  for (const auto& s : data.samples) if (s.tip_fixed) rows.push_back(s.rows);
  if (rows.empty()) return 1.0;
  std::nth_element(rows.begin(), rows.begin() + long(rows.size() / 2), rows.end());
  return rows[rows.size() / 2];
}

// The take-up widths profiled (joint_smoother_width.h) up to the largest load
// the clamps put on each joint (a wider take-up never reaches the wall in the
// log) and left held there; every solve starts from the best one so far.
// `above_floor`: the joints whose width the profile put above its floor.
std::string ProfileTakeUp(const IdentificationData& data, const SmootherState& state,
                          const JointSmootherOptions& options, const std::array<double, 2>& log_floor,
                          const detail::UndeterminedParameters& held, SmootherProblem* problem,
                          std::array<bool, 2>* above_floor) {
  detail::WidthSearch search;
  search.lower = log_floor;
  for (int j = 0; j < 2; ++j) {
    double largest = 0.0;
    for (std::size_t i = 0; i < data.samples.size(); ++i)
      if (data.samples[i].tip_fixed) largest = std::max(largest, std::abs(state.tau_ext_nm[i][j]));
    search.upper[j] = std::max(log_floor[j], std::log(largest));
    search.search[j] = !held.backlash[j];
  }
  double best = HUGE_VAL;
  SmootherProblem::Snapshot best_state = problem->Save();
  search.solve_at = [&](const std::array<double, 2>& log_width) {
    problem->Restore(best_state);
    problem->HoldLogWidths(log_width);
    const ceres::Solver::Summary summary = problem->Solve(options);
    if (summary.IsSolutionUsable() && summary.final_cost < best)
      best = summary.final_cost, best_state = problem->Save();
    return summary;
  };
  search.slope = [&] { return problem->WidthSlope(); };
  const detail::WidthProfile profile = detail::ProfileWidths(search);
  problem->Restore(best_state);
  problem->HoldLogWidths(profile.log_width);
  *above_floor = {!profile.at_floor[0], !profile.at_floor[1]};
  return detail::Describe(profile, search);
}

}  // namespace

namespace detail {
// joint_smoother_output.cpp: residual statistics, covariance, parameters.
Noise RescaledNoise(const IdentificationData& data, const SmootherState& state,
                    const JointSmootherOptions& options, const Noise& noise, std::string* note);
void FillResult(const IdentificationData& data, const models::ModelParameters& prior,
                const SmootherPrior& smoother_prior, const JointSmootherOptions& options,
                SmootherState* state, const Eigen::MatrixXd* covariance,
                const std::array<bool, 2>& width_fitted, IdentificationResult* result);
}  // namespace detail

IdentificationResult RunJointSmoother(const IdentificationData& data,
                                      const models::ModelParameters& prior,
                                      const JointSmootherOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("joint smoother options: " + why);
  const double start = detail::NowSeconds();
  PaperProcedureOptions paper_options = options.paper;
  paper_options.law = options.law;
  paper_options.cannula_length_m = options.cannula_length_m;
  const IdentificationResult paper = RunPaperProcedure(data, prior, paper_options);
  const SmootherPrior smoother_prior = detail::MakePrior(prior, options);
  // The paper's procedure's bias table is the measured tau0 when a sweep was
  // logged: the branch test then looks at the load, not at a wrong bias.
  detail::UndeterminedParameters held =
      detail::FindUndetermined(data, paper.parameters, options.paper);
  detail::HoldUndeterminedDepthHarmonic(data, smoother_prior, options, &held);
  SmootherState state = detail::MakeInitialState(data, smoother_prior, paper, options, held);
  for (int j = 0; j < 2; ++j) {
    if (held.backlash[j]) state.delta_rad[j] = smoother_prior.delta_rad[j];
    if (held.bias[j]) state.bias[j] = smoother_prior.bias[j];
  }
  std::vector<long> held_indices;
  std::vector<double> held_sd;
  detail::HeldParameters(held, smoother_prior, options, &held_indices, &held_sd);

  Noise noise;
  for (int j = 0; j < 2; ++j) {
    noise.effort_free_nm[j] = noise.effort_fixed_nm[j] = options.effort_noise_nm;
    noise.angle_fixed_rad[j] = options.encoder_noise_rad;
    // The branch lines' scatter is the held-tip effort noise: start from it.
    if (paper.effort_rms_nm[j] > 0.0) {
      noise.effort_fixed_nm[j] = paper.effort_rms_nm[j] * std::sqrt(TypicalRows(data));
    }

  }
  // The take-up of the clearance cannot be resolved below the effort noise of
  // one sample: w's floor, fixed before the first pass, which holds w there.
  std::array<double, 2> log_floor;
  for (int j = 0; j < 2; ++j) {
    log_floor[j] = std::log(options.deadzone_resolution_sd * noise.effort_fixed_nm[j] /
                            std::sqrt(TypicalRows(data)));
  }
  state.log_width = log_floor;
  IdentificationResult result;
  result.method = "smoother";
  result.depth_estimates = paper.depth_estimates;
  // Two passes: the second weighs the samples by the noise the first found.
  std::string width_line;
  std::array<bool, 2> width_fitted{false, false};
  for (int pass = 0; pass < 2; ++pass) {
    SmootherProblem problem(data, smoother_prior, options, noise, held, &state);
    if (pass == 1 && options.estimate_deadzone_width) {
      width_line = ProfileTakeUp(data, state, options, log_floor, held, &problem, &width_fitted);
    }
    const ceres::Solver::Summary summary = problem.Solve(options);
    result.report += "pass " + std::to_string(pass + 1) + ": " + summary.BriefReport() +
                     " (" + std::to_string(summary.total_time_in_seconds) + " s)\n" + width_line;
    if (!summary.IsSolutionUsable()) {
      throw std::runtime_error("the joint smoother failed: " + summary.message);
    }
    if (pass == 0) {
      std::string note;
      noise = detail::RescaledNoise(data, state, options, noise, &note);
      result.report += note;
      continue;
    }
    // The variance factor of the robust fit, 2·cost/(m − n): above 1 when the
    // model misses something the noise alone does not explain; never below 1.
    const double dof = double(summary.num_residuals_reduced - summary.num_effective_parameters_reduced);
    const double variance_factor = dof > 0.0 ? std::max(1.0, 2.0 * summary.final_cost / dof) : 1.0;
    result.report += "  variance factor " + std::to_string(variance_factor) + "\n";
    int clamps = 0, blocks = 0;
    const Eigen::MatrixXd sandwich = problem.Sandwich(detail::SampleClusters(data, &clamps, &blocks));
    result.report += "  covariance: clustered sandwich over " + std::to_string(clamps) +
                     " tip_fixed segment(s) and " + std::to_string(blocks) +
                     " block(s) of free-tip samples, never below the white noise's\n";
    Eigen::MatrixXd covariance;
    const bool ok = problem.GlobalCovariance(options, variance_factor, &covariance);
    detail::ConsiderResult considered;
    if (ok) {
      // The white noise's covariance (times the variance factor: s²·H⁻¹, as
      // least squares states it) is the floor of the sandwich of the fitted
      // parameters; the considered parameters' share is added to both.
      considered.covariance = covariance;
      considered.conditional = covariance;
      if (!held_indices.empty())
        considered = detail::ConsiderCovariance(covariance, held_indices, held_sd);
      const Eigen::MatrixXd fitted = detail::NotBelow(sandwich, considered.conditional);
      covariance = considered.covariance - considered.conditional + fitted;
      considered.conditional = fitted;
    }
    detail::FillResult(data, prior, smoother_prior, options, &state, ok ? &covariance : nullptr,
                       width_fitted, &result);
    if (ok && !held_indices.empty()) {
      for (const auto& w : detail::HeldParameterWarnings(result.parameters, considered.conditional, held))
        result.warnings.push_back(w);
    }
  }
  result.seconds = detail::SecondsSince(start);
  return result;
}

}  // namespace pliant::estimation
