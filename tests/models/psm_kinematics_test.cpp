#include "pliant/models/psm_kinematics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace pliant::models {
namespace {

TEST(PsmKinematics, WristLiesQ3Minus15p6MillimetresFromTheRcm) {
  for (double q3 : {0.09, 0.15, 0.22}) {
    const Eigen::Vector3d q(0.3, -0.4, q3);
    EXPECT_NEAR(PsmWristPosition(q).norm(), q3 - 0.0156, 1e-12);
    EXPECT_NEAR(WristDistance(q3), q3 - 0.0156, 1e-15);
  }
}

TEST(PsmKinematics, HomePointsTheShaftDownTheBaseZAxis) {
  // At q1 = q2 = 0 the modified-DH chain (offsets +π/2, −π/2) points the shaft
  // along −z of the base frame: the instrument goes down into the patient.
  const Eigen::Vector3d p = PsmWristPosition({0.0, 0.0, 0.2});
  EXPECT_NEAR(p.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.y(), 0.0, 1e-12);
  EXPECT_NEAR(p.z(), -(0.2 - 0.0156), 1e-12);
}

TEST(PsmKinematics, YawAndPitchRotateAboutTheRcm) {
  const Eigen::Vector3d base(0.0, 0.0, 0.15);
  const double r = 0.15 - 0.0156;
  // A pure yaw or pitch step moves the wrist along a chord of radius r.
  EXPECT_NEAR(TipErrorMm(base, 0.1, 0.0), 1000.0 * 2.0 * r * std::sin(0.05), 1e-9);
  EXPECT_NEAR(TipErrorMm(base, 0.0, 0.1), 1000.0 * 2.0 * r * std::sin(0.05), 1e-9);
}

TEST(PsmKinematics, SmallAngleFormulaMatchesExactDisplacement) {
  const Eigen::Vector3d q(0.2, 0.5, 0.18);
  const double dq1 = 2e-4, dq2 = -1e-4;
  const double expected = 1000.0 * (0.18 - 0.0156) * std::hypot(std::cos(0.5) * dq1, dq2);
  EXPECT_NEAR(TipErrorSmallAngleMm(q, dq1, dq2), expected, 1e-12);
  EXPECT_NEAR(TipErrorMm(q, dq1, dq2), expected, 1e-4 * expected);
}

TEST(PsmKinematics, JacobianMapsJointCovarianceToTipCovariance) {
  const Eigen::Vector3d q(0.0, 0.6, 0.12);
  const Eigen::Matrix2d j = TipDisplacementJacobianMm(q);
  const double scale = 1000.0 * (0.12 - 0.0156);
  EXPECT_NEAR(j(0, 0), scale * std::cos(0.6), 1e-9);
  EXPECT_NEAR(j(1, 1), scale, 1e-9);
  EXPECT_EQ(j(0, 1), 0.0);
  // Consistent with the small-angle error for any direction.
  const Eigen::Vector2d dq(3e-4, 4e-4);
  EXPECT_NEAR((j * dq).norm(), TipErrorSmallAngleMm(q, dq[0], dq[1]), 1e-12);
}

}  // namespace
}  // namespace pliant::models
