#include "pliant/estimation/extra_effects.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pliant::estimation {
namespace {

std::string SpecNames(const EffectModel& model) {
  std::string names;
  for (const auto& spec : model.Parameters()) names += (names.empty() ? "" : ", ") + spec.name;
  return names;
}

// The file's values (or, with `sd`, their σ: 0 where the file gives none) in
// the catalogue's order; every parameter must be there.
std::vector<double> Ordered(const EffectModel& model, const models::EffectParameters& effect,
                            bool sd = false) {
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
    const bool stated = k < effect.sd.size() && std::isfinite(effect.sd[k]);
    values.push_back(!sd ? effect.values[k] : stated ? std::abs(effect.sd[k]) : 0.0);
  }
  return values;
}

}  // namespace

ExtraEffects::ExtraEffects(const std::vector<models::EffectParameters>& effects) {
  for (const auto& effect : effects) {
    models_.push_back(EffectCatalogue::Global().Create(effect.name));
    values_.push_back(Ordered(*models_.back(), effect));
    sd_.push_back(Ordered(*models_.back(), effect, true));
  }
  Seed();
}

ExtraEffects::ExtraEffects(const ExtraEffects& other)
    : values_(other.values_), sd_(other.sd_), learned_(other.learned_), seeded_(other.seeded_) {
  for (const auto& m : other.models_) models_.push_back(m->Clone());
}

void ExtraEffects::Seed() {
  seeded_.clear();
  for (std::size_t k = 0; k < models_.size(); ++k) {
    const std::size_t n = values_[k].size();
    for (std::size_t first = 0; first < n; first += kEffectJetSize) {
      const std::size_t last = std::min(n, first + kEffectJetSize);
      const auto sd = sd_[k].begin();
      if (std::all_of(sd + first, sd + last, [](double v) { return v == 0.0; })) continue;
      SeededPass pass{k, first, {}};
      for (std::size_t i = 0; i < n; ++i) {
        pass.values.emplace_back(values_[k][i]);
        if (i >= first && i < last) pass.values.back().v[i - first] = 1.0;
      }
      seeded_.push_back(std::move(pass));
    }
  }
}

Eigen::Vector2d ExtraEffects::ConsideredVariance(const models::JointState<double>& state,
                                                 models::Channel channel,
                                                 Eigen::Vector2d* learned_part) const {
  Eigen::Vector2d variance = Eigen::Vector2d::Zero();
  if (learned_part) learned_part->setZero();
  if (seeded_.empty()) return variance;
  const models::JointState<EffectJet> jets = state.Cast<EffectJet>();
  for (const SeededPass& pass : seeded_) {
    if (models_[pass.effect]->Info().channel != channel) continue;
    const models::Vec2<EffectJet> out = models_[pass.effect]->Evaluate(pass.values.data(), jets);
    const std::vector<double>& sd = sd_[pass.effect];
    const std::size_t last = std::min(sd.size(), pass.first + kEffectJetSize);
    const bool learned = learned_part && pass.effect < learned_.size() && learned_[pass.effect];
    for (std::size_t i = pass.first; i < last; ++i) {
      for (int j = 0; j < 2; ++j) {
        const double term = out[j].v[i - pass.first] * sd[i];
        if (!std::isfinite(term)) continue;
        variance[j] += term * term;
        if (learned) (*learned_part)[j] += term * term;
      }
    }
  }
  return variance;
}

ExtraEffects& ExtraEffects::operator=(const ExtraEffects& other) {
  if (this != &other) {
    ExtraEffects copy(other);
    models_ = std::move(copy.models_);
    values_ = std::move(copy.values_);
    sd_ = std::move(copy.sd_);
    learned_ = std::move(copy.learned_);
    seeded_ = std::move(copy.seeded_);
  }
  return *this;
}

void ExtraEffects::SetLearned(const std::vector<std::string>& names) {
  learned_.assign(models_.size(), false);
  for (std::size_t k = 0; k < models_.size(); ++k)
    learned_[k] = std::find(names.begin(), names.end(), models_[k]->Info().name) != names.end();
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
