// The arm's own torque, learned online (filter_internal_torque.h).
#include "filter_internal_torque.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Cholesky>
#include <ceres/jet.h>

#include "pliant/models/effects/joint_friction.h"
#include "pliant/models/effects/joint_inertia.h"
#include "pliant/estimation/filter.h"

namespace pliant::estimation::filter_internal {

void InternalTorque::Start(const FilterOptions& o, const Eigen::Vector3d& motion_sd) {
  coefficients.setZero();
  regressor.setZero();
  information_mean.setZero();
  const Vector4 sd(motion_sd[0], motion_sd[1], motion_sd[2], o.internal_bias_error_sd_nm);
  prior_information = sd.cwiseProduct(sd).cwiseInverse().asDiagonal();
  information = prior_information;
  covariance = sd.cwiseProduct(sd).asDiagonal();
  open = Batch{};
  oldest = queued = 0;
  rest_variance_nm2 = o.unmodelled_effort_sd_nm * o.unmodelled_effort_sd_nm;
  level.Start(o, LevelEquilibrium());
}

void InternalTorque::AddLevelRow(double still, double residual_without_level,
                                 const Eigen::Vector3d& pose) {
  if (!level.on || !(still > 1e-3) || !std::isfinite(residual_without_level) ||
      !pose.allFinite()) {
    return;
  }
  open.level_weight += still;
  open.level_sum += still * residual_without_level;
  open.level_pose_sum += still * pose;
}

Eigen::Vector3d ArmPriorSd(const FilterOptions& o,
                           const std::vector<models::EffectParameters>& effects, int joint) {
  Eigen::Vector3d sd(o.internal_inertia_sd_kg_m2, o.internal_coulomb_sd_nm,
                     o.internal_viscous_sd_nm_s);
  const std::string index = std::to_string(joint + 1);
  for (const auto& e : effects) {
    const auto stated = [&e](const std::string& name, double* out) {
      for (std::size_t k = 0; k < e.parameter_names.size() && k < e.sd.size(); ++k) {
        if (e.parameter_names[k] == name && std::isfinite(e.sd[k]) && e.sd[k] > 0.0) *out = e.sd[k];
      }
    };
    if (e.name == models::JointInertiaEffect::kInfo.name) stated("inertia" + index, &sd[0]);
    if (e.name == models::JointFrictionEffect::kInfo.name) {
      stated("coulomb" + index, &sd[1]);
      stated("viscous" + index, &sd[2]);
    }
  }
  return sd;
}

Eigen::Matrix2d ArmFriction(double velocity_scale_rad_s, const Eigen::Vector2d& velocity_rad_s) {
  // One evaluation with both levels seeded (joint j's torque reads only its
  // own): dimension 0 the viscous levels, 1 the Coulomb levels.
  using Jet = ceres::Jet<double, 2>;
  const Jet viscous(0.0, 0), coulomb(0.0, 1);
  const Jet p[5] = {viscous, viscous, coulomb, coulomb, Jet(velocity_scale_rad_s)};
  models::JointState<Jet> state;
  state.velocity_rad_s = velocity_rad_s.cast<Jet>();
  const models::Vec2<Jet> torque = models::JointFrictionEffect{}(p, state);
  Eigen::Matrix2d columns;
  for (int j = 0; j < 2; ++j) columns.row(j) << torque[j].v[1], torque[j].v[0];
  return columns;
}

// Why the lesson waits: a push's first rows, while the encoder crosses the
// clearance at next to no load, move the encoder as a free arm's would and
// are no contact yet to the chain, which recognises the push a few tenths of
// a second later. Taught at once, they taught f·tanh(θ̇/v_f) the push's load
// (0.09 N·m of 0.8, on FilterContact's push), which then left every later
// push's effort and its correction (6 mrad). Waiting kDelayWindows windows
// (0.5 s), a window is taught with the weight 1 − the largest contact
// probability from its first row until then.
void InternalTorque::Learn(double weight, double residual, double variance,
                           double contact_probability, double dt_s, double memory_s) {
  open.contact = std::max(open.contact, std::clamp(contact_probability, 0.0, 1.0));
  if (weight > 1e-3 && variance > 0.0) {
    const double w = weight / variance;
    open.information.noalias() += w * regressor * regressor.transpose();
    open.information_mean += (w * residual) * regressor;
    open.teaching_s += dt_s;
  }
  open.duration_s += dt_s;
  if (open.duration_s < kWindowS) return;
  if (queued == kDelayWindows) {
    // The largest contact probability from the oldest batch's first row
    // until now: its own and every later batch's, each the largest of its rows.
    Batch& due = waiting[oldest];
    for (int k = 1; k < queued; ++k) {
      due.contact = std::max(due.contact, waiting[(oldest + k) % kDelayWindows].contact);
    }
    due.contact = std::max(due.contact, open.contact);
    Teach(due, memory_s);
    // The level's lesson waits as the torque's does: Learn says why.
    if (due.level_weight >= 1.0) {
      level.Teach(due.level_sum / due.level_weight, due.level_pose_sum / due.level_weight,
                  1.0 - due.contact, LevelEquilibrium());
    }
    oldest = (oldest + 1) % kDelayWindows;
    --queued;
  }
  waiting[(oldest + queued) % kDelayWindows] = open;
  ++queued;
  open = Batch{};
}

// Weighted least squares with stabilised forgetting, in information form: per
// batch that teaches (weight w = 1 − its contact probability), the past's
// information fades over the time its rows taught toward the prior's, not
// toward none: I ← λ·I + (1 − λ)·I₀ + w·Σφφᵀ/σ², ξ ← λ·ξ + w·Σφ·r/σ² (the prior's
// mean is 0). Plain exponential forgetting (P ← P/λ) blows up the covariance
// in the directions a motion does not excite (a constant sign of θ̇ makes
// tanh(θ̇/v_f), θ̇ and 1 nearly collinear) until rounding makes it indefinite:
// on the synthetic free motion of filter_contact_test.cpp the arm's torque
// then jumped to 1.4 N·m and was read as a contact for the rest of the log.
// Here I ≥ (1 − λ)·I₀ > 0 always, so the coefficients' spread never exceeds
// the prior's by more than 1/(1 − λ) and the covariance stays positive.
void InternalTorque::Teach(const Batch& batch, double memory_s) {
  const double w = 1.0 - batch.contact;
  if (!(w * batch.teaching_s > 0.0)) return;
  const double forget = std::exp(-w * batch.teaching_s / memory_s);
  information = forget * information + (1.0 - forget) * prior_information;
  information.noalias() += w * batch.information;
  information_mean = forget * information_mean + w * batch.information_mean;
  const Eigen::LLT<Eigen::Matrix4d> factor(information);
  if (factor.info() != Eigen::Success) return;
  coefficients = factor.solve(information_mean);
  covariance = factor.solve(Eigen::Matrix4d::Identity());
}

}  // namespace pliant::estimation::filter_internal

namespace pliant::estimation {

std::string OptionsAgainstParameters(const models::ModelParameters& parameters,
                                     const FilterOptions& options) {
  if (!(options.motor_inertia_kg_m2 > 0.0)) return "";
  for (const auto& e : parameters.effects) {
    if (e.name != models::JointInertiaEffect::kInfo.name) continue;
    char text[320];
    std::snprintf(text, sizeof text,
                  "FilterOptions::motor_inertia_kg_m2 = %g beside the parameters' joint_inertia, "
                  "which the filter already takes out of every effort: J·θ̈ would count twice "
                  "with the tip held \u2014 set it to 0 and keep the file's identified inertia, "
                  "or remove joint_inertia from the parameters",
                  options.motor_inertia_kg_m2);
    return text;
  }
  return "";
}

}  // namespace pliant::estimation
