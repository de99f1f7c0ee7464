#include "joint_smoother_setup.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "identification_costs.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/models/effects/compliance.h"

namespace pliant::estimation::detail {
namespace {

using FourierEffect = models::BiasTorqueFourierEffect;

// Basis of the Fourier bias, in the order of its coefficients; the depth
// slope's and the depth harmonic's (c1, d1) columns are zero where they are held.
Eigen::RowVectorXd BiasBasis(double q, double depth_m, const JointSmootherOptions& options,
                             bool slope, std::array<bool, 2> harmonic) {
  const int h = options.bias_harmonics;
  const double lever = depth_m - options.bias_reference_depth_m;
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(FourierEffect::ParameterCount(h));
  row[0] = 1.0;
  for (int k = 1; k <= h; ++k) row[2 * k - 1] = std::cos(k * q), row[2 * k] = std::sin(k * q);
  if (slope) row[FourierEffect::DepthSlopeIndex(h)] = lever;
  if (harmonic[0]) row[FourierEffect::DepthHarmonicIndex(h)] = lever * std::cos(q);
  if (harmonic[1]) row[FourierEffect::DepthHarmonicIndex(h) + 1] = lever * std::sin(q);
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
    const int h = options.bias_harmonics;
    const auto bias_specs = FourierEffect(h).Parameters();
    const int n = FourierEffect::ParameterCount(h);
    out.bias[j].assign(std::size_t(n), 0.0);
    out.bias_sd[j].resize(std::size_t(n));
    for (int i = 0; i < n; ++i) out.bias_sd[j][i] = s * bias_specs[i].prior_sd;
    if (joint.bias_form == models::BiasForm::kFourier) {
      const auto& f = joint.bias_fourier;
      for (int i = 0; i <= 2 * h && i < int(f.coefficients.size()); ++i)
        out.bias[j][i] = f.coefficients[i];
      const double shift = options.bias_reference_depth_m - f.reference_depth_m;
      out.bias[j][FourierEffect::DepthSlopeIndex(h)] = f.depth_slope_nm_per_m;
      out.bias[j][0] += f.depth_slope_nm_per_m * shift;
      for (int i = 0; i < 2; ++i) {
        out.bias[j][FourierEffect::DepthHarmonicIndex(h) + i] = f.depth_harmonic_nm_per_m[i];
        if (h > 0) out.bias[j][1 + i] += f.depth_harmonic_nm_per_m[i] * shift;
      }
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
  return BiasBasis(sample.angle_rad[joint], sample.insertion_depth_m, options, true, {true, true})
      .dot(c);
}

SmootherState MakeInitialState(const IdentificationData& data, const SmootherPrior& prior,
                               const IdentificationResult& paper,
                               const JointSmootherOptions& options,
                               const UndeterminedParameters& held) {
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
      rows.push_back(BiasBasis(s.angle_rad[j], s.insertion_depth_m, options,
                               options.bias_depth_term,
                               {!held.depth_harmonic[j][0], !held.depth_harmonic[j][1]}));
      efforts.push_back(s.effort_nm[j]);
    }
    const long n = long(state.bias[j].size());
    if (long(rows.size()) >= 2 * n) {
      Eigen::MatrixXd X(long(rows.size()), n);
      Eigen::VectorXd y(long(rows.size()));
      for (std::size_t r = 0; r < rows.size(); ++r) X.row(long(r)) = rows[r], y[long(r)] = efforts[r];
      const Eigen::VectorXd c = X.colPivHouseholderQr().solve(y);
      for (long i = 0; i < n; ++i) state.bias[j][i] = c[i];
      for (int i = 0; i < 2; ++i) {
        const int at = FourierEffect::DepthHarmonicIndex(options.bias_harmonics) + i;
        if (held.depth_harmonic[j][i]) state.bias[j][at] = prior.bias[j][at];
      }
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

void HoldUndeterminedDepthHarmonic(const IdentificationData& data, const SmootherPrior& prior,
                                   const JointSmootherOptions& options,
                                   UndeterminedParameters* held) {
  const int h = options.bias_harmonics, n = FourierEffect::ParameterCount(h);
  const int at = FourierEffect::DepthHarmonicIndex(h);
  for (int j = 0; j < 2; ++j) {
    // The information of the free-tip rows plus the prior's, every bias
    // coefficient free: the posterior sd of c1 and d1 says what the rows fix.
    Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) information(i, i) = 1.0 / std::pow(prior.bias_sd[j][i], 2);
    for (const auto& s : data.samples) {
      if (s.tip_fixed || !std::isfinite(s.angle_rad[j]) || !std::isfinite(s.effort_nm[j])) continue;
      const Eigen::RowVectorXd x = BiasBasis(s.angle_rad[j], s.insertion_depth_m, options,
                                             options.bias_depth_term, {true, true});
      information += x.transpose() * x * (double(s.rows) / std::pow(options.effort_noise_nm, 2));
    }
    const Eigen::MatrixXd covariance = information.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
    for (int i = 0; i < 2; ++i) {
      const double sd = std::sqrt(covariance(at + i, at + i));
      held->depth_harmonic[j][i] = !options.bias_depth_harmonic || held->bias[j] ||
                                   !(sd <= options.identified_fraction * prior.bias_sd[j][at + i]);
    }
  }
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
