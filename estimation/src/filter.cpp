// The online filter (filter.h). Two 6-state joint blocks, sparse prediction,
// sequential scalar Joseph updates, Jacobians from ceres::Jet. Nothing in
// Step() allocates or throws: every buffer is sized in the constructor.
#include "pliant/estimation/filter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <ceres/jet.h>

#include "chi_squared.h"
#include "filter_impl.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/effects/shaft_damping.h"

namespace pliant::estimation {

using namespace filter_internal;

namespace {

// Joint j's prior covariance: diag(σ_tip0², σ_τ0², (δ² + σ_δ²)/3, σ_s², σ_δ², σ_β²);
// b uniform on ±(δ + e). The floors keep P positive definite when σ = 0.
Matrix PriorCovariance(const FilterOptions& o, double delta, const InstrumentUncertainty& u) {
  const double sd_delta2 = u.clearance_sd_rad * u.clearance_sd_rad;
  Vector d;
  d << o.initial_tip_sd_rad * o.initial_tip_sd_rad,
      o.initial_torque_sd_nm * o.initial_torque_sd_nm, (delta * delta + sd_delta2) / 3.0 + 1e-14,
      o.compliance_scale_sd * o.compliance_scale_sd, sd_delta2 + 1e-14,
      u.effort_offset_sd_nm * u.effort_offset_sd_nm + 1e-14;
  return d.asDiagonal();
}

// Fixed-size Cholesky: no allocation, a bounded number of operations.
bool IsPositiveDefinite(const Matrix& p) {
  return Eigen::LLT<Matrix>(p).info() == Eigen::Success;
}

// The option when it is given (finite), else the parameters' covariance,
// else the documented default.
double ResolveSd(double option, const models::ModelParameters& p, const std::string& name,
                 double fallback) {
  if (std::isfinite(option)) return option;
  const double from_covariance = ParameterStandardDeviation(p, name);
  return std::isfinite(from_covariance) ? from_covariance : fallback;
}

}  // namespace

ComplianceFilter::Impl::Impl(const models::ModelParameters& p, const FilterOptions& o)
    : parameters(p), options(o), compliance(p.joints[0], p.joints[1]) {
  const std::string why = models::ValidateParameters(p);
  if (!why.empty()) throw std::invalid_argument(why);
  std::string error;
  if (!o.IsValid(&error)) throw std::invalid_argument(error);
  options.deflection_model_error = o.DeflectionModelError();  // NaN resolved once
  for (int j = 0; j < 2; ++j) {
    const auto& joint_parameters = p.joints[j];
    for (int i = 0; i < 4; ++i) {
      compliance_coefficients[4 * j + i] = StateJet(joint_parameters.compliance.cubic.coefficients[i]);
    }
    delta[j] = joint_parameters.backlash_rad;
    const std::string prefix = "joint" + std::to_string(j + 1) + ".";
    uncertainty[j].clearance_sd_rad = ResolveSd(o.backlash_sd_rad[j], p, prefix + "backlash_rad",
                                                FilterOptions::kDefaultBacklashSdRad);
    uncertainty[j].effort_offset_sd_nm =
        ResolveSd(o.effort_offset_sd_nm[j], p, prefix + "bias_torque.coefficients[0]",
                  FilterOptions::kDefaultEffortOffsetSdNm);
    // The width over which the filter lets the load pin the shaft.
    width[j] = FilterDeadZoneWidth(o, joint_parameters);
  }
  depth = 0.5 * (p.joints[0].depth_min_m + p.joints[0].depth_max_m);
  gate = internal::ChiSquaredQuantile(1.0, o.gate_probability);
  output_count_rad = std::sqrt(12.0) * o.encoder_noise_rad;
  const int max_dof = kMaxScalarsPerStep * o.mismatch_window;
  window_threshold.resize(max_dof + 1);
  window_threshold[0] = 0.0;
  const double z = std::sqrt(2.0) * [&] {
    // Normal quantile from χ²(1): z² = χ²₁(2p − 1).
    return std::sqrt(0.5 * internal::ChiSquaredQuantile(1.0, 2.0 * o.mismatch_probability - 1.0));
  }();
  for (int d = 1; d <= max_dof; ++d) {
    if (d <= kExactQuantileDof) {
      window_threshold[d] = internal::ChiSquaredQuantile(d, o.mismatch_probability);
    } else {
      const double c = 2.0 / (9.0 * d);
      window_threshold[d] = d * std::pow(1.0 - c + z * std::sqrt(c), 3.0);
    }
  }
  window_nis.assign(o.mismatch_window, 0.0);
  window_dof.assign(o.mismatch_window, 0);
  if (o.align_inertial_torque && o.motor_inertia_kg_m2 > 0.0) {
    const double lag_steps = MotorMotion::LagSeconds(o) / o.sample_period_s;
    alignment_steps = std::clamp(static_cast<int>(std::lround(lag_steps)), 0, kHeldCapacity - 1);
  }
  Reset();
}

void ComplianceFilter::Impl::Reset() {
  initialised = false;
  last_tip_fixed = false;
  for (int j = 0; j < 2; ++j) {
    joint[j].mean << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0;
    joint[j].covariance = PriorCovariance(options, delta[j], uncertainty[j]);
    transition[j] = FilterTransition{};
    for (int& r : rejections[j]) r = 0;
    motion[j] = MotorMotion{};
    bend_rate_rad_s[j] = step_hold[j] = 0.0;
    walls[j].Seat();
    restart_output[j] = true;
  }
  std::fill(window_nis.begin(), window_nis.end(), 0.0);
  std::fill(window_dof.begin(), window_dof.end(), 0);
  window_position = window_count = window_dof_sum = check_phase = 0;
  motion_started = advanced = false;
  held_first = held_count = 0;
  newest_step.setZero();
  window_sum = 0.0;
}

void ComplianceFilter::Impl::Initialise(const FilterSample& sample, double depth_m) {
  for (int j = 0; j < 2; ++j) {
    const double q = std::isfinite(sample.encoder_rad[j])     ? sample.encoder_rad[j]
                     : std::isfinite(sample.reference_rad[j]) ? sample.reference_rad[j]
                                                              : 0.0;
    const double tau0 = models::BiasTorqueAt(parameters.joints[j], q, depth_m);
    // Unloaded (unloaded_start_s): the effort's departure from tau0 is β's,
    // for the updates to find, and the shaft is where its prior says.
    const double tau = std::isfinite(sample.effort_nm[j]) && !InUnloadedStart(options, 0.0)
                           ? sample.effort_nm[j] - tau0
                           : 0.0;
    // Start where the model puts the tip for this sample (the dead-zone
    // correction), so that the first encoder update adds no information twice.
    // One effort sample: a load within its noise puts the shaft nowhere in particular.
    const double sure = SureLoad(options, tau, options.effort_noise_nm * options.effort_noise_nm);
    const double b = delta[j] * models::SmoothSaturation(sure / width[j]);
    const double tip = q - b - models::ComplianceAt(parameters.joints[j], depth_m) * tau;
    joint[j].mean << tip, tau, b, 1.0, 0.0, 0.0;
    joint[j].covariance = PriorCovariance(options, delta[j], uncertainty[j]);
    transition[j] = FilterTransition{};
    transition[j].predicted_mean = joint[j].mean;
  }
  start_time_s = sample.time_s;
  initialised = true;
}

// F = I but for b's row (∂b+/∂tau, ∂b+/∂b, ∂b+/∂e from the hysteresis step's Jet), so
// F·P·Fᵀ touches only b's row and column.
void ComplianceFilter::Impl::Predict(int j, double dt, bool tip_fixed, bool seated,
                                     double encoder_increment) {
  FilterJointState& s = joint[j];
  FilterTransition& t = transition[j];
  const auto& o = options;
  t.seating_bound_weight = seated ? o.seating_bound_weight : 1.0;
  SeatingBound(&s.covariance, t.seating_bound_weight);
  // The fraction of its wall an unloaded shaft forgets as the arm moves by
  // the encoder increment: nothing holds an unloaded shaft on a wall, but it
  // only leaves it when the arm moves (a joint at rest keeps its offset).
  // Held tip: the encoders see b, and an arm moving against a held tip loads
  // the shaft toward a wall rather than freeing it, so b keeps its memory.
  const double relax = tip_fixed ? 0.0 : BacklashRelax(o, dt, encoder_increment);
  const StateJet tau(s.mean[kTorque], kTorque);
  const StateJet b(s.mean[kBacklash], kBacklash);
  // The shaft's wall is at the instrument's clearance δ + e, not the nominal δ.
  const StateJet clearance = delta[j] + StateJet(s.mean[kClearance], kClearance);
  // g enters as a constant: the Jacobian keeps ∂b+/∂tau through the target
  // δ·S(tau/w) but not through the hold (backlash_hysteresis.h says why).
  // The hold is that of the load the filter is sure of (load_margin_sd).
  const double sure_load = SureLoad(o, s.mean[kTorque], s.covariance(kTorque, kTorque));
  const double hold = models::BacklashHold(sure_load, width[j]);
  step_hold[j] = hold;
  if (seated) walls[j].Seat();
  if (tip_fixed) walls[j].Observe(hold);
  const StateJet next = models::BacklashHysteresisStep(b, tau, clearance, width[j], relax, hold);
  // How firmly the load holds the shaft on a wall: S² = 1 beyond the width,
  // 0 at no load (BacklashProcessVariance).
  const double saturation = models::SmoothSaturation(sure_load / width[j]);
  const double sd_delta = uncertainty[j].clearance_sd_rad;
  const double prior_variance = (delta[j] * delta[j] + sd_delta * sd_delta) / 3.0;
  Matrix& P = s.covariance;
  // b's row of F has three non-zeros (∂b+/∂tau, ∂b+/∂b, ∂b+/∂e): F·P's b-row
  // and b's propagated variance cost three columns, computed once and then
  // scaled by the bound (the bound scales b's row of F).
  Vector row = next.v[kTorque] * P.col(kTorque) + next.v[kBacklash] * P.col(kBacklash) +
               next.v[kClearance] * P.col(kClearance);
  const double propagated = next.v[kTorque] * row[kTorque] +
                            next.v[kBacklash] * row[kBacklash] +
                            next.v[kClearance] * row[kClearance];
  const BacklashVarianceBound bound = BoundBacklashVariance(
      tip_fixed, propagated,
      BacklashProcessVariance(o, dt, tip_fixed, relax, saturation, delta[j]), prior_variance);
  const double fbt = bound.row_scale * next.v[kTorque];
  const double fbb = bound.row_scale * next.v[kBacklash];
  const double fbe = bound.row_scale * next.v[kClearance];
  row *= bound.row_scale;
  const double pbb = bound.row_scale * bound.row_scale * propagated;

  s.mean[kTip] += tip_fixed ? 0.0 : encoder_increment;
  s.mean[kBacklash] = next.a;

  P.col(kBacklash) = row;
  P.row(kBacklash) = row.transpose();
  P(kBacklash, kBacklash) = pbb;

  // A held tip's motor bends the shaft: tau follows the encoder (F's tau row
  // gains ∂tau+/∂s). b's step above read the load before this one, so F is
  // this row's map after b's, and F·P·Fᵀ takes it after b's.
  double fts = 0.0;
  if (tip_fixed && o.load_follows_motor) {
    const StateJet added = HeldLoadIncrement(hold, encoder_increment,
                                             StateJet(s.mean[kScale], kScale), ComplianceAtDepth(j));
    s.mean[kTorque] += added.a;
    fts = added.v[kScale];
    const Vector torque_row = P.col(kTorque) + fts * P.col(kScale);
    P.col(kTorque) = torque_row;
    P.row(kTorque) = torque_row.transpose();
    P(kTorque, kTorque) = torque_row[kTorque] + fts * torque_row[kScale];
  }

  Vector q;
  q[kTip] = tip_fixed ? 0.0 : o.free_tip_rate_rad * o.free_tip_rate_rad * dt;
  // A held tip's load moves only as the motor bends the shaft (HeldLoadProcessVariance).
  q[kTorque] =
      tip_fixed ? HeldLoadProcessVariance(
                      o, dt, motion[j].increment_peak_rad,
                      s.mean[kScale] * ComplianceAtDepth(j),
                      motion[j].InertialTorque(o), hold)
                : o.external_torque_rate_nm * o.external_torque_rate_nm * dt;
  q[kBacklash] = bound.process_variance;
  q[kScale] = o.compliance_scale_rate * o.compliance_scale_rate * dt;
  q[kClearance] = 0.0;
  q[kOffset] = o.effort_offset_rate_nm * o.effort_offset_rate_nm * dt;
  P.diagonal() += q;

  t.predicted_mean = s.mean;
  t.f_torque_torque = 1.0;
  t.f_torque_scale = fts;
  t.f_backlash_torque = fbt;
  t.f_backlash_backlash = fbb;
  t.f_backlash_clearance = fbe;
  t.process_noise = q;
  t.predicted = true;
}

// Released and held again elsewhere, after a transit the log does not show
// (hold means): the load came off and the arm moved with the tip free, so the
// shaft forgets its wall as a free tip's does (BacklashRelax: by how far the
// joint moved; a joint that did not move keeps it). The tip and the load start
// again from their priors (F's row for tau is zero); the instrument's states
// (s, e, beta) carry over with what was learned about them.
void ComplianceFilter::Impl::Release(int j, double dt, double encoder_increment) {
  FilterJointState& s = joint[j];
  FilterTransition& t = transition[j];
  const Matrix prior = PriorCovariance(options, delta[j], uncertainty[j]);
  const double keep = 1.0 - BacklashRelax(options, dt, encoder_increment);
  s.mean[kTip] += encoder_increment;
  s.mean[kTorque] = 0.0;
  s.mean[kBacklash] *= keep;
  step_hold[j] = 0.0;
  walls[j].Seat();  // held elsewhere: the shaft starts anew
  Matrix& P = s.covariance;
  P.row(kTorque).setZero();
  P.col(kTorque).setZero();
  P.row(kBacklash) *= keep;
  P.col(kBacklash) *= keep;
  Vector q = Vector::Zero();
  q[kTip] = prior(kTip, kTip);
  q[kTorque] = prior(kTorque, kTorque);
  q[kBacklash] = (1.0 - keep * keep) * prior(kBacklash, kBacklash);
  P.diagonal() += q;
  t.predicted_mean = s.mean;
  t.f_torque_torque = t.f_torque_scale = 0.0;
  t.f_backlash_torque = t.f_backlash_clearance = 0.0;
  t.f_backlash_backlash = keep;
  t.process_noise = q;
  t.seating_bound_weight = 1.0;
  t.predicted = true;
}

// h_j(x) = q_tip_j + b_j + s_j·K_j(L)·tau_j, K from the ComplianceEffect; its
// Jet gives the value and the row ∂h_j/∂(q_tip, tau, b, s, e, beta).
void ComplianceFilter::Impl::EncoderModel(double depth_m, Eigen::Vector2d* predicted,
                                          Vector* h) const {
  models::JointState<StateJet> state;
  state.insertion_depth_m = StateJet(depth_m);
  for (int j = 0; j < 2; ++j) {
    state.external_torque_nm[j] = StateJet(joint[j].mean[kTorque], kTorque);
  }
  const models::Vec2<StateJet> bend = compliance(compliance_coefficients.data(), state);
  for (int j = 0; j < 2; ++j) {
    const auto& x = joint[j].mean;
    const StateJet q = StateJet(x[kTip], kTip) + StateJet(x[kBacklash], kBacklash) +
                       StateJet(x[kScale], kScale) * bend[j];
    (*predicted)[j] = q.a;
    h[j] = q.v;
  }
}

// Joseph form, P+ = (I − k hᵀ) P (I − k hᵀ)ᵀ + k r kᵀ, for one scalar, after a
// χ² gate. After `reacquire_after` consecutive rejections on a channel the
// prior covariance is added to the block and the measurement is taken: the
// world has changed (a slip, a new contact) and the filter must follow it.
void ComplianceFilter::Impl::ScalarUpdate(int j, Channel channel, const Vector& h,
                                          double innovation, double variance, StepTally* tally,
                                          bool implausible, unsigned consider) {
  FilterJointState& s = joint[j];
  Matrix& P = s.covariance;
  Vector u = P * h;
  double S = h.dot(u) + variance;
  double nis = innovation * innovation / S;
  int& rejected = rejections[j][channel];
  if (implausible || !(nis <= gate)) {
    tally->window_nis += std::isfinite(nis) ? std::min(nis, 2.0 * gate) : 2.0 * gate;
    tally->window_dof += 1;
    tally->flags |= kFlagRejected;
    if (++rejected < options.reacquire_after || !std::isfinite(S)) return;
    // Re-acquire. Effort: the torque back to its prior spread. Encoder: the
    // backlash back to its prior, and the tip as uncertain as the part of the
    // innovation the clearance cannot explain (a slip, or a start from a bad
    // sample); a jump within ±δ is left to the backlash, which is what moves
    // at low load. Reference: the tip, by the innovation.
    // Each channel re-opens the states it measures most directly.
    const Matrix prior = PriorCovariance(options, delta[j], uncertainty[j]);
    if (channel == kEffortChannel) P(kTorque, kTorque) += prior(kTorque, kTorque);
    if (channel == kReferenceChannel) P(kTip, kTip) += innovation * innovation;
    if (channel == kEncoderChannel) {
      const double slip = std::max(0.0, std::abs(innovation) - delta[j]);
      P(kBacklash, kBacklash) += prior(kBacklash, kBacklash);
      P(kTip, kTip) += slip * slip;
    }
    u = P * h;
    S = h.dot(u) + variance;
    nis = innovation * innovation / S;
    tally->flags |= kFlagReacquired;
    restart_output[j] = true;
  } else {
    tally->window_nis += nis;
    tally->window_dof += 1;
  }
  rejected = 0;
  Vector k = u / S;
  // A free tip's encoder and effort say where the tip is and what loads it,
  // not what the instrument is: s, e and beta are "consider" states there
  // (Schmidt–Kalman: their gain is zero, their doubt still flows into P
  // through the Joseph form below). With a gain they drifted over a long
  // free log on tiny correlations with the tip (s 1 → 0.82 over 2 M samples
  // of the clamped sweep; validation.md). A reference still teaches them.
  if (consider & kConsiderScale) k[kScale] = 0.0;
  // e, likewise, while the tip is free; held, until the hold's load has
  // pressed the shaft against a wall (clearance_needs_a_wall says why).
  if (consider & kConsiderClearance) k[kClearance] = 0.0;
  // β is a consider state of a held tip's encoder and effort too, but for
  // samples with a reference. A held tip cannot tell β from the load: across
  // a clamped sweep the encoders fix s (the slope), e (wall to wall) and only
  // tip − s·K·β. The one handle on β is where the shaft leaves its wall,
  // which the dead zone's smooth S(tau/w) stands in for; the EKF read it
  // sharply and wrongly (in a clamped-beam Monte Carlo trial, β 0.013 N·m
  // against a true −0.019, and the held tip 270 encoder counts off with a σ
  // of 48; the clamped study's NEES 7.8, with this 1.9; docs/validation.md
  // Part 4, "The bias offset as a consider state"). A reference (the tip
  // known) breaks the tie, and then the encoder and effort teach β; so does
  // a load known to be 0 (unloaded_start_s).
  if (consider & kConsiderOffset) k[kOffset] = 0.0;
  // Joseph form for one scalar, P+ = (I − k hᵀ) P (I − k hᵀ)ᵀ + k r kᵀ, which
  // for any gain k (not only the optimal one) expands exactly to
  //   P+ = P − k uᵀ − u kᵀ + S k kᵀ = P + k vᵀ + v kᵀ,   v = S k / 2 − u.
  // Written this way it costs two outer products and is symmetric to the
  // last bit (each entry adds the same two products in either order).
  const Vector v = 0.5 * S * k - u;
  P += k * v.transpose() + v * k.transpose();
  s.mean += k * innovation;
  tally->nis += nis;
  tally->dof += 1;
}

void ComplianceFilter::Impl::Repair(int j, const FilterSample& sample, bool full_check,
                                    StepTally* tally) {
  FilterJointState& s = joint[j];
  // A clearance is never negative nor twice the nominal one.
  s.mean[kClearance] = std::clamp(s.mean[kClearance], -delta[j], delta[j]);
  const double clearance = delta[j] + s.mean[kClearance];
  s.mean[kBacklash] = std::clamp(s.mean[kBacklash], -clearance, clearance);
  s.mean[kScale] = std::clamp(s.mean[kScale], kMinScale, kMaxScale);
  // A calibration offset of spread σ_β is not many σ_β away: beyond the bound
  // the effort's change is the load's, which a held tip's β would otherwise
  // take (effort_offset_bound_sd).
  const double offset_bound = options.effort_offset_bound_sd * uncertainty[j].effort_offset_sd_nm;
  if (offset_bound > 0.0) {
    s.mean[kOffset] = std::clamp(s.mean[kOffset], -offset_bound, offset_bound);
  }
  if (!s.mean.allFinite() || !s.covariance.allFinite()) {
    const double q = std::isfinite(sample.encoder_rad[j]) ? sample.encoder_rad[j] : 0.0;
    s.mean << q, 0.0, 0.0, 1.0, 0.0, 0.0;
    s.covariance = PriorCovariance(options, delta[j], uncertainty[j]);
    tally->flags |= kFlagRepaired;
    restart_output[j] = true;
    return;
  }
  // The Joseph form keeps P positive semi-definite but for rounding: a
  // non-positive variance is looked for every step; the full Cholesky test
  // (a fifth of a step's time when both blocks ran it every step) runs on
  // one block every fourth step, so on each every eighth (kFullCheckPeriod).
  const bool diagonal_positive = (s.covariance.diagonal().array() > 0.0).all();
  if (!diagonal_positive || (full_check && !IsPositiveDefinite(s.covariance))) {
    const double jitter = 1e-12 * s.covariance.diagonal().cwiseAbs().maxCoeff() + 1e-20;
    s.covariance.diagonal() = s.covariance.diagonal().cwiseAbs().array() + jitter;
    tally->flags |= kFlagRepaired;
  }
}

// Sliding window of the last W samples' NIS: under the model their sum is
// χ² with the window's scalar count as degrees of freedom.
void ComplianceFilter::Impl::UpdateWindow(StepTally* tally) {
  const int w = options.mismatch_window;
  window_sum += tally->window_nis - window_nis[window_position];
  window_dof_sum += tally->window_dof - window_dof[window_position];
  window_nis[window_position] = tally->window_nis;
  window_dof[window_position] = tally->window_dof;
  if (++window_position == w) {
    window_position = 0;
    window_sum = 0.0;  // re-add exactly once per window: no drift from subtractions
    for (double v : window_nis) window_sum += v;
  }
  window_count = std::min(window_count + 1, w);
}

void ComplianceFilter::Impl::StepState(const FilterSample& sample) {
  StepTally tally;
  const double previous_depth = depth;
  if (std::isfinite(sample.insertion_depth_m)) {
    depth = sample.insertion_depth_m;
  } else {
    tally.flags |= kFlagMissing;
  }
  for (const auto& jp : parameters.joints) {
    if (depth < jp.depth_min_m || depth > jp.depth_max_m) tally.flags |= kFlagDepthOutOfRange;
  }

  if (!initialised) {
    Initialise(sample, depth);
    state_clock.Start(sample);
    restart_output[0] = restart_output[1] = true;
  } else {
    const bool released =
        sample.tip_fixed && last_tip_fixed && std::abs(depth - previous_depth) > kMaxHeldDepthChange;
    Eigen::Vector2d increment;
    const double dt =
        state_clock.Advance(sample, options.sample_period_s, &increment, implausible_jump);
    for (int j = 0; j < 2; ++j) {
      bend_rate_rad_s[j] = increment[j] / dt;
      if (released) {
        Release(j, dt, increment[j]);
        restart_output[j] = true;
      } else {
        Predict(j, dt, sample.tip_fixed, sample.tip_fixed && !last_tip_fixed, increment[j]);
      }
    }
  }
  last_tip_fixed = sample.tip_fixed;

  // s is taught by the load the filter is sure of: ∂h/∂s = K·tau scaled to
  // SureLoad (K·tau is linear in tau), so that a load within its noise is not
  // a regressor whose noise biases s toward 0; and only while that load holds
  // the shaft on its wall (ScaleLearningFraction). Taken at the prediction, as
  // the dense baselines, which update all channels at once, do.
  double sure_fraction[2];
  for (int j = 0; j < 2; ++j) {
    sure_fraction[j] = ScaleLearningFraction(options, joint[j].mean[kTorque],
                                             joint[j].covariance(kTorque, kTorque), width[j]);
  }
  // Efforts: tau_meas − tau0(q_enc, L) = tau + beta (tau0 is evaluated at the
  // measured angle, an input, so its row is the unit vectors of tau and beta).
  const bool unloaded = InUnloadedStart(options, sample.time_s - start_time_s);
  for (int j = 0; j < 2; ++j) {
    if (unloaded) {  // the load is known: 0, with no doubt, whatever the effort says
      joint[j].mean[kTorque] = 0.0;
      joint[j].covariance.row(kTorque).setZero();
      joint[j].covariance.col(kTorque).setZero();
    }
    const double effort = sample.effort_nm[j];
    if (!std::isfinite(effort)) {
      tally.flags |= kFlagMissing;
      continue;
    }
    if (std::abs(effort) >= options.effort_limit_nm) {
      tally.flags |= kFlagEffortSaturated;
      continue;
    }
    const double q = std::isfinite(sample.encoder_rad[j]) ? sample.encoder_rad[j]
                                                          : joint[j].mean[kTip];
    const double tau0 = models::BiasTorqueAt(parameters.joints[j], q, depth);
    // The inertial torque, with the tip held only. With a free tip the load
    // is ~0 and the effort serves to pin b; there the flicker of the estimated
    // acceleration (one count ≈ 0.07 rad/s², 0.006 N·m) walked b across the
    // clearance during the long free-tip rests of a divot log and moved the
    // tip by δ (docs/validation.md, Part 4).
    // With it, the shaft's damping, in proportion to how firmly the load the
    // filter is sure of holds the shaft on its wall (the prediction's hold;
    // the simulator's is all or nothing, by contact).
    // The fitted J·θ̈ is also what the effort's variance allows a share of
    // to be misread (HeldEffortVariance).
    const double inertial_torque = sample.tip_fixed ? motion[j].InertialTorque(options) : 0.0;
    const double inertial =
        sample.tip_fixed ? inertial_torque +
                               models::ShaftDampingTorque(options.shaft_damping_nm_s_per_rad,
                                                          bend_rate_rad_s[j], step_hold[j])
                         : 0.0;
    const double variance = sample.tip_fixed
                                ? HeldEffortVariance(options, inertial_torque)
                                : options.effort_noise_nm * options.effort_noise_nm;
    ScalarUpdate(j, kEffortChannel, Vector::Unit(kTorque) + Vector::Unit(kOffset),
                 effort - tau0 - inertial - joint[j].mean[kTorque] - joint[j].mean[kOffset],
                 variance, &tally, false, ConsiderFor(sample, j, unloaded));
  }
  // Encoders, linearised at the state the efforts just updated.
  Eigen::Vector2d predicted;
  Vector h[2];
  EncoderModel(depth, &predicted, h);
  for (int j = 0; j < 2; ++j) {
    if (!std::isfinite(sample.encoder_rad[j])) {
      tally.flags |= kFlagMissing;
      continue;
    }
    const double deflection = options.deflection_model_error * h[j][kScale];
    h[j][kScale] *= sure_fraction[j];
    ScalarUpdate(j, kEncoderChannel, h[j], sample.encoder_rad[j] - predicted[j],
                 options.encoder_noise_rad * options.encoder_noise_rad + deflection * deflection,
                 &tally, implausible_jump[j] && !sample.tip_fixed,
                 ConsiderFor(sample, j, unloaded));
  }
  for (int j = 0; j < 2; ++j) {
    const double ref = sample.reference_rad[j];
    if (!std::isfinite(ref)) continue;  // most logs have no reference: not "missing"
    ScalarUpdate(j, kReferenceChannel, Vector::Unit(kTip), ref - joint[j].mean[kTip],
                 options.reference_noise_rad * options.reference_noise_rad, &tally);
  }
  for (int j = 0; j < 2; ++j) Repair(j, sample, check_phase == kFullCheckPeriod / 2 * j, &tally);
  check_phase = (check_phase + 1) % kFullCheckPeriod;
  UpdateWindow(&tally);

  FilterEstimate& estimate = state_estimate;
  estimate = MakeEstimate(joint[0], joint[1], sample.encoder_rad, depth);
  estimate.nis = tally.nis;
  estimate.nis_dof = tally.dof;
  estimate.window_nis = window_sum;
  estimate.window_threshold = window_threshold[window_dof_sum];
  if (window_count == options.mismatch_window && window_dof_sum > 0 &&
      window_sum > estimate.window_threshold) {
    tally.flags |= kFlagModelMismatch;
  }
  estimate.flags = tally.flags;
  state_sample = sample;
  advanced = true;
}

ComplianceFilter::ComplianceFilter(const models::ModelParameters& parameters,
                                   const FilterOptions& options)
    : impl_(std::make_unique<Impl>(parameters, options)) {}
ComplianceFilter::~ComplianceFilter() = default;
ComplianceFilter::ComplianceFilter(const ComplianceFilter& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
ComplianceFilter& ComplianceFilter::operator=(const ComplianceFilter& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
ComplianceFilter::ComplianceFilter(ComplianceFilter&&) noexcept = default;
ComplianceFilter& ComplianceFilter::operator=(ComplianceFilter&&) noexcept = default;

FilterEstimate ComplianceFilter::Step(const FilterSample& sample) noexcept {
  return impl_->Step(sample);
}
void ComplianceFilter::Reset() noexcept { impl_->Reset(); }
bool ComplianceFilter::StepHeldSample() noexcept {
  impl_->advanced = false;
  return impl_->StepHeldSample();
}
int ComplianceFilter::alignment_steps() const { return impl_->alignment_steps; }
bool ComplianceFilter::advanced() const { return impl_->advanced; }
const FilterSample& ComplianceFilter::state_sample() const { return impl_->state_sample; }
const FilterEstimate& ComplianceFilter::state_estimate() const { return impl_->state_estimate; }
const FilterOptions& ComplianceFilter::options() const { return impl_->options; }
const FilterJointState& ComplianceFilter::joint_state(int joint) const {
  return impl_->joint[joint];
}
const FilterTransition& ComplianceFilter::transition(int joint) const {
  return impl_->transition[joint];
}

}  // namespace pliant::estimation
