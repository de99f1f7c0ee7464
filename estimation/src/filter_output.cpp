// What the filter and the smoother hand out (filter.h): the corrected angles
// with their covariance and the tip correction, and the step limit that keeps
// the online output free of jumps.
#include <algorithm>
#include <cmath>

#include "pliant/estimation/filter.h"
#include "pliant/models/psm_kinematics.h"

namespace pliant::estimation {
namespace {

// The uncorrected tip (encoders) minus the corrected one, through
// J = r·diag(cos q2, 1) (mm/rad); encoders are exact at this scale, so its
// covariance is J·C·Jᵀ, and the σ of its length is taken along it.
void SetTipCorrection(const Eigen::Vector2d& encoder_rad, double insertion_depth_m,
                      FilterEstimate* e) {
  // A joint without its encoder (missing, or unrecorded) adds no correction.
  const Eigen::Vector2d q(std::isfinite(encoder_rad[0]) ? encoder_rad[0] : e->corrected_rad[0],
                          std::isfinite(encoder_rad[1]) ? encoder_rad[1] : e->corrected_rad[1]);
  const Eigen::Matrix2d jac = models::TipDisplacementJacobianMm(
      Eigen::Vector3d(q[0], q[1], insertion_depth_m));
  const Eigen::Vector2d shift = jac * (q - e->corrected_rad);
  const Eigen::Matrix2d tip_cov = jac * e->covariance_rad2 * jac.transpose();
  e->tip_correction_mm = shift.norm();
  if (e->tip_correction_mm > 1e-9) {
    const Eigen::Vector2d along = shift / e->tip_correction_mm;
    e->tip_correction_sd_mm = std::sqrt(along.dot(tip_cov * along));
  } else {
    e->tip_correction_sd_mm = std::sqrt(0.5 * tip_cov.trace());
  }
}

}  // namespace

FilterEstimate MakeEstimate(const FilterJointState& joint1, const FilterJointState& joint2,
                            const Eigen::Vector2d& encoder_rad, double insertion_depth_m) {
  FilterEstimate e;
  const FilterJointState* joints[2] = {&joint1, &joint2};
  for (int j = 0; j < 2; ++j) {
    const auto& x = joints[j]->mean;
    e.corrected_rad[j] = x[kStateTip];
    e.covariance_rad2(j, j) = joints[j]->covariance(kStateTip, kStateTip);
    e.external_torque_nm[j] = x[kStateTorque];
    e.backlash_offset_rad[j] = x[kStateBacklash];
    e.compliance_scale[j] = x[kStateScale];
    e.clearance_error_rad[j] = x[kStateClearance];
    e.effort_offset_nm[j] = x[kStateEffortOffset];
  }
  e.filtered_rad = e.corrected_rad;
  SetTipCorrection(encoder_rad, insertion_depth_m, &e);
  return e;
}

void CarryEstimate(const FilterSample& from, const FilterSample& to, double depth_m,
                   FilterEstimate* e) {
  for (int j = 0; j < 2; ++j) {
    if (from.tip_fixed && to.tip_fixed) continue;
    const double moved = to.encoder_rad[j] - from.encoder_rad[j];
    if (std::isfinite(moved)) {
      e->corrected_rad[j] += moved;
      e->filtered_rad[j] += moved;
    }
  }
  SetTipCorrection(to.encoder_rad, depth_m, e);
}

void OutputStepLimiter::Apply(const Eigen::Vector2d& limit_rad, const bool restart[2],
                              const Eigen::Vector2d& encoder_rad, double insertion_depth_m,
                              FilterEstimate* e) {
  Eigen::Vector2d gap(0.0, 0.0);
  for (int j = 0; j < 2; ++j) {
    const double target = e->filtered_rad[j];
    const double step = target - output_[j];
    // Within the limit the output is the estimate to the last bit (not
    // output + step, which rounds): with the limit off nothing changes.
    if (restart[j] || !(std::abs(step) > limit_rad[j])) {
      output_[j] = target;
    } else {
      output_[j] += std::copysign(limit_rad[j], step);
      gap[j] = output_[j] - target;
    }
  }
  if (gap.isZero()) return;
  // The estimate's error is N(0, P) given the data; the output's is N(gap, P):
  // its mean squared error, what a consumer that weighs it needs, is P + gap·gapᵀ.
  e->corrected_rad = output_;
  e->covariance_rad2 += gap * gap.transpose();
  e->flags |= kFlagOutputLimited;
  SetTipCorrection(encoder_rad, insertion_depth_m, e);
}

}  // namespace pliant::estimation
