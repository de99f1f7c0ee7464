// The joint smoother's results: noise levels, covariance, parameters, warnings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "branch_classifier.h"
#include "identification_common.h"
#include "identification_costs.h"
#include "joint_smoother_setup.h"
#include "pliant/models/effects/bias_torque_fourier.h"

namespace pliant::estimation::detail {
namespace {

// For a Gaussian residual of sd s, median(r²) = 0.4549·s² (the χ²₁ median):
// a noise level that a few bad samples (a leg the protocol cut short, a row
// taken as the joint settled) do not inflate. Model error in the bulk of the
// samples is charged to the covariance afterwards (the variance factor in
// joint_smoother.cpp).
constexpr double kChiSquare1Median = 0.45493642311957;

double NoiseScale(std::vector<double> squares) {
  if (squares.size() < 10) return 1.0;
  std::nth_element(squares.begin(), squares.begin() + long(squares.size() / 2), squares.end());
  return std::sqrt(squares[squares.size() / 2] / kChiSquare1Median);
}

struct Residuals {
  std::array<std::vector<double>, 2> free_squares, fixed_squares;  // whitened
  std::array<double, 2> angle_sum2{}, effort_sum2{};               // raw
  std::array<int, 2> angle_count{}, effort_count{};
};

Residuals Evaluate(const IdentificationData& data, const SmootherState& state,
                   const JointSmootherOptions& options, const SmootherNoise& noise) {
  Residuals out;
  const std::array<models::ComplianceForm, 2> forms{options.law, options.law};
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const auto& s = data.samples[i];
    const double rows = std::sqrt(double(s.rows));
    for (int j = 0; j < 2; ++j) {
      const double bias = BiasOf(state, j, s, options);
      if (!s.tip_fixed) {
        const double e = s.effort_nm[j] - bias;
        out.free_squares[j].push_back(std::pow(e * rows / noise.effort_free_nm[j], 2));
        out.effort_sum2[j] += e * e, out.effort_count[j] += 1;
        continue;
      }
      const double tau = state.tau_ext_nm[i][j];
      const double e = s.effort_nm[j] - bias - tau;
      const double a = s.angle_rad[j] - state.tip_rad.at(s.segment)[j] -
                       Deflection(j, forms, state.law[j].data(), state.delta_rad[j],
                                  state.log_width[j], tau, s.insertion_depth_m);
      out.fixed_squares[j].push_back(std::pow(e * rows / noise.effort_fixed_nm[j], 2) +
                                     std::pow(a * rows / noise.angle_fixed_rad[j], 2));
      out.effort_sum2[j] += e * e, out.effort_count[j] += 1;
      out.angle_sum2[j] += a * a, out.angle_count[j] += 1;
    }
  }
  return out;
}

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

}  // namespace

SmootherNoise RescaledNoise(const IdentificationData& data, const SmootherState& state,
                            const JointSmootherOptions& options, const SmootherNoise& noise,
                            std::string* note) {
  const Residuals r = Evaluate(data, state, options, noise);
  SmootherNoise out = noise;
  for (int j = 0; j < 2; ++j) {
    const double free = NoiseScale(r.free_squares[j]);
    const double fixed = NoiseScale(r.fixed_squares[j]);
    out.effort_free_nm[j] *= free;
    out.effort_fixed_nm[j] *= fixed;
    // Never below the encoder's own resolution: a tinier angle sd only makes
    // the problem stiff (the effort noise, times K, dominates anyway).
    out.angle_fixed_rad[j] = std::max(options.encoder_noise_rad, out.angle_fixed_rad[j] * fixed);
    *note += Format("  joint %.0f noise per row: effort %.3g N·m (free tip), ", j + 1.0,
                    out.effort_free_nm[j]) +
             Format("%.3g N·m and %.3g rad (tip held)\n", out.effort_fixed_nm[j],
                    out.angle_fixed_rad[j]);
  }
  return out;
}

void FillResult(const IdentificationData& data, const models::ModelParameters& prior,
                const SmootherPrior& smoother_prior, const JointSmootherOptions& options,
                SmootherState* state, const Eigen::MatrixXd* computed,
                const std::array<bool, 2>& width_fitted, IdentificationResult* result) {
  using Effect = models::BiasTorqueFourierEffect;
  const int h = options.bias_harmonics, nb = Effect::ParameterCount(h);
  std::vector<std::string> names;
  for (int j = 0; j < 2; ++j) for (const auto& n : LawNames(j, options.law)) names.push_back(n);
  for (int j = 0; j < 2; ++j) names.push_back("joint" + std::to_string(j + 1) + ".backlash_rad");
  for (int j = 0; j < 2; ++j) names.push_back("joint" + std::to_string(j + 1) + ".deadzone_width_nm");
  for (int j = 0; j < 2; ++j) {
    const std::string prefix = "joint" + std::to_string(j + 1) + ".bias_torque.";
    for (int i = 0; i <= 2 * h; ++i)
      names.push_back(prefix + "coefficients[" + std::to_string(i) + "]");
    names.push_back(prefix + "depth_slope_nm_per_m");
    for (int i = 0; i < 2; ++i)
      names.push_back(prefix + "depth_harmonic_nm_per_m[" + std::to_string(i) + "]");
  }
  const long n = long(names.size());
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  if (computed) {
    covariance = *computed;
  } else {
    result->warnings.push_back("the covariance could not be computed (the problem is singular); "
                               "reported uncertainties are the priors'");
    long k = 0;
    for (int j = 0; j < 2; ++j) for (int i = 0; i < 4; ++i, ++k) covariance(k, k) = std::pow(smoother_prior.law_sd[j][i], 2);
    for (int j = 0; j < 2; ++j, ++k) covariance(k, k) = std::pow(smoother_prior.delta_sd[j], 2);
    for (int j = 0; j < 2; ++j, ++k) covariance(k, k) = std::pow(smoother_prior.log_width_sd[j], 2);
    for (int j = 0; j < 2; ++j) for (int i = 0; i < nb; ++i, ++k) covariance(k, k) = std::pow(smoother_prior.bias_sd[j][i], 2);
  }
  // log w -> w: the covariance follows the Jacobian diag(…, w, …).
  Eigen::VectorXd jacobian = Eigen::VectorXd::Ones(n);
  for (int j = 0; j < 2; ++j) jacobian[10 + j] = std::exp(state->log_width[j]);
  Eigen::MatrixXd named = jacobian.asDiagonal() * covariance * jacobian.asDiagonal();

  models::ModelParameters& p = result->parameters;
  p = prior;
  const std::string source = "pliant identify (joint smoother) from " +
                             std::to_string(data.logs.size()) + " log(s)";
  const BranchClassifier branches(data, p, options.paper.contact_threshold_nm);
  for (int j = 0; j < 2; ++j) {
    auto& joint = p.joints[j];
    joint.compliance.form = options.law;
    joint.compliance.cubic.coefficients = state->law[j];
    // Valid where the held tip was loaded, on either side: a depth whose sweep
    // went one way only still informs the law (not so the paper's lines).
    double lo = 1.0, hi = 0.0;
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
      if (branches.side[j][i] == 0) continue;
      lo = std::min(lo, data.samples[i].insertion_depth_m);
      hi = std::max(hi, data.samples[i].insertion_depth_m);
    }
    if (hi > lo + 1e-3) joint.depth_min_m = lo, joint.depth_max_m = hi;
    joint.backlash_rad = state->delta_rad[j];
    joint.deadzone_width_nm = std::exp(state->log_width[j]);
    joint.bias_form = models::BiasForm::kFourier;
    const auto& bias = state->bias[j];
    joint.bias_fourier.coefficients.assign(bias.begin(), bias.begin() + 2 * h + 1);
    joint.bias_fourier.depth_slope_nm_per_m = bias[std::size_t(Effect::DepthSlopeIndex(h))];
    for (int i = 0; i < 2; ++i) {
      joint.bias_fourier.depth_harmonic_nm_per_m[i] =
          bias[std::size_t(Effect::DepthHarmonicIndex(h) + i)];
    }
    joint.bias_fourier.reference_depth_m = options.bias_reference_depth_m;
    for (const char* field : {"compliance", "backlash_rad", "deadzone_width_nm", "bias_torque"}) {
      joint.sources[field] = source;
    }
  }
  p.covariance = models::ParameterCovariance{names, named};
  result->condition_number = CorrelationCondition(named);

  SmootherNoise unit;  // raw residuals: the whitened ones are not used here
  unit.effort_free_nm = unit.effort_fixed_nm = unit.angle_fixed_rad = {1.0, 1.0};
  const Residuals r = Evaluate(data, *state, options, unit);
  for (int j = 0; j < 2; ++j) {
    if (r.angle_count[j]) result->angle_rms_rad[j] = std::sqrt(r.angle_sum2[j] / r.angle_count[j]);
    if (r.effort_count[j]) result->effort_rms_nm[j] = std::sqrt(r.effort_sum2[j] / r.effort_count[j]);
  }
  const auto structural = IdentifiabilityWarnings(
      data, p, options.paper, options.law == models::ComplianceForm::kBeamSeries ? 3 : 4);
  result->warnings.insert(result->warnings.begin(), structural.begin(), structural.end());
  // What the structure does not catch: a parameter the data hardly move from
  // its prior. A width that ended at its floor is a finding (the take-up is
  // below the resolution, a hard wall), not a failure: no warning.
  for (int j = 0; j < 2; ++j) {
    const double width_sd = std::sqrt(covariance(10 + j, 10 + j));  // in log w
    if (width_fitted[j] && width_sd > options.identified_fraction * smoother_prior.log_width_sd[j]) {
      result->warnings.push_back(Format(
          "joint %.0f: the dead-zone width is hardly informed (sd of log w is %.0f%% of its "
          "prior's): few samples lie where the shaft crosses the clearance",
          j + 1.0, 100.0 * width_sd / smoother_prior.log_width_sd[j]));
    }
  }
  const std::string why = models::ValidateParameters(p);
  if (!why.empty()) {
    throw std::runtime_error("the identified parameters are not usable (" + why +
                             "); try another --model law or more depths");
  }
}

}  // namespace pliant::estimation::detail
