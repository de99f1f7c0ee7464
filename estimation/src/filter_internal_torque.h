// The arm's own torque in the effort while it moves (the online filter's,
// filter_impl.h): inertia J·θ̈, the catalogue's joint friction (Coulomb f·tanh(θ̇/v_f), viscous
// c·θ̇) and the bias table's mean error τ_b, learned online from the
// rows where nothing touches the instrument (recursive least squares with
// forgetting; filter_internal_torque.cpp).
#pragma once

#include <array>

#include <Eigen/Core>

#include "filter_free_level.h"
#include "pliant/estimation/filter_options.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation::filter_internal {

struct InternalTorque {
  using Vector4 = Eigen::Matrix<double, 4, 1>;
  Vector4 coefficients = Vector4::Zero();  // J, f, c, τ_b
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  // Information form (the fading is done there; filter_internal_torque.cpp says why).
  Eigen::Matrix4d information = Eigen::Matrix4d::Zero();
  Eigen::Matrix4d prior_information = Eigen::Matrix4d::Zero();
  Vector4 information_mean = Vector4::Zero();  // information · coefficients
  Vector4 regressor = Vector4::Zero();     // this row's (θ̈, tanh(θ̇/v_f), θ̇, 1)
  /// motion_sd: the prior σ of J, f and c (ArmPriorSd).
  void Start(const FilterOptions& o, const Eigen::Vector3d& motion_sd);
  /// This row's regressor: the acceleration and the joint's row of ArmFriction.
  void SetMotion(double acceleration_rad_s2, const Eigen::Vector2d& friction_columns) {
    regressor << acceleration_rad_s2, friction_columns[0], friction_columns[1], 1.0;
  }
  double Torque() const { return coefficients.dot(regressor) + (level.on ? level.Torque() : 0.0); }
  // With the free level on, the level holds τ_b's doubt at this pose
  // (LevelEquilibrium) and the other terms' doubt is theirs alone.
  double Variance() const {
    if (!level.on) return regressor.dot(covariance * regressor);
    const Eigen::Vector3d motion = regressor.head<3>();
    return motion.dot(covariance.topLeftCorner<3, 3>() * motion) +
           level.Variance(LevelEquilibrium());
  }
  // The free level where nothing was learned: the table's error σ_rest² and τ_b's doubt.
  FreeLevel level;
  double rest_variance_nm2 = 0.0;
  double LevelEquilibrium() const { return rest_variance_nm2 + covariance(3, 3); }
  // This row's lesson for the level, taught with its batch (Learn): the
  // residual without the level, weighted by how still the arm stands.
  void AddLevelRow(double still, double residual_without_level, const Eigen::Vector3d& pose);
  // A row's lesson (weight: how much the arm moves as a free arm), taught
  // only once the contact chain has had kDelayWindows windows to say whether
  // something touched the instrument then (Batch).
  void Learn(double weight, double residual, double variance, double contact_probability,
             double dt_s, double memory_s);

  // The rows of one window of duration kWindowS: their information, and the
  // largest contact probability over them (at teaching, from their first row
  // until then: Learn takes the later batches' too).
  struct Batch {
    Eigen::Matrix4d information = Eigen::Matrix4d::Zero();
    Vector4 information_mean = Vector4::Zero();
    double teaching_s = 0.0, duration_s = 0.0, contact = 0.0;
    double level_weight = 0.0, level_sum = 0.0;  // Σw and Σw·r over the still rows
    Eigen::Vector3d level_pose_sum = Eigen::Vector3d::Zero();
  };
  static constexpr double kWindowS = 0.05;
  static constexpr int kDelayWindows = 10;
  Batch open;
  std::array<Batch, kDelayWindows> waiting;
  int oldest = 0, queued = 0;

 private:
  void Teach(const Batch& batch, double memory_s);
};

/// The prior σ of joint `joint`'s J, f and c: the options' unless the
/// parameters file states the arm's dynamics (joint_inertia, joint_friction
/// with σ, identified from free motion): then the learned terms correct the
/// file's, which the filter takes out of the effort, within the file's σ.
Eigen::Vector3d ArmPriorSd(const FilterOptions& o,
                           const std::vector<models::EffectParameters>& effects, int joint);

/// The arm's friction is the catalogue's `joint_friction` (models/effects/
/// joint_friction.h), evaluated, not restated: row j holds ∂τ_j/∂coulomb_j and
/// ∂τ_j/∂viscous_j at the joints' velocities (rad/s), the effect being linear
/// in both levels; velocity_scale_rad_s is its v_s (FilterOptions' v_f).
Eigen::Matrix2d ArmFriction(double velocity_scale_rad_s, const Eigen::Vector2d& velocity_rad_s);

}  // namespace pliant::estimation::filter_internal
