#pragma once
// The effect catalogue: every effect pliant knows, by name, usable with double
// and with ceres::Jet without knowing its type. Built-in effects are
// registered on first use of Global(); a user adds their own with
//
//   pliant::estimation::EffectCatalogue::Global().Add<CrossCoupling>();
//
// (CrossCoupling is the worked example in pliant/models/effect.h.) From then on
// the simulator, the filter, the smoother and the diagnostics can create it by
// name. Register during start-up: Add() is not safe against concurrent calls
// to Add() or Create(); Create() alone is safe from many threads.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <ceres/jet.h>

#include "pliant/models/effect.h"

namespace pliant::estimation {

/// The Jet every type-erased effect is evaluated with: 8 derivative slots,
/// the size of the filter's state. Longer parameter vectors are differentiated
/// 8 slots at a time (as ceres::DynamicAutoDiffCostFunction does).
inline constexpr int kEffectJetSize = 8;
using EffectJet = ceres::Jet<double, kEffectJetSize>;

/// An effect behind a virtual interface, for code that chooses effects at run
/// time. Evaluate() forwards to the effect's templated operator().
class EffectModel {
 public:
  virtual ~EffectModel() = default;
  virtual const models::EffectInfo& Info() const = 0;
  virtual std::vector<models::ParameterSpec> Parameters() const = 0;
  virtual models::Vec2<double> Evaluate(const double* parameters,
                                        const models::JointState<double>& state) const = 0;
  virtual models::Vec2<EffectJet> Evaluate(const EffectJet* parameters,
                                           const models::JointState<EffectJet>& state) const = 0;
  virtual std::unique_ptr<EffectModel> Clone() const = 0;

  /// Default parameter values, from Parameters().
  std::vector<double> DefaultParameters() const;
};

template <typename Effect>
class EffectAdapter final : public EffectModel {
 public:
  explicit EffectAdapter(Effect effect) : effect_(std::move(effect)) {}
  const models::EffectInfo& Info() const override { return Effect::kInfo; }
  std::vector<models::ParameterSpec> Parameters() const override { return effect_.Parameters(); }
  models::Vec2<double> Evaluate(const double* p,
                                const models::JointState<double>& s) const override {
    return effect_(p, s);
  }
  models::Vec2<EffectJet> Evaluate(const EffectJet* p,
                                   const models::JointState<EffectJet>& s) const override {
    return effect_(p, s);
  }
  std::unique_ptr<EffectModel> Clone() const override {
    return std::make_unique<EffectAdapter>(effect_);
  }
  const Effect& effect() const { return effect_; }

 private:
  Effect effect_;
};

template <typename Effect>
std::unique_ptr<EffectModel> MakeEffectModel(Effect effect) {
  return std::make_unique<EffectAdapter<Effect>>(std::move(effect));
}

class EffectCatalogue {
 public:
  using Factory = std::function<std::unique_ptr<EffectModel>()>;

  /// The process-wide catalogue, holding the built-in effects.
  static EffectCatalogue& Global();

  /// Registers a default-constructed Effect under Effect::kInfo.name.
  template <typename Effect>
  void Add() {
    Add(std::string(Effect::kInfo.name), [] { return MakeEffectModel(Effect{}); });
  }
  /// Throws std::invalid_argument if the name is taken or not snake_case.
  void Add(std::string name, Factory factory);

  /// Throws std::invalid_argument listing the known names when unknown.
  std::unique_ptr<EffectModel> Create(std::string_view name) const;
  bool Contains(std::string_view name) const;
  std::vector<std::string> Names() const;

 private:
  std::vector<std::pair<std::string, Factory>> entries_;
};

}  // namespace pliant::estimation
