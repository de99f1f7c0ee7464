// The parameters file's deflection effects in the online filter (filter.h):
// the encoder sees q_tip + b + s·K(L)·τ + Σ Δq(τ_ext = τ, the row's inputs),
// each Δq the catalogue effect's own templated code, differentiated with
// ceres::Jet (slot 0: τ_1, slot 1: τ_2). The filter keeps nothing of an
// effect's physics but its name.
#include <cmath>

#include "filter_impl.h"

namespace pliant::estimation {

using namespace filter_internal;

void ComplianceFilter::Impl::PrepareDeflectionEffects() {
  const auto& models = extra_effects.models();
  for (std::size_t k = 0; k < models.size(); ++k) {
    if (models[k]->Info().channel != models::Channel::kDeflection) continue;
    DeflectionEffect effect;
    effect.index = k;
    for (double value : extra_effects.values()[k]) effect.parameters.emplace_back(value);
    deflection_effects.push_back(std::move(effect));
  }
}

// A non-finite value or slope (an effect outside its domain) counts as none:
// the filter must not diverge on one row.
ExtraDeflection ComplianceFilter::Impl::DeflectionAt(double torque1_nm, double torque2_nm) const {
  ExtraDeflection out;
  if (deflection_effects.empty()) return out;
  models::JointState<EffectJet> state = effect_inputs.Cast<EffectJet>();
  state.external_torque_nm[0] = EffectJet(torque1_nm, 0);
  state.external_torque_nm[1] = EffectJet(torque2_nm, 1);
  models::Vec2<EffectJet> sum(EffectJet(0.0), EffectJet(0.0));
  for (const DeflectionEffect& effect : deflection_effects) {
    sum += extra_effects.models()[effect.index]->Evaluate(effect.parameters.data(), state);
  }
  for (int j = 0; j < 2; ++j) {
    const bool finite = std::isfinite(sum[j].a) && std::isfinite(sum[j].v[0]) &&
                        std::isfinite(sum[j].v[1]);
    if (!finite) continue;
    out.value[j] = sum[j].a;
    out.slope(j, 0) = sum[j].v[0];
    out.slope(j, 1) = sum[j].v[1];
  }
  return out;
}

}  // namespace pliant::estimation
