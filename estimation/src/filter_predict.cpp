// The online filter's prediction (filter.h): the process model of one joint
// block, a release (held again elsewhere) and a re-initialisation (a pose
// jump, a time gap, a stretch of missing samples).
#include <algorithm>
#include <cmath>

#include "filter_impl.h"
#include "pliant/models/effects/backlash_hysteresis.h"

namespace pliant::estimation {

using namespace filter_internal;

// F = I but for b's row (∂b+/∂tau, ∂b+/∂b, ∂b+/∂e from the hysteresis step's Jet), so
// F·P·Fᵀ touches only b's row and column.
// extra_compliance: the file's deflection effects' ∂Δq_j/∂tau_j (rad/N·m), on
// top of s·K(L) where a held load follows the motor.
// held_share: without the tip_fixed hint, the chance that a contact holds the
// tip; the prediction is the mixture of a held tip's (the load follows the
// bend) and a free one's (the tip follows the encoder), moment-matched.
void ComplianceFilter::Impl::Predict(int j, double dt, bool tip_fixed, bool seated,
                                     double encoder_increment, double extra_compliance,
                                     double held_share) {
  FilterJointState& s = joint[j];
  FilterTransition& t = transition[j];
  const auto& o = options;
  t.seating_bound_weight = seated ? o.seating_bound_weight : 1.0;
  SeatingBound(&s.covariance, t.seating_bound_weight);
  // The fraction of its wall an unloaded shaft forgets as the arm moves by
  // the encoder increment: nothing holds an unloaded shaft on a wall, but it
  // only leaves it when the arm moves (a joint at rest keeps its offset).
  // Held tip: the encoders see b, and an arm moving against a held tip loads
  // the shaft toward a wall rather than freeing it, so b keeps its memory;
  // without the hint, so does the share of the increment a held contact bends.
  const double held = tip_fixed ? 1.0 : std::clamp(held_share, 0.0, 1.0);
  const double relax = tip_fixed ? 0.0 : BacklashRelax(o, dt, (1.0 - held) * encoder_increment);
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
  // Only a held tip's walls are observed (a free tip's e is a consider state).
  const bool first_press =
      tip_fixed && walls[j].Observe(hold, ClearanceLearnable(o, sure_load, width[j],
                                                             uncertainty[j].width_sd_nm, delta[j],
                                                             s.covariance(kClearance, kClearance)));
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

  s.mean[kTip] += (1.0 - held) * encoder_increment;
  s.mean[kBacklash] = next.a;

  P.col(kBacklash) = row;
  P.row(kBacklash) = row.transpose();
  P(kBacklash, kBacklash) = pbb;

  // A held tip's motor bends the shaft: tau follows the encoder (F's tau row
  // gains ∂tau+/∂s). b's step above read the load before this one, so F is
  // this row's map after b's, and F·P·Fᵀ takes it after b's.
  double fts = 0.0;
  // s·K + c = (s + c/K)·K: the scale's Jet carries the effects' slope c. A
  // slope that would leave no positive compliance is not taken.
  const double k_depth = ComplianceAtDepth(j);
  const double bend = s.mean[kScale] * k_depth;
  const double extra = bend + extra_compliance > 0.1 * bend ? extra_compliance : 0.0;
  double load_step = 0.0;
  if (held > 0.0 && o.load_follows_motor) {
    const StateJet added =
        HeldLoadIncrement(hold, encoder_increment,
                          StateJet(s.mean[kScale], kScale) + extra / k_depth, k_depth);
    load_step = added.a;
    s.mean[kTorque] += held * added.a;
    // Without the hint the held share is itself a guess: through ∂tau+/∂s
    // the effort's innovations would teach s a bend nobody saw held.
    fts = tip_fixed ? added.v[kScale] : 0.0;
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
                      bend + extra, motion[j].InertialTorque(o), hold)
                : o.external_torque_rate_nm * o.external_torque_rate_nm * dt + contact_onset[j];
  q[kBacklash] = bound.process_variance;
  q[kScale] = o.compliance_scale_rate * o.compliance_scale_rate * dt;
  q[kClearance] = 0.0;
  q[kOffset] = o.effort_offset_rate_nm * o.effort_offset_rate_nm * dt;
  t.f_offset_offset = 1.0;
  if (std::isfinite(o.effort_offset_correlation_s[j])) {  // Gauss–Markov: σ_β stationary
    const double rho = std::exp(-dt / o.effort_offset_correlation_s[j]);
    const double sd = uncertainty[j].effort_offset_sd_nm;
    s.mean[kOffset] *= rho;
    P.row(kOffset) *= rho;
    P.col(kOffset) *= rho;
    q[kOffset] += sd * sd * (1.0 - rho * rho);
    t.f_offset_offset = rho;
  }
  // The two predictions' means differ by Δq in the tip and the bend's load in
  // tau: the mixture's spread (its diagonal: the process noise stays diagonal).
  const double spread = held * (1.0 - held);
  q[kTip] += spread * encoder_increment * encoder_increment;
  q[kTorque] += spread * load_step * load_step;
  P.diagonal() += q;
  // The held tip forgets where the shaft started (ClearanceWalls says why).
  if (first_press) P(kTip, kTip) += ClearanceWalls::ForgottenStartVariance(prior_variance);

  t.predicted_mean = s.mean;
  t.f_torque_torque = 1.0;
  t.f_torque_scale = fts;
  t.f_backlash_torque = fbt;
  t.f_backlash_backlash = fbb;
  t.f_backlash_clearance = fbe;
  t.process_noise = q;
  t.predicted = true;
  PredictBranchGap(j, encoder_increment, load_step);
}

// Released and held again elsewhere, after a transit the log does not show
// (hold means): the load came off and the arm moved with the tip free, so the
// shaft forgets its wall as a free tip's does (BacklashRelax: by how far the
// joint moved; a joint that did not move keeps it). Whether the unseen transit
// re-seated the shaft the log cannot say: b's doubt gains the prior's whole
// spread, δ²/3, whatever the mean keeps (an instrument whose clearance has no
// memory sits centred when unloaded). The tip and the load start
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
  q[kBacklash] = prior(kBacklash, kBacklash);
  P.diagonal() += q;
  ClearBranches(j);
  t.predicted_mean = s.mean;
  t.f_torque_torque = t.f_torque_scale = 0.0;
  t.f_backlash_torque = t.f_backlash_clearance = 0.0;
  t.f_backlash_backlash = keep;
  t.f_offset_offset = 1.0;
  t.process_noise = q;
  t.seating_bound_weight = 1.0;
  t.predicted = true;
}

// What the process model cannot bridge (a pose change between two rows, a
// time gap, the first sample after missing ones, every quasi-static row):
// a free tip starts again at the encoder with the prior's doubt, uncorrelated
// (q_tip = q_enc − b − s·K·tau − Σ Δq at the predicted b, tau, s). A tip held
// on this row and the last one stays, as the tip_fixed hint says (held_tip_stays);
// a hold that begins here (after free rows: a new clamp, a pose away) starts
// at the encoder as a free tip does. The shaft keeps its wall (the hysteresis
// moves it with the load). The load starts again from its prior spread. The
// instrument's states (s, e, β) carry over. The prediction has run first:
// this widens its result.
void ComplianceFilter::Impl::Reinitialise(int j, const FilterSample& sample, bool held_tip_stays) {
  FilterJointState& s = joint[j];
  Matrix& P = s.covariance;
  const Matrix prior = PriorCovariance(options, delta[j], uncertainty[j]);
  if (!held_tip_stays && std::isfinite(sample.encoder_rad[j])) {
    s.mean[kTip] = sample.encoder_rad[j] - s.mean[kBacklash] -
                   s.mean[kScale] * ComplianceAtDepth(j) * s.mean[kTorque] -
                   Deflection().value[j];
    P.row(kTip).setZero();
    P.col(kTip).setZero();
    P(kTip, kTip) = prior(kTip, kTip);
  }
  P(kTorque, kTorque) += prior(kTorque, kTorque);
  transition[j].process_noise[kTorque] += prior(kTorque, kTorque);
  for (int& r : rejections[j]) r = 0;
  restart_output[j] = true;
  ClearBranches(j);
  free_motion[j].started = false;  // z jumps with the pose
  // A continuous log's pair window does not span a jump or a gap; a
  // quasi-static log's every row re-initialises and pairs with the last pose.
  pair_window[j].Restart();
}

}  // namespace pliant::estimation
