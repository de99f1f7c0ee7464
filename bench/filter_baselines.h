#pragma once
// The two baselines the online filter is measured against (bench/filter_bench.cpp),
// implementing the same model as estimation/filter.h (its header states it):
//   DenseFixedEkf    — a straightforward fixed-size Eigen EKF: the 12-state
//                      process and the 4 measurements (q1, q2, tau1, tau2) as
//                      functions of the whole state, Jacobians by ceres::Jet<12>,
//                      dense F P Fᵀ + Q, batch update with a 4×4 S and the
//                      dense Joseph form (I − K H) P (I − K H)ᵀ + K R Kᵀ.
//   DenseDynamicEkf  — the same with Eigen::MatrixXd / VectorXd.
// Like the filter: the seating bound when a free tip is held, s, e and beta
// as consider states (zero gain) while the tip is free, e with the tip held
// until a wall is pressed, beta but in the unloaded start. No gating,
// mismatch test, release or reference channel: the bench feeds clean data.
// Header-only so that a test can check the fast filter against it.

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <ceres/jet.h>

#include "pliant/estimation/filter.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/effects/shaft_damping.h"
#include "pliant/models/parameters.h"

namespace pliant::bench {

constexpr int kN = 2 * estimation::kFilterJointStates;  // 12
constexpr int kS = estimation::kFilterJointStates;       // per joint
using Jet8 = ceres::Jet<double, kN>;

// State order: (q_tip, tau, b, s, e, beta) of joint 1, then of joint 2.
class EkfModel {
 public:
  EkfModel(const models::ModelParameters& p, const estimation::FilterOptions& o)
      : parameters_(p), options_(o), compliance_(p.joints[0], p.joints[1]) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 4; ++i) coefficients_[4 * j + i] = Jet8(p.joints[j].compliance.cubic.coefficients[i]);
      delta_[j] = p.joints[j].backlash_rad;
      const std::string prefix = "joint" + std::to_string(j + 1) + ".";
      sd_delta_[j] = estimation::ResolvedStandardDeviation(
          o.backlash_sd_rad[j], p, prefix + "backlash_rad", o.kDefaultBacklashSdRad);
      sd_width_[j] = estimation::ResolvedStandardDeviation(o.deadzone_width_sd_nm[j], p,
                                                           prefix + "deadzone_width_nm", 0.0);
      sd_beta_[j] = estimation::ResolvedStandardDeviation(
          o.effort_offset_sd_nm[j], p, prefix + "bias_torque.coefficients[0]",
          o.kDefaultEffortOffsetSdNm);
      width_[j] = estimation::FilterDeadZoneWidth(o, p.joints[j]);
    }
  }

  template <typename T>
  void Process(const T* x, bool tip_fixed, const Eigen::Vector2d& increment, double dt,
               T* next) {
    dt_ = dt;
    for (int j = 0; j < 2; ++j) {
      const T* xj = x + kS * j;
      T* nj = next + kS * j;
      nj[0] = xj[0] + (tip_fixed ? 0.0 : increment[j]);
      // The hold g of the sure load, as a constant, as the filter does.
      const double hold = models::BacklashHold(sure_load_[j], width_[j]);
      // A held tip's load follows the motor, as in the filter.
      nj[1] = xj[1];
      if (tip_fixed && options_.load_follows_motor) {
        nj[1] += estimation::HeldLoadIncrement(hold, increment[j], xj[3], Compliance(j, depth_));
      }
      nj[2] = models::BacklashHysteresisStep(xj[2], xj[1], delta_[j] + xj[4], width_[j],
                                             tip_fixed ? 0.0 : Relax(j, increment[j]), hold);
      nj[3] = xj[3];
      nj[4] = xj[4];
      nj[5] = xj[5];
    }
  }

  // (q_enc1, q_enc2, tau1, tau2) predicted from the state.
  void Measure(const Jet8* x, double depth, Jet8* z) const {
    models::JointState<Jet8> state;
    state.insertion_depth_m = Jet8(depth);
    state.external_torque_nm << x[1], x[kS + 1];
    const models::Vec2<Jet8> bend = compliance_(coefficients_, state);
    for (int j = 0; j < 2; ++j) {
      z[j] = x[kS * j] + x[kS * j + 2] + x[kS * j + 3] * bend[j];
      z[2 + j] = x[kS * j + 1] + x[kS * j + 5];
    }
  }

  double dt_ = 0.0;
  double Relax(int, double increment) const {
    return estimation::BacklashRelax(options_, dt_, increment);
  }

  Eigen::Matrix<double, kN, 1> ProcessNoise(const Eigen::Matrix<double, kN, 1>& x, bool tip_fixed,
                                            const Eigen::Vector2d& increment, double dt) const {
    const auto& o = options_;
    Eigen::Matrix<double, kN, 1> q;
    for (int j = 0; j < 2; ++j) {
      const double sat = models::SmoothSaturation(sure_load_[j] / width_[j]);
      q[kS * j] = tip_fixed ? 0.0 : o.free_tip_rate_rad * o.free_tip_rate_rad * dt;
      q[kS * j + 1] = tip_fixed ? estimation::HeldLoadProcessVariance(
                                      o, dt, increment_peak_[j],
                                      x[kS * j + 3] * Compliance(j, depth_),
                                      inertial_torque_[j],
                                      models::BacklashHold(sure_load_[j], width_[j]))
                                : o.external_torque_rate_nm * o.external_torque_rate_nm * dt;
      const double relax = tip_fixed ? 0.0 : Relax(j, increment[j]);
      q[kS * j + 2] =
          estimation::BacklashProcessVariance(o, dt, tip_fixed, relax, sat, delta_[j]);
      q[kS * j + 3] = o.compliance_scale_rate * o.compliance_scale_rate * dt;
      q[kS * j + 4] = 0.0;
      q[kS * j + 5] = o.effort_offset_rate_nm * o.effort_offset_rate_nm * dt;
    }
    return q;
  }

  double SteadyBacklash(int j, double tau) const {
    const double noise = options_.effort_noise_nm * options_.effort_noise_nm;
    return delta_[j] * models::SmoothSaturation(estimation::SureLoad(options_, tau, noise) / width_[j]);
  }
  /// The loads the filter is sure of (SureLoad), the motors' inertial torques
  /// (N·m) and recent increments (rad), and the insertion depth (m), set
  /// before each prediction.
  double sure_load_[2] = {0.0, 0.0};
  double inertial_torque_[2] = {0.0, 0.0};
  double increment_peak_[2] = {0.0, 0.0};
  double depth_ = 0.15;
  double Compliance(int j, double depth) const {
    return models::ComplianceAt(parameters_.joints[j], depth);
  }
  double BacklashCap(int j) const {
    return (delta_[j] * delta_[j] + sd_delta_[j] * sd_delta_[j]) / 3.0;
  }
  double ClearanceVariance(int j) const { return sd_delta_[j] * sd_delta_[j] + 1e-14; }
  double OffsetVariance(int j) const { return sd_beta_[j] * sd_beta_[j] + 1e-14; }
  double Bias(int j, double q, double depth) const {
    return models::BiasTorqueAt(parameters_.joints[j], q, depth);
  }
  const estimation::FilterOptions& options() const { return options_; }
  double delta(int j) const { return delta_[j]; }
  double width(int j) const { return width_[j]; }
  double width_sd(int j) const { return sd_width_[j]; }

 private:
  models::ModelParameters parameters_;
  estimation::FilterOptions options_;
  models::ComplianceEffect compliance_;
  Jet8 coefficients_[8];
  double delta_[2], width_[2], sd_delta_[2], sd_width_[2], sd_beta_[2];
};

struct FixedSizeTypes {
  using V8 = Eigen::Matrix<double, kN, 1>;
  using M88 = Eigen::Matrix<double, kN, kN>;
  using M48 = Eigen::Matrix<double, 4, kN>;
  using M84 = Eigen::Matrix<double, kN, 4>;
  using V4 = Eigen::Vector4d;
  using M44 = Eigen::Matrix4d;
};
struct DynamicSizeTypes {
  using V8 = Eigen::VectorXd;
  using M88 = Eigen::MatrixXd;
  using M48 = Eigen::MatrixXd;
  using M84 = Eigen::MatrixXd;
  using V4 = Eigen::VectorXd;
  using M44 = Eigen::MatrixXd;
};

// Everything but the matrix types is shared.
template <typename Types>
class DenseEkf {
  using Vector = typename Types::V8;
  using Matrix = typename Types::M88;

 public:
  DenseEkf(const models::ModelParameters& p, const estimation::FilterOptions& o)
      : model_(p, o), x_(Vector::Zero(kN)), p_(Matrix::Zero(kN, kN)) {}

  void Step(const estimation::FilterSample& s) {
    const auto& o = model_.options();
    if (!initialised_) {
      for (int j = 0; j < 2; ++j) {
        const double tau = s.effort_nm[j] - model_.Bias(j, s.encoder_rad[j], s.insertion_depth_m);
        const double b = model_.SteadyBacklash(j, tau);
        x_.template segment<kS>(kS * j) << s.encoder_rad[j] - b - model_.Compliance(j, s.insertion_depth_m) * tau,
            tau, b, 1.0, 0.0, 0.0;
        p_(kS * j, kS * j) = o.initial_tip_sd_rad * o.initial_tip_sd_rad;
        p_(kS * j + 1, kS * j + 1) = o.initial_torque_sd_nm * o.initial_torque_sd_nm;
        p_(kS * j + 2, kS * j + 2) = model_.BacklashCap(j) + 1e-14;
        p_(kS * j + 3, kS * j + 3) = o.compliance_scale_sd * o.compliance_scale_sd;
        p_(kS * j + 4, kS * j + 4) = model_.ClearanceVariance(j);
        p_(kS * j + 5, kS * j + 5) = model_.OffsetVariance(j);
        if (estimation::InUnloadedStart(o, 0.0)) {
          x_.template segment<kS>(kS * j) << s.encoder_rad[j], 0.0, 0.0, 1.0, 0.0, 0.0;
        }
      }
      for (int j = 0; j < 2 && s.tip_fixed; ++j) walls_[j].Seat();  // a log that starts held
      initialised_ = true;
      start_time_ = last_time_ = s.time_s;
      last_encoder_ = s.encoder_rad;
    } else {
      // The seating bound, per joint: without a coupling effect the joints'
      // cross-covariance is zero, so the 12-state bound is the two 6-state ones.
      if (s.tip_fixed && !last_tip_fixed_) {
        for (int j = 0; j < 2; ++j) {
          walls_[j].Seat();
          estimation::FilterStateMatrix block = p_.template block<kS, kS>(kS * j, kS * j);
          estimation::SeatingBound(&block, o.seating_bound_weight);
          p_.template block<kS, kS>(kS * j, kS * j) = block;
        }
      }
      Predict(s);
    }
    last_tip_fixed_ = s.tip_fixed;
    Update(s);
  }

  const Vector& mean() const { return x_; }
  const Matrix& covariance() const { return p_; }

 private:
  void Predict(const estimation::FilterSample& s) {
    double dt = s.time_s - last_time_;
    if (!(dt > 0.0)) dt = model_.options().sample_period_s;
    last_time_ = s.time_s;
    Eigen::Vector2d increment = s.encoder_rad - last_encoder_;
    for (int j = 0; j < 2; ++j) {
      if (!(std::abs(increment[j]) <= 5.0 * dt)) increment[j] = 0.0;
    }
    last_encoder_ = s.encoder_rad;
    for (int j = 0; j < 2; ++j) {
      motion_[j].Advance(model_.options(), dt, increment[j]);
      bend_rate_[j] = increment[j] / dt;
    }
    Jet8 x[kN], next[kN];
    for (int i = 0; i < kN; ++i) x[i] = Jet8(x_[i], i);
    bool first_press[2];
    for (int j = 0; j < 2; ++j) {
      const int t = kS * j + 1;
      model_.sure_load_[j] = estimation::SureLoad(model_.options(), x_[t], p_(t, t));
      const double sure = model_.sure_load_[j], width = model_.width(j);
      const int e = kS * j + estimation::kStateClearance;
      first_press[j] =
          s.tip_fixed && walls_[j].Observe(models::BacklashHold(sure, width),
                                           estimation::ClearanceLearnable(
                                               model_.options(), sure, width, model_.width_sd(j),
                                               model_.delta(j), p_(e, e)));
      model_.inertial_torque_[j] = motion_[j].InertialTorque(model_.options());
      model_.increment_peak_[j] = motion_[j].increment_peak_rad;
    }
    model_.depth_ = s.insertion_depth_m;
    model_.Process(x, s.tip_fixed, increment, dt, next);
    Matrix f(kN, kN);
    for (int i = 0; i < kN; ++i) {
      x_[i] = next[i].a;
      f.row(i) = next[i].v.transpose();
    }
    Eigen::Matrix<double, kN, 1> q = model_.ProcessNoise(x_, s.tip_fixed, increment, dt);
    for (int j = 0; j < 2; ++j) {
      const int b = kS * j + 2;
      const Eigen::Matrix<double, kN, 1> f_row = f.row(b).transpose();
      const auto bound = estimation::BoundBacklashVariance(
          s.tip_fixed, f_row.dot(p_ * f_row), q[b], model_.BacklashCap(j));
      f.row(b) *= bound.row_scale;
      q[b] = bound.process_variance;
    }
    p_ = (f * p_ * f.transpose()).eval();
    p_.diagonal() += q;
    for (int j = 0; j < 2; ++j) {
      if (first_press[j]) {
        p_(kS * j, kS * j) += estimation::ClearanceWalls::ForgottenStartVariance(model_.BacklashCap(j));
      }
    }
  }

  void Update(const estimation::FilterSample& s) {
    const auto& o = model_.options();
    Jet8 x[kN], z[4];
    const bool unloaded = estimation::InUnloadedStart(o, s.time_s - start_time_);
    for (int j = 0; unloaded && j < 2; ++j) {  // the load known: 0
      x_[kS * j + 1] = 0.0;
      p_.row(kS * j + 1).setZero();
      p_.col(kS * j + 1).setZero();
    }
    for (int i = 0; i < kN; ++i) x[i] = Jet8(x_[i], i);
    model_.Measure(x, s.insertion_depth_m, z);
    typename Types::M48 h(4, kN);
    typename Types::V4 innovation(4);
    for (int i = 0; i < 4; ++i) h.row(i) = z[i].v.transpose();
    for (int j = 0; j < 2; ++j) {
      innovation[j] = s.encoder_rad[j] - z[j].a;
      const int t = kS * j + 1;
      const double held =
          s.tip_fixed
              ? motion_[j].InertialTorque(o) +
                    models::ShaftDampingTorque(
                        o.shaft_damping_nm_s_per_rad, bend_rate_[j],
                        models::BacklashHold(estimation::SureLoad(o, x_[t], p_(t, t)),
                                             model_.width(j)))
              : 0.0;
      innovation[2 + j] =
          s.effort_nm[j] - model_.Bias(j, s.encoder_rad[j], s.insertion_depth_m) - held -
          z[2 + j].a;
    }
    typename Types::M44 r = Types::M44::Zero(4, 4);
    for (int j = 0; j < 2; ++j) {
      const double deflection = o.DeflectionModelError() * h(j, kS * j + 3);  // error × K·tau
      r(j, j) = o.encoder_noise_rad * o.encoder_noise_rad + deflection * deflection;
      r(2 + j, 2 + j) = s.tip_fixed ? estimation::HeldEffortVariance(o, motion_[j].InertialTorque(o))
                                    : o.effort_noise_nm * o.effort_noise_nm;
      // s is taught by the sure load while it holds the shaft, as in the filter.
      const int t = kS * j + 1;
      h(j, kS * j + 3) *= estimation::ScaleLearningFraction(o, x_[t], p_(t, t), model_.width(j));
    }
    const typename Types::M84 ph = p_ * h.transpose();
    const typename Types::M44 innovation_cov = h * ph + r;
    typename Types::M84 gain = innovation_cov.ldlt().solve(ph.transpose()).transpose();
    // Consider states (Schmidt–Kalman), as in the filter: with the tip free s
    // and e; held, e until the hold has pressed a wall and where the load may
    // not teach it (ClearanceLearnable); beta always but in the unloaded start.
    for (int j = 0; j < 2; ++j) {
      if (!s.tip_fixed) gain.row(kS * j + estimation::kStateScale).setZero();
      if (!s.tip_fixed || (o.clearance_needs_a_wall && !walls_[j].TeachClearance())) {
        gain.row(kS * j + estimation::kStateClearance).setZero();
      }
      if (!unloaded) gain.row(kS * j + estimation::kStateEffortOffset).setZero();
    }
    x_ += gain * innovation;
    const Matrix a = Matrix::Identity(kN, kN) - gain * h;
    p_ = (a * p_ * a.transpose() + gain * r * gain.transpose()).eval();
    p_ = (0.5 * (p_ + p_.transpose())).eval();
    for (int j = 0; j < 2; ++j) {
      estimation::ConfineToClearance(model_.delta(j), &x_[kS * j + estimation::kStateClearance],
                                     &x_[kS * j + estimation::kStateBacklash]);
    }
  }

  EkfModel model_;
  Vector x_;
  Matrix p_;
  bool initialised_ = false;
  bool last_tip_fixed_ = false;
  double last_time_ = 0.0, start_time_ = 0.0;
  estimation::ClearanceWalls walls_[2];
  Eigen::Vector2d last_encoder_{0.0, 0.0};
  estimation::MotorMotion motion_[2];
  double bend_rate_[2] = {0.0, 0.0};  // the encoder's rate over the step, rad/s
};

using DenseFixedEkf = DenseEkf<FixedSizeTypes>;
using DenseDynamicEkf = DenseEkf<DynamicSizeTypes>;

}  // namespace pliant::bench
