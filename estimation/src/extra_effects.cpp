#include "pliant/estimation/extra_effects.h"

#include <stdexcept>

namespace pliant::estimation {
namespace {

std::string SpecNames(const EffectModel& model) {
  std::string names;
  for (const auto& spec : model.Parameters()) names += (names.empty() ? "" : ", ") + spec.name;
  return names;
}

// The file's values in the catalogue's order; every parameter must be there.
std::vector<double> Ordered(const EffectModel& model, const models::EffectParameters& effect) {
  const auto specs = model.Parameters();
  if (effect.parameter_names.size() != specs.size()) {
    throw std::invalid_argument("effect '" + effect.name + "' needs exactly the parameters " +
                                SpecNames(model));
  }
  std::vector<double> values;
  for (const auto& spec : specs) {
    std::size_t k = 0;
    while (k < effect.parameter_names.size() && effect.parameter_names[k] != spec.name) ++k;
    if (k == effect.parameter_names.size()) {
      throw std::invalid_argument("effect '" + effect.name + "' lacks parameter '" + spec.name +
                                  "' (it needs " + SpecNames(model) + ")");
    }
    values.push_back(effect.values[k]);
  }
  return values;
}

}  // namespace

ExtraEffects::ExtraEffects(const std::vector<models::EffectParameters>& effects) {
  for (const auto& effect : effects) {
    models_.push_back(EffectCatalogue::Global().Create(effect.name));
    values_.push_back(Ordered(*models_.back(), effect));
  }
}

ExtraEffects::ExtraEffects(const ExtraEffects& other) : values_(other.values_) {
  for (const auto& m : other.models_) models_.push_back(m->Clone());
}

ExtraEffects& ExtraEffects::operator=(const ExtraEffects& other) {
  if (this != &other) {
    ExtraEffects copy(other);
    models_ = std::move(copy.models_);
    values_ = std::move(copy.values_);
  }
  return *this;
}

std::vector<std::string> ExtraEffects::Names() const {
  std::vector<std::string> names;
  for (const auto& m : models_) names.emplace_back(m->Info().name);
  return names;
}

Eigen::Vector2d ExtraEffects::InternalTorque(const models::JointState<double>& state) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < models_.size(); ++k) {
    if (models_[k]->Info().channel == models::Channel::kInternalTorque)
      sum += models_[k]->Evaluate(values_[k].data(), state);
  }
  return sum;
}

Eigen::Vector2d ExtraEffects::Deflection(const models::JointState<double>& state) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < models_.size(); ++k) {
    if (models_[k]->Info().channel == models::Channel::kDeflection)
      sum += models_[k]->Evaluate(values_[k].data(), state);
  }
  return sum;
}

}  // namespace pliant::estimation
