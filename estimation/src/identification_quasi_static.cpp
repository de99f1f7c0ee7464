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
#include "quasi_static_report.h"

namespace pliant::estimation {
namespace {

constexpr double kAngleSdRad = 1e-3;  // scales the cost only; σ come from the sandwich

bool Recorded(const IdentificationData& data, int joint) {
  return std::any_of(data.samples.begin(), data.samples.end(), [&](const auto& s) {
    return std::isfinite(s.angle_rad[joint]) && std::isfinite(s.effort_nm[joint]);
  });
}

std::vector<const IdentificationSample*> ClampedSamples(const IdentificationData& data, int j) {
  std::vector<const IdentificationSample*> out;
  const std::set<int> loaded = detail::ClampsThatLoad(data, j);
  for (const auto& s : data.samples) {
    if (s.tip_fixed && loaded.count(s.segment) && std::isfinite(s.angle_rad[j]) && std::isfinite(s.effort_nm[j]) &&
        std::isfinite(s.insertion_depth_m))
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
  double held_friction_nm = 0.0, backlash_rad = 0.0;
  Eigen::MatrixXd sandwich, white;  // over (law ×4, F, δ), the law unscaled
  double rms_rad = 0.0;
  int clusters = 0;
  std::string summary;
};

// Clustered sandwich (clustered_sandwich.h): the rows of one clamp share
// their errors (unknown start, model error), so the score of each clamp is one
// draw, not each row's.
void Covariance(ceres::Problem* problem, const std::vector<double*>& blocks,
                const std::vector<int>& cluster_of_row, JointFit* fit) {
  Eigen::SparseMatrix<double> jacobian;
  Eigen::VectorXd r;
  detail::EvaluateJacobian(problem, blocks, {}, &jacobian, &r);
  // The global numbers are the last six columns: law (scaled) ×4, F, δ.
  std::vector<Eigen::Index> globals;
  for (Eigen::Index c = jacobian.cols() - 6; c < jacobian.cols(); ++c) globals.push_back(c);
  const detail::SandwichCovariance s =
      detail::ClusteredSandwich(jacobian, r, cluster_of_row, globals);
  const double dof = std::max(1.0, double(r.size() - jacobian.cols()));
  Eigen::VectorXd unscale(6);
  unscale << fit->law_scale[0], fit->law_scale[1], fit->law_scale[2], fit->law_scale[3], 1.0, 1.0;
  fit->white = unscale.asDiagonal() * (s.residual_square_sum / dof * s.model) * unscale.asDiagonal();
  // Never below the white noise's s²·H⁻¹, as the smoother's: with a tip per
  // clamp profiled out, a few clamps' scores can agree by chance, and the
  // sandwich alone put δ's σ at a tenth of the white σ on a generator whose
  // take-up the held friction does not describe.
  fit->sandwich =
      detail::NotBelow(unscale.asDiagonal() * s.clustered * unscale.asDiagonal(), fit->white);
  // Residuals were scaled by 1/kAngleSdRad: back to radians.
  fit->rms_rad = std::sqrt(r.squaredNorm() / double(r.size())) * kAngleSdRad;
}

JointFit FitJoint(const std::vector<const IdentificationSample*>& samples, int j,
                  const models::JointParameters& joint, const QuasiStaticOptions& options) {
  if (joint.compliance.form == models::ComplianceForm::kBeamSeries)
    throw std::invalid_argument("the quasi-static identification fits a cubic law "
                                "(--model inverse_cubic or direct_cubic)");
  JointFit fit;
  std::map<int, int> cluster;  // segment -> index
  for (const auto* s : samples) cluster.emplace(s->segment, int(cluster.size()));
  fit.clusters = int(cluster.size());
  fit.tips.assign(cluster.size(), 0.0);
  for (int i = 0; i < 4; ++i) {
    const double c = joint.compliance.cubic.coefficients[i];
    fit.law_scale[i] = c != 0.0 ? std::abs(c) : 1.0;
    fit.scaled_law[i] = c / fit.law_scale[i];
  }
  fit.held_friction_nm = options.held_friction ? 0.05 : 0.0;
  fit.backlash_rad = 1e-3;
  std::vector<double> n(cluster.size(), 0.0);
  for (const auto* s : samples) {  // tips: the mean angle of each clamp
    fit.tips[cluster[s->segment]] += s->angle_rad[j];
    n[cluster[s->segment]] += 1.0;
  }
  for (std::size_t c = 0; c < n.size(); ++c) fit.tips[c] /= n[c];

  ceres::Problem problem;
  std::vector<int> cluster_of_row;
  for (const auto* s : samples) {
    const double bias = models::BiasTorqueAt(joint, s->angle_rad[j], s->insertion_depth_m);
    problem.AddResidualBlock(
        detail::NewHeldFrictionAngleResidual(*s, j, joint.compliance.form, fit.law_scale, bias,
                                             options.presliding_travel_rad, kAngleSdRad),
        nullptr, &fit.tips[cluster[s->segment]], fit.scaled_law.data(), &fit.held_friction_nm,
        &fit.backlash_rad);
    cluster_of_row.push_back(cluster[s->segment]);
  }
  problem.SetParameterLowerBound(&fit.held_friction_nm, 0, 0.0);
  problem.SetParameterUpperBound(&fit.held_friction_nm, 0, 1.0);
  problem.SetParameterLowerBound(&fit.backlash_rad, 0, 0.0);  // a clearance is never negative
  problem.SetParameterUpperBound(&fit.backlash_rad, 0, 0.05);
  if (!options.held_friction) problem.SetParameterBlockConstant(&fit.held_friction_nm);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 200;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  fit.summary = "joint " + std::to_string(j + 1) + ": " + summary.BriefReport();
  std::vector<double*> blocks;
  for (auto& tip : fit.tips) blocks.push_back(&tip);
  blocks.push_back(fit.scaled_law.data());
  blocks.push_back(&fit.held_friction_nm);
  blocks.push_back(&fit.backlash_rad);
  Covariance(&problem, blocks, cluster_of_row, &fit);
  if (!options.held_friction) {  // held at 0: no uncertainty, no correlation
    fit.sandwich.row(4).setZero(), fit.sandwich.col(4).setZero();
    fit.white.row(4).setZero(), fit.white.col(4).setZero();
  }
  return fit;
}

void Store(const JointFit& fit, int j, const QuasiStaticOptions& options,
           const std::vector<const IdentificationSample*>& samples, IdentificationResult* result,
           std::vector<std::string>* names, std::vector<Eigen::MatrixXd>* blocks) {
  auto& joint = result->parameters.joints[j];
  for (int i = 0; i < 4; ++i)
    joint.compliance.cubic.coefficients[i] = fit.scaled_law[i] * fit.law_scale[i];
  joint.backlash_rad = fit.backlash_rad;
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
    const JointFit fit = FitJoint(samples, j, joint, options);
    Store(fit, j, options, samples, &result, &names, &blocks);
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
