#include "pliant/models/psm_kinematics.h"

#include <cmath>

namespace pliant::models {
namespace {

// Craig's modified DH link transform: Rx(alpha) · Tx(a) · Rz(theta) · Tz(d),
// written out (Craig, eq. 3.6) rather than composed from four transforms: the
// filter's output and the tip-error statistics evaluate it on every row.
Eigen::Isometry3d ModifiedDh(double alpha, double a, double theta, double d) {
  const double ct = std::cos(theta), st = std::sin(theta);
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  Eigen::Isometry3d t;
  t.linear() << ct, -st, 0.0,  //
      st * ca, ct * ca, -sa,   //
      st * sa, ct * sa, ca;
  t.translation() << a, -sa * d, ca * d;
  t.makeAffine();
  return t;
}

}  // namespace

Eigen::Isometry3d PsmJoint3Pose(const Eigen::Vector3d& q, const PsmGeometry& g) {
  constexpr double kHalfPi = 1.57079632679489661923;
  return ModifiedDh(kHalfPi, 0.0, q[0] + kHalfPi, 0.0) *
         ModifiedDh(-kHalfPi, 0.0, q[1] - kHalfPi, 0.0) *
         ModifiedDh(kHalfPi, 0.0, 0.0, q[2] + g.insertion_offset_m);
}

Eigen::Vector3d PsmWristPosition(const Eigen::Vector3d& q, const PsmGeometry& g) {
  // Joint 4 (roll) turns about the shaft axis z3 and does not move the wrist.
  return PsmJoint3Pose(q, g) * Eigen::Vector3d(0.0, 0.0, g.tool_offset_m);
}

double WristDistance(double insertion_m, const PsmGeometry& g) {
  return std::abs(insertion_m + g.insertion_offset_m + g.tool_offset_m);
}

double TipErrorMm(const Eigen::Vector3d& q, double dq1_rad, double dq2_rad,
                  const PsmGeometry& g) {
  const Eigen::Vector3d moved = q + Eigen::Vector3d(dq1_rad, dq2_rad, 0.0);
  return 1000.0 * (PsmWristPosition(moved, g) - PsmWristPosition(q, g)).norm();
}

double TipErrorSmallAngleMm(const Eigen::Vector3d& q, double dq1_rad, double dq2_rad,
                            const PsmGeometry& g) {
  return 1000.0 * WristDistance(q[2], g) * std::hypot(std::cos(q[1]) * dq1_rad, dq2_rad);
}

Eigen::Matrix2d TipDisplacementJacobianMm(const Eigen::Vector3d& q, const PsmGeometry& g) {
  const double scale = 1000.0 * WristDistance(q[2], g);
  return Eigen::Vector2d(scale * std::cos(q[1]), scale).asDiagonal();
}

}  // namespace pliant::models
