#include "psm_plant.h"

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <stdexcept>
#include <string>

#include "pliant/models/effects/shaft_damping.h"

namespace pliant::experiments::detail {
namespace {

constexpr int kStates = 8;
constexpr int kRoots = 4;  // per joint: the upper and the lower wall

void Check(int flag, const char* call) {
  if (flag < 0) {
    throw std::runtime_error(std::string("CVODE: ") + call +
                             " failed: " + CVodeGetReturnFlagName(flag));
  }
}

// CVODE's own messages go nowhere: a failure becomes an exception naming the call.
void QuietErrors(int, const char*, const char*, char*, void*) {}

}  // namespace

PsmPlant::PsmPlant(const Scenario& scenario, const TruthModel& truth,
                   const Eigen::Vector2d& angle_rad, double depth_m)
    : truth_(truth), inertia_(scenario.joint.inertia_kg_m2), tip_(scenario.tip), depth_m_(depth_m) {
  if (SUNContext_Create(nullptr, &context_) != 0) throw std::runtime_error("SUNContext_Create");
  y_ = N_VNew_Serial(kStates, context_);
  double* y = N_VGetArrayPointer(y_);
  const Eigen::Vector2d centre = truth_.clearance_centre_rad();
  for (int j = 0; j < 2; ++j) {
    y[j] = angle_rad[j];
    y[2 + j] = 0.0;
    y[4 + j] = centre[j] + scenario.truth.initial_shaft_offset_rad[j];  // inside the clearance
    y[6 + j] = 0.0;
  }
  // BDF with Newton iterations: a light tip on a stiff shaft makes the system
  // stiff (eigenvalues near −1e4 1/s against a 0.67 ms control period).
  cvode_ = CVodeCreate(CV_BDF, context_);
  if (!cvode_) throw std::runtime_error("CVodeCreate failed");
  Check(CVodeSetErrHandlerFn(cvode_, QuietErrors, nullptr), "CVodeSetErrHandlerFn");
  Check(CVodeInit(cvode_, &PsmPlant::Rhs, 0.0, y_), "CVodeInit");
  Check(CVodeSetUserData(cvode_, this), "CVodeSetUserData");
  N_Vector tolerances = N_VNew_Serial(kStates, context_);
  double* atol = N_VGetArrayPointer(tolerances);
  const auto& in = scenario.integrator;
  for (int i = 0; i < kStates; ++i) {
    atol[i] = (i / 2) % 2 == 0 ? in.angle_tolerance_rad : in.velocity_tolerance_rad_s;
  }
  Check(CVodeSVtolerances(cvode_, in.relative_tolerance, tolerances), "CVodeSVtolerances");
  N_VDestroy(tolerances);
  matrix_ = SUNDenseMatrix(kStates, kStates, context_);
  solver_ = SUNLinSol_Dense(y_, matrix_, context_);
  Check(CVodeSetLinearSolver(cvode_, solver_, matrix_), "CVodeSetLinearSolver");
  Check(CVodeSetJacFn(cvode_, &PsmPlant::Jacobian), "CVodeSetJacFn");
  Check(CVodeRootInit(cvode_, kRoots, &PsmPlant::Roots), "CVodeRootInit");
  Check(CVodeSetNoInactiveRootWarn(cvode_), "CVodeSetNoInactiveRootWarn");
  ClassifyContacts();
}

PsmPlant::~PsmPlant() {
  CVodeFree(&cvode_);
  SUNLinSolFree(solver_);
  SUNMatDestroy(matrix_);
  N_VDestroy(y_);
  SUNContext_Free(&context_);
}

void PsmPlant::SetInput(const Eigen::Vector2d& effort_nm, double depth_m) {
  // A new zero-order-hold value each period: a small jump in the acceleration
  // that CVODE's error control absorbs without a restart (docs/simulator.md).
  effort_nm_ = effort_nm;
  depth_m_ = depth_m;
}

void PsmPlant::SetTipFixed(bool fixed) {
  if (fixed == tip_fixed_) return;
  tip_fixed_ = fixed;
  double* y = N_VGetArrayPointer(y_);
  if (fixed) y[6] = y[2], y[7] = y[3];  // the clamp stops the tip where it is: psi = 0
  Restart();
}

void PsmPlant::Restart() {
  long steps = 0;
  CVodeGetNumSteps(cvode_, &steps);
  steps_before_restart_ += steps;
  ClassifyContacts();
  Check(CVodeReInit(cvode_, t_, y_), "CVodeReInit");
}

void PsmPlant::Advance(double t_end) {
  Check(CVodeSetStopTime(cvode_, t_end), "CVodeSetStopTime");
  while (t_ < t_end) {
    const int flag = CVode(cvode_, t_end, y_, &t_, CV_NORMAL);
    Check(flag, "CVode");
    if (flag == CV_ROOT_RETURN) {
      int found[kRoots];
      CVodeGetRootInfo(cvode_, found);
      for (int j = 0; j < 2; ++j) {
        // Upper wall crossed upward: contact; downward: back in the clearance.
        if (found[2 * j] != 0) contact_[j] = found[2 * j] > 0 ? +1 : 0;
        if (found[2 * j + 1] != 0) contact_[j] = found[2 * j + 1] < 0 ? -1 : 0;
      }
      ++stats_.contact_events;
      long steps = 0;
      CVodeGetNumSteps(cvode_, &steps);
      steps_before_restart_ += steps;
      Check(CVodeReInit(cvode_, t_, y_), "CVodeReInit");
      Check(CVodeSetStopTime(cvode_, t_end), "CVodeSetStopTime");
    }
  }
  long steps = 0;
  CVodeGetNumSteps(cvode_, &steps);
  stats_.integrator_steps = steps_before_restart_ + steps;
  stats_.simulated_s = t_;
}

models::JointState<double> PsmPlant::StateAt(double t, const double* y) const {
  models::JointState<double> state;
  state.encoder_angle_rad << y[0], y[1];
  state.velocity_rad_s << y[2], y[3];
  state.insertion_depth_m = depth_m_;
  state.time_s = t;
  return state;
}

Eigen::Vector2d PsmPlant::GapPosition(double t, const double* y) {
  // Where the shaft sits in the clearance: d minus the bend the other joint's
  // load causes here (non-zero only with deflection coupling).
  models::JointState<double> state = StateAt(t, y);
  const Eigen::Vector2d tau = ShaftTorqueAt(t, y);
  Eigen::Vector2d p;
  for (int j = 0; j < 2; ++j) {
    state.external_torque_nm = tau;
    state.external_torque_nm[j] = 0.0;
    p[j] = y[4 + j] - truth_.Deflection(state)[j];
  }
  return p;
}

Eigen::Vector2d PsmPlant::ShaftTorqueAt(double t, const double* y,
                                        Eigen::Matrix2d* d_torque_d_deflection) {
  const std::array<bool, 2> contact{contact_[0] != 0, contact_[1] != 0};
  if (d_torque_d_deflection) d_torque_d_deflection->setZero();
  if (!contact[0] && !contact[1]) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d& delta = truth_.backlash_rad();
  const Eigen::Vector2d& centre = truth_.clearance_centre_rad();
  Eigen::Vector2d elastic;
  for (int j = 0; j < 2; ++j) {
    elastic[j] = y[4 + j] - (centre[j] + contact_[j] * delta[j]);
  }
  Eigen::Vector2d tau =
      truth_.ShaftTorque(elastic, contact, StateAt(t, y), torque_guess_, d_torque_d_deflection);
  torque_guess_ = tau;
  for (int j = 0; j < 2; ++j) {
    tau[j] += models::ShaftDampingTorque(tip_.shaft_damping_nm_s_per_rad, y[6 + j],
                                         contact[j] ? 1.0 : 0.0);
  }
  return tau;
}

Eigen::Vector2d PsmPlant::ShaftTorque() { return ShaftTorqueAt(t_, N_VGetArrayPointer(y_)); }

void PsmPlant::ClassifyContacts() {
  const double* y = N_VGetArrayPointer(y_);
  // Classify with no contact assumed, then with the result, so that coupled
  // loads are accounted for; strict inequalities keep a shaft exactly at a
  // wall in the clearance until the root event says otherwise.
  contact_ = {0, 0};
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Vector2d p = GapPosition(t_, y);
    std::array<int, 2> next{0, 0};
    for (int j = 0; j < 2; ++j) {
      const double upper = truth_.clearance_centre_rad()[j] + truth_.backlash_rad()[j];
      const double lower = truth_.clearance_centre_rad()[j] - truth_.backlash_rad()[j];
      next[j] = p[j] > upper ? +1 : (p[j] < lower ? -1 : 0);
    }
    contact_ = next;
  }
}

int PsmPlant::Rhs(double t, N_Vector y_vector, N_Vector ydot_vector, void* self) {
  auto& plant = *static_cast<PsmPlant*>(self);
  const double* y = N_VGetArrayPointer(y_vector);
  double* ydot = N_VGetArrayPointer(ydot_vector);
  ++plant.stats_.rhs_evaluations;
  try {
    const Eigen::Vector2d internal = plant.truth_.InternalTorque(plant.StateAt(t, y));
    const Eigen::Vector2d shaft = plant.ShaftTorqueAt(t, y);
    for (int j = 0; j < 2; ++j) {
      ydot[j] = y[2 + j];
      ydot[2 + j] = (plant.effort_nm_[j] - internal[j] - shaft[j]) / plant.inertia_[j];
      ydot[4 + j] = y[6 + j];
      ydot[6 + j] = ydot[2 + j];  // the tip held: d'' = omega'
      if (!plant.tip_fixed_) {
        const double tip_velocity = y[2 + j] - y[6 + j];
        ydot[6 + j] -=
            (shaft[j] - plant.tip_.damping_nm_s_per_rad * tip_velocity) / plant.tip_.inertia_kg_m2;
      }
    }
  } catch (const std::exception&) {
    return -1;  // unrecoverable: CVODE stops and Advance throws
  }
  return 0;
}

int PsmPlant::Roots(double t, N_Vector y_vector, double* g, void* self) {
  auto& plant = *static_cast<PsmPlant*>(self);
  const double* y = N_VGetArrayPointer(y_vector);
  const Eigen::Vector2d p = plant.GapPosition(t, y);
  for (int j = 0; j < 2; ++j) {
    g[2 * j] = p[j] - (plant.truth_.clearance_centre_rad()[j] + plant.truth_.backlash_rad()[j]);
    g[2 * j + 1] = p[j] - (plant.truth_.clearance_centre_rad()[j] - plant.truth_.backlash_rad()[j]);
  }
  return 0;
}

}  // namespace pliant::experiments::detail

namespace pliant::experiments::detail {

// The exact Jacobian of Rhs, so that a restart costs no difference quotients.
int PsmPlant::Jacobian(double t, N_Vector y_vector, N_Vector, SUNMatrix jacobian, void* self,
                       N_Vector, N_Vector, N_Vector) {
  auto& plant = *static_cast<PsmPlant*>(self);
  const double* y = N_VGetArrayPointer(y_vector);
  try {
    const Eigen::Matrix<double, 2, 4> internal =
        plant.truth_.InternalTorqueJacobian(plant.StateAt(t, y));
    Eigen::Matrix2d stiffness;  // d tau_s / d d
    plant.ShaftTorqueAt(t, y, &stiffness);
    Eigen::Matrix<double, 8, 8> J = Eigen::Matrix<double, 8, 8>::Zero();
    const bool free_tip = !plant.tip_fixed_;
    const double tip_inertia = plant.tip_.inertia_kg_m2;
    const double c_t = plant.tip_.damping_nm_s_per_rad;
    for (int j = 0; j < 2; ++j) {
      const double damping = plant.contact_[j] != 0 ? plant.tip_.shaft_damping_nm_s_per_rad : 0.0;
      J(j, 2 + j) = 1.0;
      J(4 + j, 6 + j) = 1.0;
      // omega_j' = (u − tau_int(theta, omega) − tau_s(d, d')) / J_j
      J.block<1, 4>(2 + j, 0) = -internal.row(j) / plant.inertia_[j];
      J(2 + j, 4) = -stiffness(j, 0) / plant.inertia_[j];
      J(2 + j, 5) = -stiffness(j, 1) / plant.inertia_[j];
      J(2 + j, 6 + j) = -damping / plant.inertia_[j];
      // d_j'' = omega_j' − (tau_s − c_t·(omega − d')) / J_t when the tip is free
      J.row(6 + j) = J.row(2 + j);
      if (free_tip) {
        J(6 + j, 4) -= stiffness(j, 0) / tip_inertia;
        J(6 + j, 5) -= stiffness(j, 1) / tip_inertia;
        J(6 + j, 6 + j) -= (damping + c_t) / tip_inertia;
        J(6 + j, 2 + j) += c_t / tip_inertia;
      }
    }
    for (int column = 0; column < 8; ++column) {
      double* out = SUNDenseMatrix_Column(jacobian, column);
      for (int row = 0; row < 8; ++row) out[row] = J(row, column);
    }
  } catch (const std::exception&) {
    return -1;
  }
  return 0;
}

}  // namespace pliant::experiments::detail
