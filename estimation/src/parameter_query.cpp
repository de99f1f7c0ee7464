#include "pliant/estimation/parameter_query.h"

#include <algorithm>
#include <cmath>

#include <ceres/jet.h>

#include "identification_common.h"

namespace pliant::estimation {
namespace {

// Index of a covariance name, or −1.
long IndexOf(const models::ParameterCovariance& c, const std::string& name) {
  const auto found = std::find(c.names.begin(), c.names.end(), name);
  return found == c.names.end() ? -1 : long(found - c.names.begin());
}

}  // namespace

ParametersAtDepth QueryParametersAtDepth(const models::ModelParameters& parameters,
                                         double insertion_depth_m) {
  ParametersAtDepth out;
  out.insertion_depth_m = insertion_depth_m;
  for (int j = 0; j < 2; ++j) {
    const auto& joint = parameters.joints[j];
    auto& at = out.joints[j];
    const double depth = std::clamp(insertion_depth_m, joint.depth_min_m, joint.depth_max_m);
    at.depth_clamped = depth != insertion_depth_m;
    // K and dK/d(law numbers) in one evaluation of the model's own law.
    using Jet = ceres::Jet<double, 4>;
    Jet law[4];
    for (int i = 0; i < 4; ++i) law[i] = Jet(joint.compliance.cubic.coefficients[i], i);
    const Jet k = models::EvaluateCompliance(joint.compliance.form, law, Jet(depth));
    at.compliance_rad_per_nm = k.a;
    at.inverse_compliance_nm_per_rad = 1.0 / k.a;
    at.backlash_rad = joint.backlash_rad;
    if (!parameters.covariance) continue;
    const auto& c = *parameters.covariance;
    const auto names = detail::LawNames(j, joint.compliance.form);
    double variance = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        const long ia = IndexOf(c, names[a]), ib = IndexOf(c, names[b]);
        if (ia >= 0 && ib >= 0) variance += k.v[a] * c.matrix(ia, ib) * k.v[b];
        at.in_covariance = at.in_covariance || (ia >= 0 && ib >= 0);
      }
    }
    at.compliance_sd = std::sqrt(std::max(0.0, variance));
    at.inverse_compliance_sd = at.compliance_sd / (k.a * k.a);  // d(1/K) = −dK/K²
    const long delta = IndexOf(c, "joint" + std::to_string(j + 1) + ".backlash_rad");
    if (delta >= 0) at.backlash_sd = std::sqrt(std::max(0.0, c.matrix(delta, delta)));
  }
  return out;
}

}  // namespace pliant::estimation
