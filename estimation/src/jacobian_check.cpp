#include "pliant/estimation/jacobian_check.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace pliant::estimation {
namespace {

using models::JointState;

// The state as a flat vector, in the order of JointStateInputNames().
template <typename T>
std::vector<T> Flatten(const JointState<T>& s) {
  return {s.encoder_angle_rad[0],  s.encoder_angle_rad[1],  s.insertion_depth_m,
          s.external_torque_nm[0], s.external_torque_nm[1], s.velocity_rad_s[0],
          s.velocity_rad_s[1],     s.time_s,                s.effort_rate_nm_s[0],
          s.effort_rate_nm_s[1],   s.travel_since_reversal_rad[0],
          s.travel_since_reversal_rad[1], s.acceleration_rad_s2[0],
          s.acceleration_rad_s2[1], s.compliance_rad_per_nm[0],
          s.compliance_rad_per_nm[1]};
}

template <typename T>
JointState<T> Unflatten(const T* x) {
  JointState<T> s;
  s.encoder_angle_rad << x[0], x[1];
  s.insertion_depth_m = x[2];
  s.external_torque_nm << x[3], x[4];
  s.velocity_rad_s << x[5], x[6];
  s.time_s = x[7];
  s.effort_rate_nm_s << x[8], x[9];
  s.travel_since_reversal_rad << x[10], x[11];
  s.acceleration_rad_s2 << x[12], x[13];
  s.compliance_rad_per_nm << x[14], x[15];
  return s;
}

// Derivatives by Jet, kEffectJetSize inputs per pass.
Eigen::MatrixXd AutodiffJacobian(const EffectModel& effect, const std::vector<double>& inputs,
                                 std::size_t num_parameters) {
  const int n = static_cast<int>(inputs.size());
  Eigen::MatrixXd jacobian(2, n);
  std::vector<EffectJet> x(inputs.size());
  for (int first = 0; first < n; first += kEffectJetSize) {
    for (int i = 0; i < n; ++i) {
      x[i] = EffectJet(inputs[i]);
      if (i >= first && i < first + kEffectJetSize) x[i].v[i - first] = 1.0;
    }
    const auto y = effect.Evaluate(x.data(), Unflatten(x.data() + num_parameters));
    for (int i = first; i < std::min(n, first + kEffectJetSize); ++i) {
      for (int j = 0; j < 2; ++j) jacobian(j, i) = y[j].v[i - first];
    }
  }
  return jacobian;
}

Eigen::MatrixXd NumericJacobian(const EffectModel& effect, std::vector<double> inputs,
                                std::size_t num_parameters, double relative_step) {
  const int n = static_cast<int>(inputs.size());
  Eigen::MatrixXd jacobian(2, n);
  auto evaluate = [&] {
    return effect.Evaluate(inputs.data(), Unflatten(inputs.data() + num_parameters));
  };
  for (int i = 0; i < n; ++i) {
    const double x0 = inputs[i];
    const double h = relative_step * std::max(1.0, std::abs(x0));
    inputs[i] = x0 + h;
    const auto plus = evaluate();
    inputs[i] = x0 - h;
    const auto minus = evaluate();
    inputs[i] = x0;
    jacobian.col(i) = (plus - minus) / (2.0 * h);
  }
  return jacobian;
}

std::string InputName(const EffectModel& effect, int column) {
  const auto specs = effect.Parameters();
  if (column < static_cast<int>(specs.size())) return specs[column].name;
  return JointStateInputNames()[column - specs.size()];
}

}  // namespace

const std::vector<std::string>& JointStateInputNames() {
  static const std::vector<std::string> names = {
      "q1", "q2", "insertion_depth_m", "external_torque1", "external_torque2", "v1", "v2", "t",
      "effort_rate1", "effort_rate2", "travel1", "travel2", "a1", "a2", "compliance1",
      "compliance2"};
  return names;
}

JacobianCheckResult CheckEffectJacobians(const EffectModel& effect,
                                         const std::vector<double>& parameters,
                                         const JointState<double>& state,
                                         const JacobianCheckOptions& options) {
  std::vector<double> inputs = parameters;
  const auto flat_state = Flatten(state);
  inputs.insert(inputs.end(), flat_state.begin(), flat_state.end());

  JacobianCheckResult result;
  result.autodiff = AutodiffJacobian(effect, inputs, parameters.size());
  result.numeric = NumericJacobian(effect, inputs, parameters.size(), options.relative_step);
  result.worst_error = 0.0;
  for (int i = 0; i < result.autodiff.cols(); ++i) {
    for (int j = 0; j < 2; ++j) {
      const double numeric = result.numeric(j, i);
      const double error =
          std::abs(result.autodiff(j, i) - numeric) / std::max(1.0, std::abs(numeric));
      if (!(error <= result.worst_error)) {  // also catches NaN
        result.worst_error = error;
        result.worst_entry = "d joint" + std::to_string(j + 1) + " / d " + InputName(effect, i);
      }
    }
  }
  result.ok = result.worst_error <= options.tolerance;
  if (result.ok) result.worst_entry += " (within tolerance)";
  return result;
}

std::string JacobianCheckResult::Report() const {
  std::ostringstream out;
  out << (ok ? "ok" : "MISMATCH") << ": worst relative error " << std::setprecision(3)
      << worst_error << " at " << worst_entry;
  if (!ok) {
    out << "\n  autodiff:\n" << autodiff << "\n  central differences:\n" << numeric;
  }
  return out.str();
}

}  // namespace pliant::estimation
