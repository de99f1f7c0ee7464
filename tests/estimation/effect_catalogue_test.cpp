#include "pliant/estimation/effect_catalogue.h"

#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

// The worked example of pliant/models/effect.h, as a user would write it.
struct CrossCoupling {
  static constexpr models::EffectInfo kInfo{
      "cross_coupling_test", models::Channel::kDeflection,
      "the shaft bends a little toward yaw when pushed in pitch"};
  std::vector<models::ParameterSpec> Parameters() const {
    return {{"k12", "rad/(N·m)", 0.0, -0.05, 0.05, 0.01}};
  }
  template <typename T>
  models::Vec2<T> operator()(const T* p, const models::JointState<T>& s) const {
    return {p[0] * s.external_torque_nm[1], T(0.0)};
  }
};

TEST(EffectCatalogue, HoldsThePapersEffects) {
  const auto names = EffectCatalogue::Global().Names();
  for (const char* name : {"bias_torque", "compliance", "backlash_sign", "backlash_deadzone"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
  EXPECT_EQ(EffectCatalogue::Global().Create("compliance")->Info().channel,
            models::Channel::kDeflection);
}

TEST(EffectCatalogue, AUserEffectJoinsAndEvaluatesInBothScalarTypes) {
  EffectCatalogue catalogue;
  catalogue.Add<CrossCoupling>();
  const auto effect = catalogue.Create("cross_coupling_test");
  models::JointState<double> s;
  s.external_torque_nm << 0.5, 2.0;
  const double k12 = 0.01;
  EXPECT_DOUBLE_EQ(effect->Evaluate(&k12, s)[0], 0.02);
  const EffectJet k12_jet(0.01, 0);
  const auto jet = effect->Evaluate(&k12_jet, s.Cast<EffectJet>());
  EXPECT_DOUBLE_EQ(jet[0].a, 0.02);
  EXPECT_DOUBLE_EQ(jet[0].v[0], 2.0);  // d(k12·tau2)/d k12
  EXPECT_EQ(effect->DefaultParameters(), std::vector<double>{0.0});
}

TEST(EffectCatalogue, RefusesDuplicateAndMalformedNames) {
  EffectCatalogue catalogue;
  catalogue.Add<CrossCoupling>();
  try {
    catalogue.Add<CrossCoupling>();
    FAIL() << "accepted a duplicate";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "an effect named 'cross_coupling_test' is already registered — give yours "
                 "another name");
  }
  EXPECT_THROW(catalogue.Add("Bad Name", [] { return MakeEffectModel(CrossCoupling{}); }),
               std::invalid_argument);
}

TEST(EffectCatalogue, UnknownNameListsTheKnownOnes) {
  EffectCatalogue catalogue;
  catalogue.Add<CrossCoupling>();
  try {
    catalogue.Create("friction");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no effect named 'friction' — known effects: cross_coupling_test");
  }
}

}  // namespace
}  // namespace pliant::estimation
