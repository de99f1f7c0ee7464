#pragma once
// The catalogue effects a parameters file carries beyond the paper's model
// ("effects" in docs/parameters.md), evaluated for any consumer: pliant
// correct, the filter, the smoother. One object per parameters file; the
// consumer fills a models::JointState per row (with travel_since_reversal_rad
// from a models::TravelSinceReversal when an effect reads it) and asks for
// the sum of the internal torques (subtract them from the measured effort
// before reading the external torque) and of the deflections (subtract them
// from the encoder angle, as the compliance).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

class ExtraEffects {
 public:
  ExtraEffects() = default;
  /// Throws std::invalid_argument when an effect is not in the catalogue or
  /// its parameters are not exactly the catalogue's (the message lists them).
  explicit ExtraEffects(const std::vector<models::EffectParameters>& effects);
  ExtraEffects(const ExtraEffects& other);
  ExtraEffects& operator=(const ExtraEffects& other);

  bool empty() const { return models_.empty(); }
  std::vector<std::string> Names() const;

  /// N·m per joint: the part of the measured effort that is not external load.
  Eigen::Vector2d InternalTorque(const models::JointState<double>& state) const;
  /// rad per joint: added to the encoder angle beyond the tip (state must
  /// carry the external torque).
  Eigen::Vector2d Deflection(const models::JointState<double>& state) const;
  /// What the parameters' stated σ (the file's "sd") put into one channel's
  /// sum at this row, per joint: Σ_k (∂f_j/∂p_k · σ_k)², the effects' own code
  /// differentiated with EffectJet. A consumer that treats the parameters as
  /// known adds it to that channel's noise (a consider parameter whose error is
  /// taken as independent from row to row). 0 when every σ is 0. Never allocates.
  /// learned_part (optional): the share of it from the effects SetLearned names.
  Eigen::Vector2d ConsideredVariance(const models::JointState<double>& state,
                                     models::Channel channel,
                                     Eigen::Vector2d* learned_part = nullptr) const;

  /// The named effects, whose doubt a consumer may carry itself where it
  /// learns them (the filter's arm torque, on the rows it teaches it): their
  /// share of ConsideredVariance is also returned apart. Allocates.
  void SetLearned(const std::vector<std::string>& names);
  /// Each effect with its parameter values, in the catalogue's order (for
  /// consumers that evaluate them with Jets, such as the filter).
  const std::vector<std::unique_ptr<EffectModel>>& models() const { return models_; }
  const std::vector<std::vector<double>>& values() const { return values_; }

 private:
  std::vector<std::unique_ptr<EffectModel>> models_;
  std::vector<std::vector<double>> values_;
  std::vector<std::vector<double>> sd_;  // the file's σ, in the catalogue's order
  std::vector<bool> learned_;            // SetLearned, per effect
  // An effect's values as Jets, parameters first…first+7 seeded (one pass of
  // ConsideredVariance); passes whose σ are all 0 are left out.
  struct SeededPass {
    std::size_t effect = 0, first = 0;
    std::vector<EffectJet> values;
  };
  std::vector<SeededPass> seeded_;
  void Seed();
};

}  // namespace pliant::estimation
