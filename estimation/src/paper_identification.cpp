// The paper's procedure (sections 3–5), step by step, with the uncertainty of
// every step carried to the parameters.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "pliant/models/paper_parameters.h"
#include "branch_classifier.h"
#include "identification_common.h"
#include "pliant/estimation/identification.h"

namespace pliant::estimation {
namespace {

// Ordinary least squares effort = a + b·q with the covariance of (a, b).
struct Line {
  double a = 0.0, b = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  double residual_rms = 0.0;
  int points = 0;
};

// Which held tip each sample is on, counted over the logs: a hold begins
// where a log begins or a held sample follows a free one. A clamped beam's
// loops at one depth are one clamp; each divot push, reached through free
// motion, is another, with its own tip angle.
std::vector<int> ClampOf(const IdentificationData& data) {
  std::vector<int> clamp(data.samples.size(), 0);
  int count = 0;
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const auto& s = data.samples[i];
    const bool begins = i == 0 || s.log != data.samples[i - 1].log || !data.samples[i - 1].tip_fixed;
    if (s.tip_fixed && begins) ++count;
    clamp[i] = count;
  }
  return clamp;
}

Line FitLine(const std::vector<double>& q, const std::vector<double>& tau) {
  Line line;
  line.points = int(q.size());
  double mq = 0.0, mt = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) mq += q[i], mt += tau[i];
  mq /= double(q.size());
  mt /= double(q.size());
  double sqq = 0.0, sqt = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    sqq += (q[i] - mq) * (q[i] - mq);
    sqt += (q[i] - mq) * (tau[i] - mt);
  }
  line.b = sqt / sqq;
  line.a = mt - line.b * mq;
  double rss = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) rss += std::pow(tau[i] - line.a - line.b * q[i], 2);
  const double s2 = rss / double(q.size() - 2);
  line.residual_rms = std::sqrt(rss / double(q.size()));
  // Var(b) = s²/Sqq; a = mean − b·mq.
  const double var_b = s2 / sqq;
  line.covariance << s2 / double(q.size()) + mq * mq * var_b, -mq * var_b, -mq * var_b, var_b;
  return line;
}

// Position where a line reaches effort `tau` and its variance.
std::pair<double, double> Crossing(const Line& line, double tau) {
  const double q = (tau - line.a) / line.b;
  const Eigen::Vector2d gradient(-1.0 / line.b, -(tau - line.a) / (line.b * line.b));
  return {q, gradient.dot(line.covariance * gradient)};
}

}  // namespace

bool PaperProcedureOptions::IsValid(std::string* error) const {
  if (!(contact_threshold_nm[0] > 0.0 && contact_threshold_nm[1] > 0.0)) {
    *error = "contact_threshold_nm must be > 0 for both joints";
    return false;
  }
  if (!(bias_table_step_rad > 0.0) || !(depth_resolution_m > 0.0) || !(cannula_length_m >= 0.0)) {
    *error = "bias_table_step_rad and depth_resolution_m must be > 0, cannula_length_m >= 0";
    return false;
  }
  return true;
}

models::BiasTorqueTable FitBiasTable(const IdentificationData& data, int joint, double step_rad) {
  std::map<long, std::array<double, 3>> bins;  // bin -> {Σ rows·q, Σ rows·tau, Σ rows}
  for (const auto& s : data.samples) {
    if (s.tip_fixed || !std::isfinite(s.angle_rad[joint]) || !std::isfinite(s.effort_nm[joint]))
      continue;  // a clamped row, or a joint the log does not record
    auto& bin = bins[std::lround(s.angle_rad[joint] / step_rad)];
    bin[0] += s.rows * s.angle_rad[joint];
    bin[1] += s.rows * s.effort_nm[joint];
    bin[2] += s.rows;
  }
  models::BiasTorqueTable table;
  for (const auto& [key, bin] : bins) {
    table.angle_rad.push_back(bin[0] / bin[2]);
    table.torque_nm.push_back(bin[1] / bin[2]);
  }
  return table;
}

models::ModelParameters PaperPrior() { return models::PaperParameters(); }

IdentificationResult RunPaperProcedure(const IdentificationData& data,
                                       const models::ModelParameters& prior,
                                       const PaperProcedureOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("paper procedure options: " + why);
  const double start = detail::NowSeconds();
  IdentificationResult result;
  result.method = "paper";
  models::ModelParameters& p = result.parameters;
  p = prior;
  p.covariance.reset();
  for (int j = 0; j < 2; ++j) {
    const auto table = FitBiasTable(data, j, options.bias_table_step_rad);
    if (table.angle_rad.empty()) continue;
    p.joints[j].bias_form = models::BiasForm::kTable;
    p.joints[j].bias_torque = table;
    p.joints[j].sources["bias_torque"] = "pliant identify (paper): free-tip effort averaged per " +
                                         std::to_string(options.bias_table_step_rad) + " rad";
  }
  const detail::BranchClassifier branches(data, p, options.contact_threshold_nm);

  std::vector<std::string> names;
  std::vector<std::string> clamped_backlash;  // warnings for a crossed pair of branch lines
  std::vector<std::pair<std::vector<int>, Eigen::MatrixXd>> blocks;
  const std::vector<int> clamp = ClampOf(data);
  for (int j = 0; j < 2; ++j) {
    // Per clamp and depth: the two branches' (position, effort) points. Two
    // clamps are two tips: their lines need not coincide, and a depth's
    // pushes from many tips are no lines at all (their scatter is the tips').
    using Key = std::pair<int, long>;  // clamp, depth
    std::map<Key, std::array<std::vector<double>, 4>> depths;  // q+, tau+, q−, tau−
    std::map<Key, std::pair<double, int>> reference;  // Σ tau_ref, count
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
      const int side = branches.side[j][i];
      if (side == 0) continue;
      const auto& s = data.samples[i];
      const Key key{clamp[i], detail::DepthKey(s.insertion_depth_m, options.depth_resolution_m)};
      auto& d = depths[key];
      d[side > 0 ? 0 : 2].push_back(s.angle_rad[j]);
      d[side > 0 ? 1 : 3].push_back(s.effort_nm[j]);
      reference[key].first += branches.reference_effort_nm[j][i];
      reference[key].second += 1;
    }
    std::vector<DepthCompliance> points;
    std::vector<double> deltas, delta_vars;
    double sum2 = 0.0;
    int count = 0;
    for (const auto& [key, d] : depths) {
      if (d[0].size() < 3 || d[2].size() < 3) continue;  // a line needs a spread of points
      const Line plus = FitLine(d[0], d[1]), minus = FitLine(d[2], d[3]);
      const double tau_ref = reference[key].first / reference[key].second;
      const auto [q_plus, var_plus] = Crossing(plus, tau_ref);
      const auto [q_minus, var_minus] = Crossing(minus, tau_ref);
      DepthEstimate e;
      e.joint = j;
      e.insertion_depth_m = double(key.second) * options.depth_resolution_m;
      e.inverse_compliance_nm_per_rad = 0.5 * (plus.b + minus.b);
      e.inverse_compliance_sd = 0.5 * std::sqrt(plus.covariance(1, 1) + minus.covariance(1, 1));
      e.backlash_rad = 0.5 * (q_plus - q_minus);  // δ is half the gap (equation 1)
      e.backlash_sd = 0.5 * std::sqrt(var_plus + var_minus);
      e.loaded_samples = plus.points + minus.points;
      result.depth_estimates.push_back(e);
      points.push_back({e.insertion_depth_m, e.inverse_compliance_nm_per_rad, e.inverse_compliance_sd});
      deltas.push_back(e.backlash_rad);
      delta_vars.push_back(e.backlash_sd * e.backlash_sd);
      sum2 += plus.residual_rms * plus.residual_rms * plus.points +
              minus.residual_rms * minus.residual_rms * minus.points;
      count += plus.points + minus.points;
    }
    if (count > 0) {
      result.effort_rms_nm[j] = std::sqrt(sum2 / count);
      double mean_slope = 0.0;
      for (const auto& point : points) mean_slope += point.inverse_compliance_nm_per_rad;
      result.angle_rms_rad[j] = result.effort_rms_nm[j] / (mean_slope / double(points.size()));
    }
    auto& joint = p.joints[j];
    const int law_size = options.law == models::ComplianceForm::kBeamSeries ? 3 : 4;
    if (int(points.size()) >= law_size) {
      const ComplianceLawFit fit = FitComplianceLaw(options.law, points, false, options.cannula_length_m);
      joint.compliance = fit.law;
      joint.sources["compliance"] = "pliant identify (paper): " + std::string(models::ComplianceFormName(options.law)) +
                                    " through " + std::to_string(points.size()) + " per-depth slopes";
      double lo = 1e9, hi = 0.0;
      for (const auto& point : points) lo = std::min(lo, point.insertion_depth_m), hi = std::max(hi, point.insertion_depth_m);
      joint.depth_min_m = lo;
      joint.depth_max_m = hi;
      std::vector<int> idx;
      for (const auto& name : detail::LawNames(j, options.law)) idx.push_back(int(names.size())), names.push_back(name);
      blocks.push_back({idx, fit.covariance});
    }
    if (!deltas.empty()) {
      const double n = double(deltas.size());
      double mean = 0.0, var = 0.0, mean_var = 0.0;
      for (std::size_t k = 0; k < deltas.size(); ++k) mean += deltas[k] / n, mean_var += delta_vars[k] / (n * n);
      for (double d : deltas) var += (d - mean) * (d - mean) / std::max(1.0, n - 1.0);
      joint.backlash_rad = std::max(0.0, mean);  // a clearance is >= 0: crossed lines say 0
      if (mean < 0.0) {
        char text[320];
        std::snprintf(text, sizeof text,
                      "joint %d: the loading and unloading lines cross (half their gap %.3g ± "
                      "%.2g rad over %zu depths): a clearance cannot be negative, so delta%d is "
                      "written as 0; these data do not resolve it (push further both ways, or "
                      "use --method smoother)",
                      j + 1, mean, std::sqrt(std::max(var / n, mean_var)), deltas.size(), j + 1);
        clamped_backlash.push_back(text);
      }
      joint.sources["backlash_rad"] = "pliant identify (paper): half the gap between the branch lines, mean of " +
                                      std::to_string(deltas.size()) + " depths";
      names.push_back("joint" + std::to_string(j + 1) + ".backlash_rad");
      // The scatter between depths when there is one, else the lines' own error.
      blocks.push_back({{int(names.size()) - 1},
                        Eigen::MatrixXd::Constant(1, 1, n > 1 ? std::max(var / n, mean_var) : mean_var)});
    }
  }
  if (!names.empty()) {
    models::ParameterCovariance covariance;
    covariance.names = names;
    covariance.matrix = Eigen::MatrixXd::Zero(long(names.size()), long(names.size()));
    for (const auto& [idx, m] : blocks) {
      for (std::size_t a = 0; a < idx.size(); ++a)
        for (std::size_t b = 0; b < idx.size(); ++b) covariance.matrix(idx[a], idx[b]) = m(long(a), long(b));
    }
    result.condition_number = detail::CorrelationCondition(covariance.matrix);
    p.covariance = covariance;
  }
  result.warnings = IdentifiabilityWarnings(data, p, options,
                                            options.law == models::ComplianceForm::kBeamSeries ? 3 : 4);
  result.warnings.insert(result.warnings.end(), clamped_backlash.begin(), clamped_backlash.end());
  result.report = "paper procedure: " + std::to_string(result.depth_estimates.size()) +
                  " depth lines, closed-form least squares";
  result.seconds = detail::SecondsSince(start);
  return result;
}

}  // namespace pliant::estimation
