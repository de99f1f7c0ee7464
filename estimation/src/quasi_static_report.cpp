#include "quasi_static_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/Dense>

#include "identification_common.h"
#include "pliant/estimation/extra_effects.h"

namespace pliant::estimation {
namespace {

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

struct Row {
  double angle, load, depth, travel;
};

// tau_e of every clamped row of joint j, grouped by clamp.
std::map<int, std::vector<Row>> Loads(const IdentificationData& data,
                                      const models::ModelParameters& parameters, int j) {
  const ExtraEffects extra(parameters.effects);
  std::map<int, std::vector<Row>> out;
  const std::set<int> loaded = detail::ClampsThatLoad(data, j);
  for (const auto& s : data.samples) {
    if (!s.tip_fixed || !loaded.count(s.segment) || !std::isfinite(s.angle_rad[j]) ||
        !std::isfinite(s.effort_nm[j]))
      continue;
    models::JointState<double> state;
    state.travel_since_reversal_rad = s.travel_since_reversal_rad;
    const double load = s.effort_nm[j] -
                        models::BiasTorqueAt(parameters.joints[j], s.angle_rad[j],
                                             s.insertion_depth_m) -
                        extra.InternalTorque(state)[j];
    out[s.segment].push_back({s.angle_rad[j], load, s.insertion_depth_m,
                              s.travel_since_reversal_rad[j]});
  }
  return out;
}

double Sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

std::vector<DepthEstimate> PerDepthSlopes(const IdentificationData& data,
                                          const models::ModelParameters& parameters, int j,
                                          double /*presliding_travel_rad*/) {
  std::vector<DepthEstimate> out;
  const double delta = parameters.joints[j].backlash_rad;
  for (const auto& [segment, rows] : Loads(data, parameters, j)) {
    if (rows.size() < 5) continue;
    Eigen::MatrixXd a(rows.size(), 2);
    Eigen::VectorXd y(rows.size());
    double depth = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      a(i, 0) = 1.0, a(i, 1) = rows[i].load;
      y[i] = rows[i].angle - delta * Sign(rows[i].load);
      depth += rows[i].depth / rows.size();
    }
    const Eigen::Vector2d x = a.colPivHouseholderQr().solve(y);
    const Eigen::VectorXd r = y - a * x;
    const double s2 = r.squaredNorm() / std::max<double>(1.0, double(rows.size()) - 2.0);
    const double sd_k = std::sqrt(s2 * (a.transpose() * a).inverse()(1, 1));
    DepthEstimate e;
    e.joint = j;
    e.insertion_depth_m = depth;
    e.inverse_compliance_nm_per_rad = 1.0 / x[1];
    e.inverse_compliance_sd = sd_k / (x[1] * x[1]);
    e.backlash_rad = delta;
    e.loaded_samples = int(rows.size());
    out.push_back(e);
  }
  return out;
}

namespace detail {

double DescribeMisfit(const IdentificationData& data, models::ModelParameters& parameters,
                    const models::EffectParameters& friction, int j,
                    const QuasiStaticOptions& options, const Eigen::MatrixXd& white,
                    const Eigen::MatrixXd& sandwich, IdentificationResult* result) {
  models::ModelParameters with = parameters;
  with.effects = {friction};
  if (!options.held_friction) with.effects.clear();
  const std::string name = "joint " + std::to_string(j + 1);
  auto& joint = parameters.joints[j];
  const auto loads = Loads(data, with, j);
  // Residual per clamp and branch: tip = the clamp's mean corrected angle.
  std::vector<std::pair<double, std::string>> depth_rms;
  for (const auto& [segment, rows] : loads) {
    std::vector<double> corrected;
    double mean = 0.0;
    for (const auto& r : rows) {
      corrected.push_back(r.angle - models::ComplianceAt(joint, r.depth) * r.load -
                          joint.backlash_rad * Sign(r.load));
      mean += corrected.back() / rows.size();
    }
    double all = 0.0, up = 0.0, down = 0.0;
    int n_up = 0, n_down = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double e = corrected[i] - mean;
      all += e * e;
      if (rows[i].travel > 0.0) up += e, ++n_up;
      if (rows[i].travel < 0.0) down += e, ++n_down;
    }
    const double rms = std::sqrt(all / rows.size());
    const double worst = std::abs(n_up ? up / n_up : 0.0) > std::abs(n_down ? down / n_down : 0.0)
                             ? (n_up ? up / n_up : 0.0) : (n_down ? down / n_down : 0.0);
    const bool upward = std::abs(n_up ? up / n_up : 0.0) >= std::abs(n_down ? down / n_down : 0.0);
    depth_rms.emplace_back(rms, Format("depth %.3f m: corrected angle spreads by %.2f mrad RMS; ",
                                       rows.front().depth, 1e3 * rms) +
                                    (upward ? "the branch moving toward +q" : "the branch moving toward -q") +
                                    Format(" sits %+.2f mrad off the clamp's mean", 1e3 * worst));
  }
  std::vector<double> sorted;
  for (const auto& d : depth_rms) sorted.push_back(d.first);
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
  for (const auto& [rms, words] : depth_rms) {
    if (rms > options.misfit_factor * median)
      result->warnings.push_back(name + " does not fit at " + words + Format(" (median depth %.2f mrad)", 1e3 * median));
  }
  // Per-depth slopes against the law: the depth-to-depth scatter joins c0.
  auto slopes = PerDepthSlopes(data, with, j, options.presliding_travel_rad);
  double scatter = 0.0;
  for (const auto& e : slopes) {
    const double law = 1.0 / models::ComplianceAt(joint, e.insertion_depth_m);
    scatter += std::pow(e.inverse_compliance_nm_per_rad - law, 2);
  }
  const double dof = std::max(1.0, double(slopes.size()) - 4.0);
  const double scatter_sd = std::sqrt(scatter / dof);
  result->depth_estimates.insert(result->depth_estimates.end(), slopes.begin(), slopes.end());
  result->report += Format("  joint %.0f: depth-to-depth scatter of 1/K about the law %.3g N·m/rad",
                           j + 1.0, scatter_sd) +
                    Format(" (%.0f depths); held friction %.4f N·m, σ white %.2g", double(slopes.size()),
                           friction.values[j], std::sqrt(std::max(0.0, white(4, 4)))) +
                    Format(", clustered %.2g; clearance σ white %.2g", std::sqrt(std::max(0.0, sandwich(4, 4))),
                           std::sqrt(std::max(0.0, white(5, 5)))) +
                    Format(", clustered %.2g rad\n", std::sqrt(std::max(0.0, sandwich(5, 5))));
  if (joint.backlash_rad == 0.0) {
    result->warnings.push_back(
        name + Format(" clearance δ is at its bound 0: the clamped loops show no clearance beyond "
                      "the held friction (95 %% upper limit %.2f mrad)",
                      1e3 * 1.645 * std::sqrt(std::max(0.0, sandwich(5, 5)))));
  }
  return scatter_sd;
}

}  // namespace detail
}  // namespace pliant::estimation
