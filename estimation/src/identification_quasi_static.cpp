#include "pliant/estimation/identification_quasi_static.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include "clustered_sandwich.h"
#include "identification_common.h"
#include "identification_costs.h"
#include "joint_smoother_width.h"
#include "quasi_static_report.h"

namespace pliant::estimation {
namespace {

constexpr double kAngleSdRad = 1e-3;  // scales the cost only; σ come from the sandwich
// The take-up width's floor: one effort sample's resolution on a Classic PSM
// (its noise, reference/dvrk.md); below it the dead zone is a step.
constexpr double kWidthFloorNm = 0.01;

bool Recorded(const IdentificationData& data, int joint) {
  return std::any_of(data.samples.begin(), data.samples.end(), [&](const auto& s) {
    return std::isfinite(s.angle_rad[joint]) && std::isfinite(s.effort_nm[joint]);
  });
}

std::vector<const IdentificationSample*> ClampedSamples(const IdentificationData& data, int j) {
  std::vector<const IdentificationSample*> out;
  const std::set<int> loaded = detail::ClampsThatLoad(data, j);
  for (const auto& s : data.samples) {
    if (s.tip_fixed && loaded.count(s.segment) && std::isfinite(s.angle_rad[j]) &&
        std::isfinite(s.effort_nm[j]) && std::isfinite(s.insertion_depth_m))
      out.push_back(&s);
  }
  return out;
}

int DistinctDepths(const std::vector<const IdentificationSample*>& samples) {
  std::map<long, int> depths;
  for (const auto* s : samples) depths[std::lround(s->insertion_depth_m / 0.005)] = 1;
  return int(depths.size());
}

// The solved problem of one joint, with what the covariance needs.
struct JointFit {
  std::vector<double> tips;
  std::array<double, 4> scaled_law{}, law_scale{};
  double held_friction_nm = 0.0, backlash_rad = 0.0, log_width = 0.0;
  bool width_above_floor = false;
  Eigen::MatrixXd sandwich, white;  // over (law ×4, F, δ), the law unscaled
  double rms_rad = 0.0;
  int clusters = 0;
  ceres::Solver::Summary solver;
  std::string summary;
};

// Clustered sandwich (clustered_sandwich.h): the rows of one clamp share
// their errors (unknown start, model error), so the score of each clamp is one
// draw, not each row's. `globals`: the trailing columns (law ×4, F, δ, and
// log w when the profile left it above its floor: its doubt is carried into
// the others', then dropped).
void Covariance(ceres::Problem* problem, const std::vector<double*>& blocks,
                const std::vector<int>& cluster_of_row, int globals, JointFit* fit) {
  Eigen::SparseMatrix<double> jacobian;
  Eigen::VectorXd r;
  detail::EvaluateJacobian(problem, blocks, {}, &jacobian, &r);
  std::vector<Eigen::Index> wanted;
  for (Eigen::Index c = jacobian.cols() - globals; c < jacobian.cols(); ++c) wanted.push_back(c);
  const detail::SandwichCovariance s =
      detail::ClusteredSandwich(jacobian, r, cluster_of_row, wanted);
  const double dof = std::max(1.0, double(r.size() - jacobian.cols()));
  Eigen::VectorXd unscale(6);
  unscale << fit->law_scale[0], fit->law_scale[1], fit->law_scale[2], fit->law_scale[3], 1.0, 1.0;
  const Eigen::MatrixXd clustered = s.clustered.topLeftCorner(6, 6);
  const Eigen::MatrixXd model = s.model.topLeftCorner(6, 6);
  fit->white = unscale.asDiagonal() * (s.residual_square_sum / dof * model) * unscale.asDiagonal();
  // Never below the white noise's s²·H⁻¹, as the smoother's: with a tip per
  // clamp profiled out, a few clamps' scores can agree by chance, and the
  // sandwich alone put δ's σ at a tenth of the white σ on a generator whose
  // take-up the held friction does not describe.
  fit->sandwich =
      detail::NotBelow(unscale.asDiagonal() * clustered * unscale.asDiagonal(), fit->white);
  // Residuals were scaled by 1/kAngleSdRad: back to radians.
  fit->rms_rad = std::sqrt(r.squaredNorm() / double(r.size())) * kAngleSdRad;
}

// One solve at a held take-up width, started from `start` (or from the prior
// and each clamp's mean angle); with `final`, w is freed for the covariance
// where it is above its floor.
JointFit SolveJoint(const std::vector<const IdentificationSample*>& samples, int j,
                    const models::JointParameters& joint, const QuasiStaticOptions& options,
                    double log_width, const JointFit* start, bool final,
                    bool hold_globals = false) {
  JointFit fit;
  std::map<int, int> cluster;  // segment -> index
  for (const auto* s : samples) cluster.emplace(s->segment, int(cluster.size()));
  if (start != nullptr) {
    fit = *start;
  } else {
    for (int i = 0; i < 4; ++i) {
      const double c = joint.compliance.cubic.coefficients[i];
      fit.law_scale[i] = c != 0.0 ? std::abs(c) : 1.0;
      fit.scaled_law[i] = c / fit.law_scale[i];
    }
    fit.held_friction_nm = options.held_friction ? 0.05 : 0.0;
    fit.backlash_rad = 1e-3;
  }
  if (fit.tips.size() != cluster.size()) {  // new clamps: each starts at its mean angle
    fit.tips.assign(cluster.size(), 0.0);
    std::vector<double> n(cluster.size(), 0.0);
    for (const auto* s : samples) {  // tips: the mean angle of each clamp
      fit.tips[cluster[s->segment]] += s->angle_rad[j];
      n[cluster[s->segment]] += 1.0;
    }
    for (std::size_t c = 0; c < n.size(); ++c) fit.tips[c] /= n[c];
  }
  fit.clusters = int(cluster.size());
  fit.log_width = log_width;

  ceres::Problem problem;
  std::vector<int> cluster_of_row;
  for (const auto* s : samples) {
    const double bias = models::BiasTorqueAt(joint, s->angle_rad[j], s->insertion_depth_m);
    problem.AddResidualBlock(
        detail::NewHeldFrictionAngleResidual(*s, j, joint.compliance.form, fit.law_scale, bias,
                                             options.presliding_travel_rad, kAngleSdRad),
        nullptr, &fit.tips[cluster[s->segment]], fit.scaled_law.data(), &fit.held_friction_nm,
        &fit.backlash_rad, &fit.log_width);
    cluster_of_row.push_back(cluster[s->segment]);
  }
  problem.SetParameterLowerBound(&fit.held_friction_nm, 0, 0.0);
  problem.SetParameterUpperBound(&fit.held_friction_nm, 0, 1.0);
  problem.SetParameterLowerBound(&fit.backlash_rad, 0, 0.0);  // a clearance is never negative
  problem.SetParameterUpperBound(&fit.backlash_rad, 0, 0.05);
  if (!options.held_friction) problem.SetParameterBlockConstant(&fit.held_friction_nm);
  problem.SetParameterBlockConstant(&fit.log_width);
  if (hold_globals) {  // only the clamps' tips: the fit predicting clamps it has not seen
    for (double* block : {fit.scaled_law.data(), &fit.held_friction_nm, &fit.backlash_rad})
      problem.SetParameterBlockConstant(block);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 200;
  ceres::Solve(solver, &problem, &fit.solver);
  fit.summary = "joint " + std::to_string(j + 1) + ": " + fit.solver.BriefReport();
  fit.rms_rad = std::sqrt(2.0 * fit.solver.final_cost / double(samples.size())) * kAngleSdRad;
  if (!final) return fit;
  problem.SetParameterBlockVariable(&fit.log_width);  // its doubt, where above its floor
  std::vector<double*> blocks;
  for (auto& tip : fit.tips) blocks.push_back(&tip);
  blocks.push_back(fit.scaled_law.data());
  blocks.push_back(&fit.held_friction_nm);
  blocks.push_back(&fit.backlash_rad);
  if (fit.width_above_floor) blocks.push_back(&fit.log_width);
  Covariance(&problem, blocks, cluster_of_row, fit.width_above_floor ? 7 : 6, &fit);
  if (!options.held_friction) {  // held at 0: no uncertainty, no correlation
    fit.sandwich.row(4).setZero(), fit.sandwich.col(4).setZero();
    fit.white.row(4).setZero(), fit.white.col(4).setZero();
  }
  return fit;
}

// The fits at the take-up width's floor (a hard wall) and at the width
// profiled as the smoother's (joint_smoother_width.h): held in each solve,
// Brent's method over log w from the floor to the largest load the clamps put
// on the joint, every solve started from the best so far.
struct WidthFits {
  JointFit floor, profiled;
};
WidthFits ProfiledFit(const std::vector<const IdentificationSample*>& samples, int j,
                      const models::JointParameters& joint, const QuasiStaticOptions& options) {
  double largest = 0.0;
  for (const auto* s : samples) {
    largest = std::max(largest, std::abs(s->effort_nm[j] - models::BiasTorqueAt(
                                             joint, s->angle_rad[j], s->insertion_depth_m)));
  }
  WidthFits out;
  out.floor = SolveJoint(samples, j, joint, options, std::log(kWidthFloorNm), nullptr, false);
  JointFit best = out.floor;
  detail::WidthSearch search;
  search.lower = {std::log(kWidthFloorNm), 0.0};
  search.upper = {std::max(search.lower[0], std::log(largest)), 0.0};
  search.search = {true, false};
  search.solve_at = [&](const std::array<double, 2>& log_width) {
    const JointFit last = SolveJoint(samples, j, joint, options, log_width[0], &best, false);
    if (last.solver.IsSolutionUsable() && last.solver.final_cost < best.solver.final_cost)
      best = last;
    return last.solver;
  };
  // Always searched (a negative slope at the floor): a clamp-by-clamp solve
  // is cheap, and on noisy poses the profile can rise from the floor before
  // it falls to a wider take-up (the third generator's noise ×3 at 100 Hz:
  // joint 2's δ 2.6 mrad at the floor, 5.0 true).
  search.slope = [] { return std::array<double, 2>{-1.0, 0.0}; };
  const detail::WidthProfile profile = detail::ProfileWidths(search);
  out.profiled = best;
  out.profiled.log_width = profile.log_width[0];
  out.profiled.width_above_floor = out.profiled.log_width > search.lower[0] + 0.1;  // 10 % above
  return out;
}

// The angle RMS on clamps of the other depth parity (ranked 5 mm bins, as
// clamped_cv.py), both ways round, of the fits at the floor and profiled
// (floor, profiled): only the clamps' tips are fitted on the held-out side.
std::array<double, 2> HeldOutRms(const std::vector<const IdentificationSample*>& samples, int j,
                                 const models::JointParameters& joint,
                                 const QuasiStaticOptions& options) {
  std::map<long, int> rank;
  for (const auto* s : samples) rank[std::lround(s->insertion_depth_m / 0.005)] = 0;
  int r = 0;
  for (auto& [bin, at] : rank) at = r++;
  std::array<double, 2> square_sum{0.0, 0.0};
  double rows = 0.0;
  for (int parity = 0; parity < 2; ++parity) {
    std::vector<const IdentificationSample*> train, test;
    for (const auto* s : samples)
      (rank[std::lround(s->insertion_depth_m / 0.005)] % 2 == parity ? train : test).push_back(s);
    const WidthFits fits = ProfiledFit(train, j, joint, options);
    for (int k = 0; k < 2; ++k) {
      JointFit start = k == 0 ? fits.floor : fits.profiled;
      start.tips.clear();
      const JointFit held =
          SolveJoint(test, j, joint, options, start.log_width, &start, false, true);
      square_sum[k] += held.rms_rad * held.rms_rad * double(test.size());
    }
    rows += double(test.size());
  }
  return {std::sqrt(square_sum[0] / rows), std::sqrt(square_sum[1] / rows)};
}

// The take-up width is kept above its floor only where that predicts clamps
// at depths the fit has not seen better than the hard wall: on the real JHU
// clamps a profiled width of 0.59 N·m took up what the law lacks and the
// held-out depths' spread grew (clamped_cv.py 1.52 → 1.56 mrad); on a
// generator's wide take-up it put K within 1 σ where the wall left it 13 σ off
// (docs/decisions/identify-auto-on-poses-of-both-joints.md).
JointFit FitJoint(const std::vector<const IdentificationSample*>& samples, int j,
                  const models::JointParameters& joint, const QuasiStaticOptions& options,
                  std::string* width_line) {
  if (joint.compliance.form == models::ComplianceForm::kBeamSeries)
    throw std::invalid_argument("the quasi-static identification fits a cubic law "
                                "(--model inverse_cubic or direct_cubic)");
  const WidthFits fits = ProfiledFit(samples, j, joint, options);
  JointFit best = fits.profiled;  // (within 10 % of the floor: the profile's minimum there)
  char line[200];
  if (fits.profiled.width_above_floor) {
    const auto [wall, profiled] = HeldOutRms(samples, j, joint, options);
    std::snprintf(line, sizeof line,
                  "  joint %d take-up width %.3g N·m %s (held-out depths' angle RMS %.3g mrad "
                  "against %.3g at the floor, %.3g N·m)\n",
                  j + 1, std::exp(fits.profiled.log_width), profiled < wall ? "kept" : "not kept",
                  1e3 * profiled, 1e3 * wall, kWidthFloorNm);
    if (!(profiled < wall)) best = fits.floor;
  } else {
    std::snprintf(line, sizeof line, "  joint %d take-up width at its floor, %.3g N·m\n", j + 1,
                  kWidthFloorNm);
  }
  *width_line = line;
  return SolveJoint(samples, j, joint, options, best.log_width, &best, true);
}

void Store(const JointFit& fit, int j, const QuasiStaticOptions& options,
           const std::vector<const IdentificationSample*>& samples, IdentificationResult* result,
           std::vector<std::string>* names, std::vector<Eigen::MatrixXd>* blocks) {
  auto& joint = result->parameters.joints[j];
  for (int i = 0; i < 4; ++i)
    joint.compliance.cubic.coefficients[i] = fit.scaled_law[i] * fit.law_scale[i];
  joint.backlash_rad = fit.backlash_rad;
  joint.deadzone_width_nm = std::exp(fit.log_width);
  // Equation (2)'s switch guards δ's sign against effort noise; on quasi-static
  // means δ is a fraction of a mrad (the held friction carries the loops'
  // width), and the switch would leave every load below tau_min uncorrected:
  // K·tau_min is 4–8 mrad on the real clamped beam.
  joint.tau_min_nm = 0.0;
  double lo = 1e9, hi = -1e9;
  for (const auto* s : samples) lo = std::min(lo, s->insertion_depth_m), hi = std::max(hi, s->insertion_depth_m);
  joint.depth_min_m = lo;
  joint.depth_max_m = hi;
  const std::string how = "pliant identify (quasi_static): clamped rows, clustered sandwich σ";
  joint.sources["compliance"] = how;
  joint.sources["backlash_rad"] = how;
  for (const auto& n : detail::LawNames(j, joint.compliance.form)) names->push_back(n);
  names->push_back("held_friction.held_friction" + std::to_string(j + 1));
  names->push_back("joint" + std::to_string(j + 1) + ".backlash_rad");
  blocks->push_back(fit.sandwich);
  result->angle_rms_rad[j] = fit.rms_rad;
  result->report += fit.summary + "\n";
  (void)options;
}

}  // namespace

IdentificationResult RunQuasiStaticIdentification(const IdentificationData& data,
                                                  const models::ModelParameters& prior,
                                                  const QuasiStaticOptions& options) {
  const double start = detail::NowSeconds();
  IdentificationResult result;
  result.method = "quasi_static";
  result.parameters = prior;
  result.parameters.covariance.reset();
  models::EffectParameters friction{"held_friction",
                                    {"held_friction1", "held_friction2", "presliding_travel"},
                                    {0.0, 0.0, options.presliding_travel_rad},
                                    {0.0, 0.0, 0.0}};
  std::vector<std::string> names;
  std::vector<Eigen::MatrixXd> blocks;
  bool any = false;
  for (int j = 0; j < 2; ++j) {
    const std::string joint_name = "joint " + std::to_string(j + 1);
    if (!Recorded(data, j)) {
      result.warnings.push_back(joint_name + " is not recorded in any log: its parameters are "
                                "the prior's, unchanged");
      continue;
    }
    auto& joint = result.parameters.joints[j];
    const auto table = FitBiasTable(data, j, options.bias_table_step_rad);
    if (table.angle_rad.empty()) {
      result.warnings.push_back(joint_name + " has no free-tip rows: its bias torque is the "
                                "prior's (tare it on the log's unloaded rows: pliant correct --tare)");
    } else {
      joint.bias_form = models::BiasForm::kTable;
      joint.bias_torque = table;
      joint.sources["bias_torque"] = "pliant identify (quasi_static): free-tip effort per 5°";
    }
    const auto samples = ClampedSamples(data, j);
    if (DistinctDepths(samples) < 5) {
      result.warnings.push_back(joint_name + " has clamped rows at fewer than 5 depths: its "
                                "compliance law and clearance are the prior's");
      continue;
    }
    any = true;
    std::string width_line;
    const JointFit fit = FitJoint(samples, j, joint, options, &width_line);
    Store(fit, j, options, samples, &result, &names, &blocks);
    result.report += width_line;
    friction.values[j] = fit.held_friction_nm;
    friction.sd[j] = std::sqrt(std::max(0.0, fit.sandwich(4, 4)));
    const double scatter = detail::DescribeMisfit(data, result.parameters, friction, j, options,
                                                  fit.white, fit.sandwich, &result);
    // A new depth's 1/K scatters about the law beyond the law's own doubt:
    // for an inverse cubic that scatter is an offset of c0 (the 1/K at every
    // L), so K(L)'s σ covers a held-out depth, not only the mean law.
    if (joint.compliance.form == models::ComplianceForm::kInverseCubic)
      blocks.back()(3, 3) += scatter * scatter;
  }
  if (!any) {
    throw std::invalid_argument("no joint has clamped (tip_fixed) rows at 5 or more depths — "
                                "add a clamped-beam log of each joint to identify");
  }
  if (options.held_friction) result.parameters.effects = {friction};
  Eigen::Index size = 0;
  for (const auto& b : blocks) size += b.rows();
  models::ParameterCovariance covariance{names, Eigen::MatrixXd::Zero(size, size)};
  Eigen::Index at = 0;
  for (const auto& b : blocks) covariance.matrix.block(at, at, b.rows(), b.cols()) = b, at += b.rows();
  result.parameters.covariance = covariance;
  result.condition_number = detail::CorrelationCondition(covariance.matrix);
  result.seconds = detail::SecondsSince(start);
  return result;
}

}  // namespace pliant::estimation
