#include "pliant/experiments/truth_model.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/bias_torque_depth.h"
#include "pliant/models/effects/compliance.h"

namespace pliant::experiments {

using estimation::EffectJet;

struct TruthModel::Term {
  std::unique_ptr<estimation::EffectModel> effect;
  std::vector<double> parameters;
  std::vector<EffectJet> jet_parameters;  // constants: the truth is not differentiated
};

namespace {

// The catalogue's defaults, overridden by name.
std::vector<double> Sized(const estimation::EffectModel& effect, const HiddenEffect& hidden) {
  std::vector<double> values;
  std::size_t used = 0;
  for (const auto& spec : effect.Parameters()) {
    const auto found = hidden.parameters.find(spec.name);
    values.push_back(found == hidden.parameters.end() ? spec.default_value : found->second);
    used += found != hidden.parameters.end();
  }
  if (used != hidden.parameters.size()) {
    throw std::invalid_argument("effect '" + hidden.name +
                                "' has a parameter the scenario names "
                                "but the effect does not declare");
  }
  return values;
}

}  // namespace

TruthModel::TruthModel(const Scenario& scenario)
    : backlash_rad_(scenario.truth.joints[0].backlash_rad, scenario.truth.joints[1].backlash_rad),
      centre_rad_(scenario.truth.backlash_centre_rad),
      joints_{scenario.truth.joints[0], scenario.truth.joints[1]} {
  const Truth& truth = scenario.truth;
  auto add = [](std::vector<Term>& terms, std::unique_ptr<estimation::EffectModel> effect,
                std::vector<double> parameters) {
    Term term{std::move(effect), std::move(parameters), {}};
    for (double p : term.parameters) term.jet_parameters.emplace_back(p);
    terms.push_back(std::move(term));
  };

  std::vector<double> bias = truth.joints[0].bias_torque.torque_nm;
  bias.insert(bias.end(), truth.joints[1].bias_torque.torque_nm.begin(),
              truth.joints[1].bias_torque.torque_nm.end());
  add(internal_,
      estimation::MakeEffectModel(
          models::BiasTorqueEffect(truth.joints[0].bias_torque, truth.joints[1].bias_torque)),
      bias);
  add(internal_, estimation::MakeEffectModel(models::BiasTorqueDepthEffect{}),
      {truth.bias_depth_slope_nm_per_m[0], truth.bias_depth_slope_nm_per_m[1],
       truth.bias_reference_depth_m});

  std::vector<double> compliance;
  for (const auto& joint : truth.joints) {
    compliance.insert(compliance.end(), joint.compliance.cubic.coefficients.begin(),
                      joint.compliance.cubic.coefficients.end());
  }
  add(deflection_,
      estimation::MakeEffectModel(models::ComplianceEffect(truth.joints[0], truth.joints[1])),
      compliance);

  for (const HiddenEffect& hidden : scenario.hidden_effects) {
    auto effect = estimation::EffectCatalogue::Global().Create(hidden.name);
    std::vector<double> values = Sized(*effect, hidden);
    const bool internal = effect->Info().channel == models::Channel::kInternalTorque;
    add(internal ? internal_ : deflection_, std::move(effect), std::move(values));
  }
}

// The truth's K(L) at the state's depth, for the deflection effects that scale with it.
void TruthModel::WithCompliance(models::JointState<double>* state) const {
  state->compliance_rad_per_nm = models::CompliancesAt(joints_, state->insertion_depth_m);
}

TruthModel::~TruthModel() = default;
TruthModel::TruthModel(TruthModel&&) noexcept = default;

Eigen::Vector2d TruthModel::InternalTorque(const models::JointState<double>& state) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Term& term : internal_) sum += term.effect->Evaluate(term.parameters.data(), state);
  return sum;
}

Eigen::Matrix<double, 2, 4> TruthModel::InternalTorqueJacobian(
    const models::JointState<double>& state) const {
  models::JointState<EffectJet> jet = state.Cast<EffectJet>();
  for (int j = 0; j < 2; ++j) {
    jet.encoder_angle_rad[j].v[j] = 1.0;
    jet.velocity_rad_s[j].v[2 + j] = 1.0;
  }
  models::Vec2<EffectJet> sum(EffectJet(0.0), EffectJet(0.0));
  for (const Term& term : internal_) sum += term.effect->Evaluate(term.jet_parameters.data(), jet);
  Eigen::Matrix<double, 2, 4> jacobian;
  for (int j = 0; j < 2; ++j) jacobian.row(j) = sum[j].v.head<4>().transpose();
  return jacobian;
}

Eigen::Vector2d TruthModel::Deflection(models::JointState<double> state) const {
  WithCompliance(&state);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Term& term : deflection_) sum += term.effect->Evaluate(term.parameters.data(), state);
  return sum;
}

Eigen::Vector2d TruthModel::ShaftTorque(const Eigen::Vector2d& elastic_deflection,
                                        const std::array<bool, 2>& contact,
                                        models::JointState<double> state,
                                        const Eigen::Vector2d& guess,
                                        Eigen::Matrix2d* d_torque_d_deflection) const {
  Eigen::Vector2d tau(contact[0] ? guess[0] : 0.0, contact[1] ? guess[1] : 0.0);
  if (d_torque_d_deflection) d_torque_d_deflection->setZero();
  if (!contact[0] && !contact[1]) return tau;
  WithCompliance(&state);
  // Converged when the deflection matches to far below an encoder count.
  constexpr double kTolerance = 1e-13;
  for (int iteration = 0; iteration < 30; ++iteration) {
    state.external_torque_nm = tau;
    models::JointState<EffectJet> jet = state.Cast<EffectJet>();
    jet.external_torque_nm[0].v[0] = 1.0;
    jet.external_torque_nm[1].v[1] = 1.0;
    models::Vec2<EffectJet> d(EffectJet(0.0), EffectJet(0.0));
    for (const Term& term : deflection_)
      d += term.effect->Evaluate(term.jet_parameters.data(), jet);
    const Eigen::Vector2d residual(d[0].a - elastic_deflection[0], d[1].a - elastic_deflection[1]);
    Eigen::Matrix2d jacobian;
    jacobian << d[0].v[0], d[0].v[1], d[1].v[0], d[1].v[1];
    if (contact[0] && contact[1]) {
      const auto lu = jacobian.partialPivLu();
      if (residual.cwiseAbs().maxCoeff() < kTolerance) {
        if (d_torque_d_deflection) *d_torque_d_deflection = lu.inverse();
        return tau;
      }
      tau -= lu.solve(residual);
    } else {
      const int j = contact[0] ? 0 : 1;
      if (std::abs(residual[j]) < kTolerance) {
        if (d_torque_d_deflection) (*d_torque_d_deflection)(j, j) = 1.0 / jacobian(j, j);
        return tau;
      }
      tau[j] -= residual[j] / jacobian(j, j);
    }
    if (!tau.allFinite()) break;
  }
  throw std::runtime_error(
      "the shaft's deflection law could not be inverted (is a deflection effect non-monotone "
      "in the load? check the hidden effects' sizes)");
}

std::vector<std::string> TruthModel::EffectNames() const {
  std::vector<std::string> names;
  for (const auto* terms : {&internal_, &deflection_}) {
    for (const Term& term : *terms) names.emplace_back(term.effect->Info().name);
  }
  return names;
}

}  // namespace pliant::experiments
