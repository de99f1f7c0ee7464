#include "identification_consider.h"

#include <cmath>
#include <cstdio>

#include "pliant/estimation/parameter_query.h"
#include "pliant/models/effects/bias_torque_fourier.h"

namespace pliant::estimation::detail {
namespace {

constexpr long kFirstBias = 12;  // after law1 (4), law2 (4), delta (2), log w (2)

std::string Format(const char* format, double a, double b, double c, double d) {
  char text[200];
  std::snprintf(text, sizeof text, format, a, b, c, d);
  return text;
}

}  // namespace

void HeldParameters(const UndeterminedParameters& held, const SmootherPrior& prior,
                    const JointSmootherOptions& options, std::vector<long>* indices,
                    std::vector<double>* prior_sd) {
  using Effect = models::BiasTorqueFourierEffect;
  const int h = options.bias_harmonics, nb = Effect::ParameterCount(h);
  for (int j = 0; j < 2; ++j) {
    if (held.backlash[j]) indices->push_back(8 + j), prior_sd->push_back(prior.delta_sd[j]);
  }
  for (int j = 0; j < 2; ++j) {
    if (!held.bias[j]) continue;
    for (int i = 0; i < nb; ++i) {
      // Coordinates held outside the fit (the slope without bias_depth_term,
      // an undetermined depth harmonic) are not carried.
      if (i == Effect::DepthSlopeIndex(h) && !options.bias_depth_term) continue;
      const int harmonic = i - Effect::DepthHarmonicIndex(h);
      if (harmonic >= 0 && held.depth_harmonic[j][std::size_t(harmonic)]) continue;
      indices->push_back(kFirstBias + long(j) * nb + i);
      prior_sd->push_back(prior.bias_sd[j][std::size_t(i)]);
    }
  }
}

std::vector<std::string> HeldParameterWarnings(const models::ModelParameters& fitted,
                                               const Eigen::MatrixXd& conditional,
                                               const UndeterminedParameters& held) {
  // The fit alone: the same file with the conditional covariance (log w → w
  // as the smoother's output does, though w is not what is reported here).
  models::ModelParameters fit_alone = fitted;
  Eigen::MatrixXd named = conditional;
  for (int j = 0; j < 2; ++j) {
    const double w = fitted.joints[j].deadzone_width_nm;
    named.row(10 + j) *= w;
    named.col(10 + j) *= w;
  }
  fit_alone.covariance->matrix = named;
  std::vector<std::string> out;
  for (int j = 0; j < 2; ++j) {
    if (!held.bias[j] && !held.backlash[j]) continue;
    const auto& joint = fitted.joints[j];
    const double depth = 0.5 * (joint.depth_min_m + joint.depth_max_m);
    const JointAtDepth all = QueryParametersAtDepth(fitted, depth).joints[j];
    const JointAtDepth fit = QueryParametersAtDepth(fit_alone, depth).joints[j];
    const std::string name = std::to_string(j + 1);
    std::string text = "joint " + name + ": K" + name +
                       Format(" at %.3f m = %.5f ± %.5f rad/(N·m) (± %.1f %%", depth,
                              all.compliance_rad_per_nm, all.compliance_sd,
                              100.0 * all.compliance_sd / all.compliance_rad_per_nm) +
                       Format("; the fit alone gives ± %.2f %%)", 100.0 * fit.compliance_sd /
                              fit.compliance_rad_per_nm, 0, 0, 0);
    if (!held.backlash[j]) {
      text += ", delta" + name + Format(" = %.5f ± %.5f rad (the fit alone ± %.5f)",
                                        all.backlash_rad, all.backlash_sd, fit.backlash_sd, 0);
    }
    std::string what;
    if (held.bias[j]) what = "the bias torque tau0 (no bias sweep)";
    if (held.backlash[j]) {
      what += std::string(what.empty() ? "" : " and ") + "delta" + name + " (no reversal)";
    }
    out.push_back(text + ": the rest is the prior uncertainty of " + what +
                  ", held at the prior and carried into these sd");
  }
  return out;
}

}  // namespace pliant::estimation::detail
