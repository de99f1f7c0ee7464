#include "pliant/models/effect.h"

#include <gtest/gtest.h>

namespace pliant::models {
namespace {

// The worked example of effect.h, evaluated with double (the simulator's use).
struct CrossCoupling {
  static constexpr EffectInfo kInfo{"cross_coupling", Channel::kDeflection,
                                    "the shaft bends a little toward yaw when pushed in pitch"};
  std::vector<ParameterSpec> Parameters() const {
    return {{"k12", "rad/(N·m)", 0.0, -0.05, 0.05, 0.01}};
  }
  template <typename T>
  Vec2<T> operator()(const T* p, const JointState<T>& s) const {
    return {p[0] * s.external_torque_nm[1], T(0.0)};
  }
};

TEST(Effect, TheHeadersWorkedExampleEvaluates) {
  JointState<double> s;
  s.external_torque_nm << 0.3, -0.8;
  const double k12 = 0.02;
  EXPECT_EQ(CrossCoupling{}(&k12, s), Vec2<double>(-0.016, 0.0));
  EXPECT_EQ(CrossCoupling::kInfo.channel, Channel::kDeflection);
  EXPECT_EQ(CrossCoupling{}.Parameters()[0].unit, "rad/(N·m)");
}

TEST(JointState, CastKeepsEveryValue) {
  JointState<double> s;
  s.encoder_angle_rad << 0.1, -0.2;
  s.insertion_depth_m = 0.15;
  s.external_torque_nm << 0.5, -0.25;
  s.velocity_rad_s << 0.01, 0.02;
  s.time_s = 3.5;
  const JointState<float> f = s.Cast<float>();
  EXPECT_EQ(f.encoder_angle_rad, Vec2<float>(0.1f, -0.2f));
  EXPECT_EQ(f.insertion_depth_m, 0.15f);
  EXPECT_EQ(f.external_torque_nm, Vec2<float>(0.5f, -0.25f));
  EXPECT_EQ(f.velocity_rad_s, Vec2<float>(0.01f, 0.02f));
  EXPECT_EQ(f.time_s, 3.5f);
}

}  // namespace
}  // namespace pliant::models
