#include "pliant/models/cubic.h"

#include <gtest/gtest.h>

namespace pliant::models {
namespace {

TEST(Cubic, EvaluatesThePapersInverseComplianceOfJoint1) {
  const Cubic inverse_k1{{639.16, -432.35, 136.32, 3.12}};
  // By hand: 639.16·0.15³ − 432.35·0.15² + 136.32·0.15 + 3.12
  //        = 2.157165 − 9.727875 + 20.448 + 3.12 = 15.99729
  EXPECT_NEAR(inverse_k1(0.15), 15.99729, 1e-12);
}

TEST(Cubic, MinimumAtAnInteriorCriticalPoint) {
  const Cubic p{{1.0, 0.0, -3.0, 0.0}};  // x³ − 3x: local minimum −2 at x = 1
  EXPECT_NEAR(p.MinimumOn(-0.5, 2.0), -2.0, 1e-12);
}

TEST(Cubic, MinimumAtAnEndWhenMonotone) {
  // The paper's 1/K2 is increasing (its derivative has no real root), so its
  // minimum on [0, 0.22] is p(0) = −6: the polynomial crosses zero near 0.014 m.
  const Cubic inverse_k2{{3163.17, -1969.15, 448.92, -6.00}};
  EXPECT_DOUBLE_EQ(inverse_k2.MinimumOn(0.0, 0.22), -6.0);
  EXPECT_LT(inverse_k2(0.014), 0.0);
  EXPECT_GT(inverse_k2(0.0145), 0.0);
  EXPECT_NEAR(inverse_k2.MinimumOn(0.09, 0.22), 20.75863593, 1e-8);
}

TEST(Cubic, MinimumOfALinearAndAQuadratic) {
  EXPECT_DOUBLE_EQ((Cubic{{0.0, 0.0, 2.0, 1.0}}.MinimumOn(-1.0, 1.0)), -1.0);
  EXPECT_DOUBLE_EQ((Cubic{{0.0, 1.0, -2.0, 0.0}}.MinimumOn(-3.0, 3.0)), -1.0);  // (x−1)² − 1
}

}  // namespace
}  // namespace pliant::models
