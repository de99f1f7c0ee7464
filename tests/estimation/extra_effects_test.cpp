// ExtraEffects::ConsideredVariance: what the parameters' stated σ put into a
// channel, Σ_k (∂f_j/∂p_k · σ_k)², against the derivatives in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/estimation/extra_effects.h"

namespace pliant::estimation {
namespace {

models::EffectParameters Friction(const std::vector<double>& sd) {
  return {"joint_friction",
          {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"},
          {0.3, 0.2, 0.06, 0.05, 0.005},
          sd};
}

// joint_friction: τ_j = b_j·v_j + F_j·tanh(v_j/v_s), so ∂τ_j/∂b_j = v_j,
// ∂τ_j/∂F_j = tanh(v_j/v_s) and ∂τ_j/∂v_s = −F_j·(1 − tanh²)·v_j/v_s².
TEST(ConsideredVariance, JointFrictionsIsItsDerivativesTimesTheStatedSdInClosedForm) {
  const std::vector<double> sd = {0.05, 0.04, 0.01, 0.02, 0.001};
  const ExtraEffects effects({Friction(sd)});
  models::JointState<double> state;
  state.velocity_rad_s << 0.01, -0.004;
  const Eigen::Vector2d variance =
      effects.ConsideredVariance(state, models::Channel::kInternalTorque);
  const double f[2] = {0.06, 0.05}, vs = 0.005;
  for (int j = 0; j < 2; ++j) {
    const double v = state.velocity_rad_s[j], t = std::tanh(v / vs);
    const double d_vs = -f[j] * (1.0 - t * t) * v / (vs * vs);
    const double expected = std::pow(v * sd[j], 2) + std::pow(t * sd[2 + j], 2) +
                            std::pow(d_vs * sd[4], 2);
    EXPECT_NEAR(variance[j], expected, 1e-12 * expected) << "joint " << j + 1;
  }
  // The friction puts nothing in the encoder's channel.
  EXPECT_EQ(effects.ConsideredVariance(state, models::Channel::kDeflection),
            Eigen::Vector2d::Zero());
}

// The learned effects' share comes apart (the filter carries it itself where
// it learns the arm's torque): with friction learned and an inertia of σ 0.02
// beside it, the share is the friction's closed form above, the total adds
// (a·σ_J)².
TEST(ConsideredVariance, TheLearnedEffectsShareComesApart) {
  const std::vector<double> sd = {0.05, 0.04, 0.01, 0.02, 0.001};
  ExtraEffects effects({Friction(sd), {"joint_inertia", {"inertia1", "inertia2"}, {0.1, 0.2}, {0.02, 0.0}}});
  models::JointState<double> state;
  state.velocity_rad_s << 0.01, -0.004;
  state.acceleration_rad_s2 << 3.0, 1.0;
  const Eigen::Vector2d friction_only =
      ExtraEffects({Friction(sd)}).ConsideredVariance(state, models::Channel::kInternalTorque);
  effects.SetLearned({"joint_friction"});
  Eigen::Vector2d learned;
  const Eigen::Vector2d total =
      effects.ConsideredVariance(state, models::Channel::kInternalTorque, &learned);
  for (int j = 0; j < 2; ++j) EXPECT_NEAR(learned[j], friction_only[j], 1e-15) << j;
  EXPECT_NEAR(total[0], friction_only[0] + std::pow(3.0 * 0.02, 2), 1e-15);
  EXPECT_NEAR(total[1], friction_only[1], 1e-15);
}

// A file without σ (hand-written, or σ 0) considers nothing: the consumers
// then treat the effect as known, as before.
TEST(ConsideredVariance, NoStatedSdIsNoVariance) {
  models::JointState<double> state;
  state.velocity_rad_s << 0.01, -0.004;
  for (const auto& sd : {std::vector<double>{}, std::vector<double>(5, 0.0)}) {
    const ExtraEffects effects({Friction(sd)});
    EXPECT_EQ(effects.ConsideredVariance(state, models::Channel::kInternalTorque),
              Eigen::Vector2d::Zero());
  }
}

// An effect with more parameters than the Jet has slots is differentiated
// eight at a time: τ_1 = Σ_i (i + 1)·p_i·v_1 over ten parameters.
struct TenGains {
  static constexpr models::EffectInfo kInfo{"ten_gains_considered_variance_test",
                                            models::Channel::kInternalTorque,
                                            "a test effect with ten parameters"};
  std::vector<models::ParameterSpec> Parameters() const {
    std::vector<models::ParameterSpec> specs;
    for (int i = 0; i < 10; ++i) specs.push_back({"g" + std::to_string(i), "", 1.0, -10, 10, 1.0});
    return specs;
  }
  template <typename T>
  models::Vec2<T> operator()(const T* p, const models::JointState<T>& s) const {
    T sum = T(0.0);
    for (int i = 0; i < 10; ++i) sum += double(i + 1) * p[i] * s.velocity_rad_s[0];
    return models::Vec2<T>(sum, T(0.0));
  }
};

TEST(ConsideredVariance, MoreParametersThanJetSlotsAreAllCounted) {
  EffectCatalogue::Global().Add<TenGains>();
  models::EffectParameters ten{std::string(TenGains::kInfo.name), {}, {}, {}};
  double expected = 0.0;
  const double v = 0.02;
  for (int i = 0; i < 10; ++i) {
    ten.parameter_names.push_back("g" + std::to_string(i));
    ten.values.push_back(1.0);
    ten.sd.push_back(i == 3 ? 0.0 : 0.1 * (i + 1));
    expected += std::pow((i + 1) * v * ten.sd.back(), 2);
  }
  const ExtraEffects effects({ten});
  models::JointState<double> state;
  state.velocity_rad_s << v, 0.0;
  const Eigen::Vector2d variance =
      effects.ConsideredVariance(state, models::Channel::kInternalTorque);
  EXPECT_NEAR(variance[0], expected, 1e-12 * expected);
  EXPECT_EQ(variance[1], 0.0);
}

}  // namespace
}  // namespace pliant::estimation
