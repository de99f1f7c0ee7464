#pragma once
// The simulator's truth, composed of the same effect functions the estimators
// use (pliant/models/effects/*, through the effect catalogue): the
// internal-torque effects act on the motor side of the joints, the deflection
// effects make the shaft's elastic law. The cannula clearance (backlash) is
// not an effect here: the simulator makes it a real gap with contact events.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/effect_catalogue.h"
#include "pliant/experiments/scenario.h"

namespace pliant::experiments {

class TruthModel {
 public:
  /// bias_torque (the truth's tau0(q) table) + bias_torque_depth (its depth
  /// slope) + the internal-torque hidden effects; compliance K(L) + the
  /// deflection hidden effects. Throws std::invalid_argument for an unknown
  /// hidden effect or parameter.
  explicit TruthModel(const Scenario& scenario);
  ~TruthModel();
  TruthModel(TruthModel&&) noexcept;

  /// Sum of the internal-torque effects (N·m) at the joint state: what the
  /// controller must supply to hold or move the joints with no external load.
  Eigen::Vector2d InternalTorque(const models::JointState<double>& state) const;

  /// Derivatives of InternalTorque with respect to (theta1, theta2, omega1,
  /// omega2): the joint angles and velocities (for the integrator's Jacobian).
  Eigen::Matrix<double, 2, 4> InternalTorqueJacobian(const models::JointState<double>& state) const;

  /// Sum of the deflection effects (rad) at state.external_torque_nm.
  Eigen::Vector2d Deflection(models::JointState<double> state) const;

  /// The shaft torque tau (N·m) whose deflection D(tau) equals
  /// `elastic_deflection` on the joints in contact, with tau = 0 on the others
  /// (Newton's method from `guess`, exact Jacobians from the effects' Jets).
  /// When `d_torque_d_deflection` is given it receives d tau / d elastic
  /// deflection (zero rows and columns for joints out of contact).
  /// Throws std::runtime_error when the deflection law cannot be inverted.
  Eigen::Vector2d ShaftTorque(const Eigen::Vector2d& elastic_deflection,
                              const std::array<bool, 2>& contact,
                              models::JointState<double> state, const Eigen::Vector2d& guess,
                              Eigen::Matrix2d* d_torque_d_deflection = nullptr) const;

  /// Backlash delta_j (rad) and the centre of the clearance c_j (rad): the
  /// shaft bears on a wall at c_j ± delta_j.
  const Eigen::Vector2d& backlash_rad() const { return backlash_rad_; }
  const Eigen::Vector2d& clearance_centre_rad() const { return centre_rad_; }

  /// Names of the composed effects, internal-torque ones first.
  std::vector<std::string> EffectNames() const;

 private:
  void WithCompliance(models::JointState<double>* state) const;
  struct Term;
  std::vector<Term> internal_;
  std::vector<Term> deflection_;
  Eigen::Vector2d backlash_rad_;
  Eigen::Vector2d centre_rad_;
  std::array<models::JointParameters, 2> joints_;  ///< K(L) the deflection effects read
};

}  // namespace pliant::experiments
