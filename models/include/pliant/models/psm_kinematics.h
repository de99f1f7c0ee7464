#pragma once
// Kinematics of the first three joints of the Classic PSM (modified DH, dVRK
// configuration files): yaw and pitch rotate about the remote centre of motion
// (RCM), insertion translates through it. Frame: the PSM base frame at the RCM.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pliant::models {

/// Modified DH parameters of the Classic PSM's first three joints, and the tool
/// offset of the Classic large needle driver (dVRK configuration files).
struct PsmGeometry {
  double insertion_offset_m = -0.4318;  ///< joint 3 offset in d
  double tool_offset_m = 0.4162;        ///< from joint-4 frame to the wrist along z
};

/// Pose of the joint-3 frame for q = (yaw rad, pitch rad, insertion m).
Eigen::Isometry3d PsmJoint3Pose(const Eigen::Vector3d& q, const PsmGeometry& geometry = {});

/// Wrist position (m) in the RCM frame; it lies r = q3 − 0.0156 m from the RCM.
Eigen::Vector3d PsmWristPosition(const Eigen::Vector3d& q, const PsmGeometry& geometry = {});

/// Distance from the RCM to the wrist, r (m).
double WristDistance(double insertion_m, const PsmGeometry& geometry = {});

/// Exact tip displacement (mm) between joints q and q + (dq1, dq2, 0).
double TipErrorMm(const Eigen::Vector3d& q, double dq1_rad, double dq2_rad,
                  const PsmGeometry& geometry = {});

/// Small-angle tip displacement (mm): r·sqrt((cos q2 · dq1)² + dq2²) · 1000.
double TipErrorSmallAngleMm(const Eigen::Vector3d& q, double dq1_rad, double dq2_rad,
                            const PsmGeometry& geometry = {});

/// Map from small joint errors (dq1, dq2) (rad) to the tip displacement (mm) in
/// the plane normal to the shaft: r·diag(cos q2, 1)·1000. A joint covariance P
/// becomes the tip covariance J·P·Jᵀ (mm²).
Eigen::Matrix2d TipDisplacementJacobianMm(const Eigen::Vector3d& q,
                                          const PsmGeometry& geometry = {});

}  // namespace pliant::models
