#include "joint_smoother_setup.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "identification_costs.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/models/effects/compliance.h"

namespace pliant::estimation::detail {
namespace {

// Basis of the Fourier bias, in the order of its coefficients.
Eigen::RowVectorXd BiasBasis(double q, double depth_m, const JointSmootherOptions& options) {
  const int h = options.bias_harmonics;
  Eigen::RowVectorXd row(2 * h + 2);
  row[0] = 1.0;
  for (int k = 1; k <= h; ++k) row[2 * k - 1] = std::cos(k * q), row[2 * k] = std::sin(k * q);
  row[2 * h + 1] = options.bias_depth_term ? depth_m - options.bias_reference_depth_m : 0.0;
  return row;
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

models::ComplianceLaw ConvertLaw(const models::JointParameters& joint, models::ComplianceForm form,
                                 double cannula_length_m) {
  if (joint.compliance.form == form) return joint.compliance;
  std::vector<DepthCompliance> points;
  for (int i = 0; i < 14; ++i) {
    const double depth = joint.depth_min_m + (joint.depth_max_m - joint.depth_min_m) * i / 13.0;
    points.push_back({depth, 1.0 / models::ComplianceAt(joint, depth), 1.0});
  }
  return FitComplianceLaw(form, points, false, cannula_length_m).law;
}

SmootherPrior MakePrior(const models::ModelParameters& prior, const JointSmootherOptions& options) {
  SmootherPrior out;
  const double s = options.prior_scale;
  for (int j = 0; j < 2; ++j) {
    const auto& joint = prior.joints[j];
    models::JointParameters both[2] = {joint, joint};
    both[0].compliance = both[1].compliance = ConvertLaw(joint, options.law, options.cannula_length_m);
    const auto specs = models::ComplianceEffect(both[0], both[1]).Parameters();
    for (int i = 0; i < 4; ++i) {
      out.law[j][i] = both[0].compliance.cubic.coefficients[i];
      out.law_sd[j][i] = s * specs[i].prior_sd;
    }
    out.delta_rad[j] = joint.backlash_rad;
    out.delta_sd[j] = s * 0.004;  // the backlash effects' prior (models/src/effects.cpp)
    out.log_width[j] = std::log(joint.deadzone_width_nm);
    out.log_width_sd[j] = s * 1.0;  // a factor e either way
    const auto bias_specs = models::BiasTorqueFourierEffect(options.bias_harmonics).Parameters();
    const int n = 2 * options.bias_harmonics + 2;
    out.bias[j].assign(n, 0.0);
    out.bias_sd[j].resize(n);
    for (int i = 0; i < n; ++i) out.bias_sd[j][i] = s * bias_specs[i].prior_sd;
    if (joint.bias_form == models::BiasForm::kFourier) {
      const auto& f = joint.bias_fourier;
      for (int i = 0; i < n - 1 && i < int(f.coefficients.size()); ++i) out.bias[j][i] = f.coefficients[i];
      out.bias[j][n - 1] = f.depth_slope_nm_per_m;
      out.bias[j][0] += f.depth_slope_nm_per_m * (options.bias_reference_depth_m - f.reference_depth_m);
    } else {
      double mean = 0.0;  // a table's mean level: the paper's files are nearly flat
      for (double t : joint.bias_torque.torque_nm) mean += t / double(joint.bias_torque.torque_nm.size());
      out.bias[j][0] = mean;
    }
  }
  return out;
}

double BiasOf(const SmootherState& state, int joint, const IdentificationSample& sample,
              const JointSmootherOptions& options) {
  const Eigen::Map<const Eigen::VectorXd> c(state.bias[joint].data(), long(state.bias[joint].size()));
  return BiasBasis(sample.angle_rad[joint], sample.insertion_depth_m, options).dot(c);
}

SmootherState MakeInitialState(const IdentificationData& data, const SmootherPrior& prior,
                               const IdentificationResult& paper,
                               const JointSmootherOptions& options) {
  SmootherState state;
  state.law = prior.law;
  state.delta_rad = prior.delta_rad;
  state.log_width = prior.log_width;
  state.bias = prior.bias;
  const int law_size = options.law == models::ComplianceForm::kBeamSeries ? 3 : 4;
  for (int j = 0; j < 2; ++j) {
    std::vector<DepthCompliance> points;
    std::vector<double> deltas;
    for (const auto& e : paper.depth_estimates) {
      if (e.joint != j) continue;
      points.push_back({e.insertion_depth_m, e.inverse_compliance_nm_per_rad, e.inverse_compliance_sd});
      deltas.push_back(e.backlash_rad);
    }
    if (int(points.size()) >= law_size) {
      state.law[j] = FitComplianceLaw(options.law, points, true, options.cannula_length_m).law.cubic.coefficients;
    }
    if (!deltas.empty()) state.delta_rad[j] = std::max(1e-4, Median(deltas));
    // The bias is linear in its coefficients: least squares on the free tip.
    std::vector<Eigen::RowVectorXd> rows;
    std::vector<double> efforts;
    for (const auto& s : data.samples) {
      if (s.tip_fixed) continue;
      rows.push_back(BiasBasis(s.angle_rad[j], s.insertion_depth_m, options));
      efforts.push_back(s.effort_nm[j]);
    }
    const long n = long(state.bias[j].size());
    if (long(rows.size()) >= 2 * n) {
      Eigen::MatrixXd X(long(rows.size()), n);
      Eigen::VectorXd y(long(rows.size()));
      for (std::size_t r = 0; r < rows.size(); ++r) X.row(long(r)) = rows[r], y[long(r)] = efforts[r];
      const Eigen::VectorXd c = X.colPivHouseholderQr().solve(y);
      for (long i = 0; i < n; ++i) state.bias[j][i] = c[i];
    }
  }
  // Latents: the load the effort shows, and the tip the encoders imply under it.
  const std::array<models::ComplianceForm, 2> forms{options.law, options.law};
  std::map<int, std::array<std::vector<double>, 2>> tips;
  state.tau_ext_nm.resize(data.samples.size(), {0.0, 0.0});
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const auto& s = data.samples[i];
    if (!s.tip_fixed) continue;
    for (int j = 0; j < 2; ++j) {
      const double tau = s.effort_nm[j] - BiasOf(state, j, s, options);
      state.tau_ext_nm[i][j] = tau;
      tips[s.segment][j].push_back(s.angle_rad[j] - Deflection(j, forms, state.law[j].data(),
                                                               state.delta_rad[j], state.log_width[j],
                                                               tau, s.insertion_depth_m));
    }
  }
  for (const auto& [segment, values] : tips) {
    state.tip_rad[segment] = {Median(values[0]), Median(values[1])};
  }
  return state;
}

}  // namespace pliant::estimation::detail

namespace pliant::estimation {

bool JointSmootherOptions::IsValid(std::string* error) const {
  if (bias_harmonics < 0 || bias_harmonics > detail::kMaxBiasHarmonics) {
    *error = "bias_harmonics must be in [0, " + std::to_string(detail::kMaxBiasHarmonics) + "]";
    return false;
  }
  if (!(effort_noise_nm > 0.0) || !(encoder_noise_rad > 0.0) || !(robust_loss_sd > 0.0) ||
      !(prior_scale > 0.0)) {
    *error = "effort_noise_nm, encoder_noise_rad, robust_loss_sd and prior_scale must be > 0";
    return false;
  }
  if (!(deadzone_resolution_sd > 0.0)) {
    *error = "deadzone_resolution_sd must be > 0";
    return false;
  }
  if (max_iterations < 1 || threads < 1 || !(identified_fraction > 0.0)) {
    *error = "max_iterations and threads must be >= 1, identified_fraction > 0";
    return false;
  }
  return paper.IsValid(error);
}

}  // namespace pliant::estimation
