#include "pliant/estimation/effect_catalogue.h"

#include <algorithm>
#include <stdexcept>

#include "pliant/models/effects/backlash.h"
#include "pliant/models/effects/backlash_depth.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/effects/bias_torque.h"
#include "pliant/models/effects/bias_torque_cross_joint.h"
#include "pliant/models/effects/bias_torque_depth.h"
#include "pliant/models/effects/bias_torque_fourier.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/effects/deflection_coupling.h"
#include "pliant/models/effects/effort_delay.h"
#include "pliant/models/effects/effort_drift.h"
#include "pliant/models/effects/held_friction.h"
#include "pliant/models/effects/joint_friction.h"
#include "pliant/models/effects/joint_inertia.h"
#include "pliant/models/effects/load_dependent_compliance.h"

namespace pliant::estimation {
namespace {

bool IsSnakeCase(const std::string& name) {
  if (name.empty() || !(name[0] >= 'a' && name[0] <= 'z')) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace

std::vector<double> EffectModel::DefaultParameters() const {
  std::vector<double> values;
  for (const auto& spec : Parameters()) values.push_back(spec.default_value);
  return values;
}

EffectCatalogue& EffectCatalogue::Global() {
  static EffectCatalogue* catalogue = [] {
    auto* c = new EffectCatalogue;
    c->Add<models::BiasTorqueEffect>();
    c->Add<models::ComplianceEffect>();
    c->Add<models::BacklashSignEffect>();
    c->Add<models::BacklashDeadZoneEffect>();
    c->Add<models::BacklashHysteresisEffect>();  // the filter's backlash, with memory
    c->Add<models::BiasTorqueFourierEffect>();
    // Effects the paper's model lacks (the simulator's hidden effects).
    c->Add<models::JointFrictionEffect>();
    c->Add<models::EffortDriftEffect>();
    c->Add<models::BiasTorqueDepthEffect>();
    c->Add<models::LoadDependentComplianceEffect>();
    c->Add<models::DeflectionCouplingEffect>();
    c->Add<models::BiasTorqueCrossJointEffect>();
    c->Add<models::BacklashDepthEffect>();
    c->Add<models::EffortDelayEffect>();
    // Found in the real clamped-beam data (docs/real-data.md).
    c->Add<models::HeldFrictionEffect>();
    // Fitted from free motion (identify --effect on a log without a held tip).
    c->Add<models::JointInertiaEffect>();
    c->Add<models::JointInertiaCouplingEffect>();
    return c;
  }();
  return *catalogue;
}

void EffectCatalogue::Add(std::string name, Factory factory) {
  if (!IsSnakeCase(name)) {
    throw std::invalid_argument("effect name '" + name +
                                "' must be snake_case (a-z, 0-9, _), starting with a letter");
  }
  if (Contains(name)) {
    throw std::invalid_argument("an effect named '" + name +
                                "' is already registered — give yours another name");
  }
  entries_.emplace_back(std::move(name), std::move(factory));
}

std::unique_ptr<EffectModel> EffectCatalogue::Create(std::string_view name) const {
  for (const auto& [entry_name, factory] : entries_) {
    if (entry_name == name) return factory();
  }
  std::string known;
  for (const auto& entry : entries_) known += (known.empty() ? "" : ", ") + entry.first;
  throw std::invalid_argument("no effect named '" + std::string(name) + "' — known effects: " +
                              known);
}

bool EffectCatalogue::Contains(std::string_view name) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const auto& entry) { return entry.first == name; });
}

std::vector<std::string> EffectCatalogue::Names() const {
  std::vector<std::string> names;
  for (const auto& entry : entries_) names.push_back(entry.first);
  return names;
}

}  // namespace pliant::estimation
