#include "pliant/estimation/jacobian_check.h"

#include <gtest/gtest.h>

namespace pliant::estimation {
namespace {

// A state away from every deliberate kink: loads beyond zero and inside the
// dead-zone ramp, depth inside the calibrated range, angles between knots.
models::JointState<double> SmoothState() {
  models::JointState<double> s;
  s.encoder_angle_rad << 0.31, -0.27;
  s.insertion_depth_m = 0.143;
  s.external_torque_nm << 0.043, -0.121;
  s.velocity_rad_s << 0.02, -0.01;
  s.time_s = 12.5;
  s.effort_rate_nm_s << 0.4, -0.7;
  return s;
}

TEST(JacobianCheck, EveryRegisteredEffectHasCorrectDerivatives) {
  const auto& catalogue = EffectCatalogue::Global();
  for (const auto& name : catalogue.Names()) {
    const auto effect = catalogue.Create(name);
    const auto result =
        CheckEffectJacobians(*effect, effect->DefaultParameters(), SmoothState());
    EXPECT_TRUE(result.ok) << name << ": " << result.Report();
    EXPECT_EQ(result.autodiff.cols(),
              static_cast<Eigen::Index>(effect->Parameters().size()) + models::kJointStateSize);
  }
}

TEST(JacobianCheck, ComplianceDerivativeWithRespectToTorqueIsK) {
  const auto compliance = EffectCatalogue::Global().Create("compliance");
  const auto result =
      CheckEffectJacobians(*compliance, compliance->DefaultParameters(), SmoothState());
  const int tau1_column = static_cast<int>(compliance->Parameters().size()) + 3;
  const double depth = 0.143;
  const double inverse_k1 = ((639.16 * depth - 432.35) * depth + 136.32) * depth + 3.12;
  EXPECT_NEAR(result.autodiff(0, tau1_column), 1.0 / inverse_k1, 1e-12);
}

// An effect whose derivative is lost: it launders the load through double.
double Value(double x) { return x; }
double Value(const EffectJet& x) { return x.a; }
struct LaunderedLoad {
  static constexpr models::EffectInfo kInfo{"laundered", models::Channel::kDeflection,
                                            "broken on purpose"};
  std::vector<models::ParameterSpec> Parameters() const {
    return {{"k", "rad/(N·m)", 0.05, 0.0, 1.0, 0.01}};
  }
  template <typename T>
  models::Vec2<T> operator()(const T* p, const models::JointState<T>& s) const {
    return {p[0] * T(Value(s.external_torque_nm[0])), T(0.0)};
  }
};

TEST(JacobianCheck, CatchesALostDerivativeAndSaysWhere) {
  const auto result = CheckEffectJacobians(MakeEffectModel(LaunderedLoad{}), {0.05}, SmoothState());
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.worst_entry, "d joint1 / d external_torque1");
  EXPECT_NEAR(result.worst_error, 0.05, 1e-8);
  EXPECT_EQ(result.Report().rfind("MISMATCH: worst relative error 0.05 at d joint1 / d "
                                  "external_torque1", 0), 0u) << result.Report();
}

}  // namespace
}  // namespace pliant::estimation
