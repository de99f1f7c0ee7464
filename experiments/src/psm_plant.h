#pragma once
// The continuous dynamics of PSM joints 1 and 2, integrated with SUNDIALS
// CVODE (BDF, Newton, dense direct linear solver; docs/simulator.md).
//
// State (8): motor-side joint angle theta_j, its velocity omega_j, and the
// shaft's angle relative to the joint d_j = theta_j − phi_j (phi_j the
// tip-consistent angle) with its rate d_j', for j = 1, 2. Integrating d rather
// than phi makes the relative tolerance act on the deflection (~0.01 rad),
// not on the joint angle (~1 rad), which is what the encoder-minus-truth needs.
//
//   J_j·omega_j' = u_j − tau_int_j(theta, omega, L, t) − tau_s_j
//   J_t·psi_j'   = tau_s_j − c_t·psi_j,  psi = omega − d'   (tip free)
//   psi = 0, d'' = omega'                                    (tip held: clamp, divot)
//
// The shaft torque tau_s acts only while the shaft bears on a cannula wall:
// with the walls at c ± delta, the shaft is in contact
// with the upper wall when p = d − D(tau without its own joint's load) > c + delta,
// and then D(tau) = d − (c + delta), plus the shaft's damping c_s·(omega − psi).
// Inside the clearance tau_s = 0: a real gap. Contact changes are CVODE root
// events (CVodeRootInit), after which the integrator restarts (CVodeReInit).

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <Eigen/Core>
#include <array>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"
#include "pliant/experiments/truth_model.h"

namespace pliant::experiments::detail {

class PsmPlant {
 public:
  /// Starts at rest with the tip centred in the clearance.
  PsmPlant(const Scenario& scenario, const TruthModel& truth, const Eigen::Vector2d& angle_rad,
           double depth_m);
  ~PsmPlant();
  PsmPlant(const PsmPlant&) = delete;
  PsmPlant& operator=(const PsmPlant&) = delete;

  /// Effort and insertion depth, held constant until the next Advance (the
  /// controller's zero-order hold).
  void SetInput(const Eigen::Vector2d& effort_nm, double depth_m);
  /// Holds the tip where it is now (clamp, divot) or frees it.
  void SetTipFixed(bool fixed);
  /// Integrates to t_end (s). Throws std::runtime_error when CVODE fails.
  void Advance(double t_end);

  double time_s() const { return t_; }
  Eigen::Vector2d JointAngle() const { return {y_data()[0], y_data()[1]}; }
  Eigen::Vector2d JointVelocity() const { return {y_data()[2], y_data()[3]}; }
  Eigen::Vector2d TipAngle() const {
    return {y_data()[0] - y_data()[4], y_data()[1] - y_data()[5]};
  }
  /// The shaft torque at the current state (N·m): the external load.
  Eigen::Vector2d ShaftTorque();
  const SimulationStats& stats() const { return stats_; }

 private:
  static int Rhs(double t, N_Vector y, N_Vector ydot, void* self);
  static int Roots(double t, N_Vector y, double* g, void* self);
  static int Jacobian(double t, N_Vector y, N_Vector f, SUNMatrix jacobian, void* self, N_Vector,
                      N_Vector, N_Vector);
  const double* y_data() const { return N_VGetArrayPointer(y_); }
  models::JointState<double> StateAt(double t, const double* y) const;
  Eigen::Vector2d ShaftTorqueAt(double t, const double* y,
                                Eigen::Matrix2d* d_torque_d_deflection = nullptr);
  Eigen::Vector2d GapPosition(double t, const double* y);
  void ClassifyContacts();
  void Restart();

  const TruthModel& truth_;
  Eigen::Vector2d inertia_;
  TipDynamics tip_;
  SUNContext context_ = nullptr;
  void* cvode_ = nullptr;
  N_Vector y_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
  double t_ = 0.0;
  Eigen::Vector2d effort_nm_ = Eigen::Vector2d::Zero();
  double depth_m_ = 0.0;
  bool tip_fixed_ = false;
  std::array<int, 2> contact_{0, 0};  // −1 lower wall, 0 in the clearance, +1 upper wall
  Eigen::Vector2d torque_guess_ = Eigen::Vector2d::Zero();
  SimulationStats stats_;
  long steps_before_restart_ = 0;
};

}  // namespace pliant::experiments::detail
