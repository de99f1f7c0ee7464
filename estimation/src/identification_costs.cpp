// Ceres residuals of identification. The physics is the effects' (models/):
// nothing here re-writes K(L), the dead zone or tau0; it only places the
// parameter blocks where the effects expect them.
#include "identification_costs.h"

#include <cmath>

#include <ceres/autodiff_cost_function.h>
#include <ceres/dynamic_autodiff_cost_function.h>

#include "pliant/models/effects/held_friction.h"
#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/models/effects/compliance.h"

namespace pliant::estimation::detail {
namespace {

models::ComplianceEffect WideRangeCompliance(const std::array<models::ComplianceForm, 2>& forms) {
  // No clamping inside identification: the data's own depths define the law.
  models::JointParameters joints[2];
  for (int j = 0; j < 2; ++j) {
    joints[j].compliance.form = forms[j];
    joints[j].depth_min_m = 1e-3;
    joints[j].depth_max_m = 0.3;
  }
  return models::ComplianceEffect(joints[0], joints[1]);
}

struct AngleModel {
  models::ComplianceEffect compliance;
  models::BacklashDeadZoneEffect deadzone;
  int joint;

  // The other joint's slots get harmless constants: its output is not read.
  template <typename T>
  T operator()(const T& tau, const T* law, const T& delta, const T& log_width,
               const T& depth) const {
    using std::exp;
    models::JointState<T> state;
    state.insertion_depth_m = depth;
    state.external_torque_nm[joint] = tau;
    T coefficients[8];
    T deadzone_parameters[4];
    for (int i = 0; i < 4; ++i) {
      coefficients[4 * joint + i] = law[i];
      coefficients[4 * (1 - joint) + i] = T(i == 3 ? 1.0 : 0.0);
    }
    deadzone_parameters[joint] = delta;
    deadzone_parameters[1 - joint] = T(0.0);
    deadzone_parameters[2 + joint] = exp(log_width);
    deadzone_parameters[2 + (1 - joint)] = T(1.0);
    return compliance(coefficients, state)[joint] + deadzone(deadzone_parameters, state)[joint];
  }
};

struct AngleResidual {
  AngleModel model;
  std::array<double, 4> law_scale;
  double angle_rad, depth_m, inverse_sd;

  template <typename T>
  bool operator()(const T* tau, const T* tip, const T* scaled_law, const T* delta,
                  const T* log_width, T* residual) const {
    T law[4];
    for (int i = 0; i < 4; ++i) law[i] = scaled_law[i] * law_scale[i];
    const T deflection = model(tau[0], law, delta[0], log_width[0], T(depth_m));
    residual[0] = (T(angle_rad) - tip[0] - deflection) * inverse_sd;
    return true;
  }
};

struct EffortResidual {
  models::BiasTorqueFourierEffect bias;
  IdentificationSample sample;
  int joint, per_joint;
  bool latent_torque;
  double inverse_sd;

  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    T coefficients[2 * models::BiasTorqueFourierEffect::ParameterCount(kMaxBiasHarmonics)];
    for (int i = 0; i < per_joint; ++i) {
      coefficients[joint * per_joint + i] = blocks[0][i];
      coefficients[(1 - joint) * per_joint + i] = T(0.0);
    }
    models::JointState<T> state;
    state.encoder_angle_rad = sample.angle_rad.cast<T>();
    state.insertion_depth_m = T(sample.insertion_depth_m);
    const T tau0 = bias(coefficients, state)[joint];
    const T load = latent_torque ? blocks[1][0] : T(0.0);
    residual[0] = (T(sample.effort_nm[joint]) - tau0 - load) * inverse_sd;
    return true;
  }
};

struct HeldFrictionAngleResidual {
  models::HeldFrictionEffect friction;
  AngleModel model;
  IdentificationSample sample;
  int joint;
  std::array<double, 4> law_scale;
  double bias_nm, presliding_travel_rad, inverse_sd;

  template <typename T>
  bool operator()(const T* tip, const T* scaled_law, const T* held, const T* delta,
                  const T* log_width, T* residual) const {
    T law[4];
    for (int i = 0; i < 4; ++i) law[i] = scaled_law[i] * law_scale[i];
    models::JointState<T> state;
    state.travel_since_reversal_rad = sample.travel_since_reversal_rad.cast<T>();
    const T p[3] = {held[0], held[0], T(presliding_travel_rad)};
    const T load = T(sample.effort_nm[joint] - bias_nm) - friction(p, state)[joint];
    const T deflection = model(load, law, delta[0], log_width[0], T(sample.insertion_depth_m));
    residual[0] = (T(sample.angle_rad[joint]) - tip[0] - deflection) * inverse_sd;
    return true;
  }
};

}  // namespace

ceres::CostFunction* NewHeldFrictionAngleResidual(const IdentificationSample& sample, int joint,
                                                  models::ComplianceForm form,
                                                  const std::array<double, 4>& law_scale,
                                                  double bias_nm, double presliding_travel_rad,
                                                  double sd_rad) {
  return new ceres::AutoDiffCostFunction<HeldFrictionAngleResidual, 1, 1, 4, 1, 1, 1>(
      new HeldFrictionAngleResidual{
          {}, {WideRangeCompliance({form, form}), models::BacklashDeadZoneEffect(), joint}, sample,
          joint, law_scale, bias_nm, presliding_travel_rad, 1.0 / sd_rad});
}

ceres::CostFunction* NewEffortResidual(const IdentificationSample& sample, int joint,
                                       int harmonics, double reference_depth_m, double sd_nm,
                                       bool latent_torque) {
  const int per_joint = models::BiasTorqueFourierEffect::ParameterCount(harmonics);
  auto* cost = new ceres::DynamicAutoDiffCostFunction<EffortResidual, 16>(new EffortResidual{
      models::BiasTorqueFourierEffect(harmonics, reference_depth_m), sample, joint, per_joint,
      latent_torque, 1.0 / sd_nm});
  cost->AddParameterBlock(per_joint);
  if (latent_torque) cost->AddParameterBlock(1);
  cost->SetNumResiduals(1);
  return cost;
}

ceres::CostFunction* NewAngleResidual(const IdentificationSample& sample, int joint,
                                      const std::array<models::ComplianceForm, 2>& law_forms,
                                      const std::array<double, 4>& law_scale, double sd_rad) {
  return new ceres::AutoDiffCostFunction<AngleResidual, 1, 1, 1, 4, 1, 1>(new AngleResidual{
      {WideRangeCompliance(law_forms), models::BacklashDeadZoneEffect(), joint}, law_scale,
      sample.angle_rad[joint], sample.insertion_depth_m, 1.0 / sd_rad});
}

double Deflection(int joint, const std::array<models::ComplianceForm, 2>& law_forms,
                  const double* law, double delta_rad, double log_width, double tau_nm,
                  double depth_m) {
  const AngleModel model{WideRangeCompliance(law_forms), models::BacklashDeadZoneEffect(), joint};
  return model(tau_nm, law, delta_rad, log_width, depth_m);
}

}  // namespace pliant::estimation::detail
