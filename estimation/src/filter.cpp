// The online filter (filter.h). Two 6-state joint blocks, sparse prediction,
// sequential scalar Joseph updates, Jacobians from ceres::Jet. Nothing in
// Step() allocates or throws: every buffer is sized in the constructor.
#include "pliant/estimation/filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <ceres/jet.h>

#include "chi_squared.h"
#include "filter_impl.h"
#include "pliant/models/effects/backlash_hysteresis.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/models/effects/joint_friction.h"
#include "pliant/models/effects/joint_inertia.h"
#include "pliant/models/effects/shaft_damping.h"

namespace pliant::estimation {

using namespace filter_internal;

namespace {

// Fixed-size Cholesky: no allocation, a bounded number of operations.
bool IsPositiveDefinite(const Matrix& p) {
  return Eigen::LLT<Matrix>(p).info() == Eigen::Success;
}

}  // namespace

// Joint j's prior covariance: diag(σ_tip0², σ_τ0², (δ² + σ_δ²)/3, σ_s², σ_δ², σ_β²);
// b uniform on ±(δ + e). The floors keep P positive definite when σ = 0.
Matrix filter_internal::PriorCovariance(const FilterOptions& o, double delta, const InstrumentUncertainty& u) {
  const double sd_delta2 = u.clearance_sd_rad * u.clearance_sd_rad;
  Vector d;
  d << o.initial_tip_sd_rad * o.initial_tip_sd_rad,
      o.initial_torque_sd_nm * o.initial_torque_sd_nm, (delta * delta + sd_delta2) / 3.0 + 1e-14,
      o.compliance_scale_sd * o.compliance_scale_sd, sd_delta2 + 1e-14,
      u.effort_offset_sd_nm * u.effort_offset_sd_nm + 1e-14;
  return d.asDiagonal();
}

ComplianceFilter::Impl::Impl(const models::ModelParameters& p, const FilterOptions& o)
    : parameters(p), options(o), extra_effects(p.effects), compliance(p.joints[0], p.joints[1]) {
  const std::string why = models::ValidateParameters(p);
  if (!why.empty()) throw std::invalid_argument(why);
  std::string error;
  if (!o.IsValid(&error) || !(error = OptionsAgainstParameters(p, o)).empty()) {
    throw std::invalid_argument(error);
  }
  options.deflection_model_error = o.DeflectionModelError();  // NaN resolved once
  // A quasi-static log has no dynamics to read: no inertial torque, no damping.
  if (o.quasi_static) options.motor_inertia_kg_m2 = options.shaft_damping_nm_s_per_rad = 0.0;
  // The arm's dynamics the file states are the learned torque's prior
  // (ArmPriorSd): where it is learned their σ is its doubt, not the effort's
  // noise as well; on held rows (no learned torque) they stay noise.
  extra_effects.SetLearned({std::string(models::JointFrictionEffect::kInfo.name),
                            std::string(models::JointInertiaEffect::kInfo.name)});
  for (int j = 0; j < 2; ++j) {
    const auto& joint_parameters = p.joints[j];
    for (int i = 0; i < 4; ++i) {
      compliance_coefficients[4 * j + i] = StateJet(joint_parameters.compliance.cubic.coefficients[i]);
    }
    delta[j] = joint_parameters.backlash_rad;
    const std::string prefix = "joint" + std::to_string(j + 1) + ".";
    auto& u = uncertainty[j];
    u.clearance_sd_rad = ResolvedStandardDeviation(o.backlash_sd_rad[j], p, prefix + "backlash_rad",
                                                   FilterOptions::kDefaultBacklashSdRad);
    u.width_sd_nm = ResolvedStandardDeviation(o.deadzone_width_sd_nm[j], p,
                                              prefix + "deadzone_width_nm", 0.0);
    u.effort_offset_sd_nm = ResolvedStandardDeviation(
        o.effort_offset_sd_nm[j], p, prefix + "bias_torque.coefficients[0]",
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
  PrepareDeflectionEffects();
  if (o.align_inertial_torque && options.motor_inertia_kg_m2 > 0.0) {
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
    walls[j] = ClearanceWalls{};
    restart_output[j] = true;
    // The chain's stationary share: contact is the exception.
    contact_probability[j] = contact_prior[j] =
        options.contact_start_rate_hz /
        (options.contact_start_rate_hz + options.contact_end_rate_hz);
    contact_onset[j] = 0.0;
    ClearBranches(j);
    branch_last[j] = branch_continuing[j] = branch_ended[j] = 0.0;
    last_gain.setZero();
    last_pose[j] = filter_internal::LastPose{};
    pair_window[j] = filter_internal::PairWindow{};
    free_pair_change[j] = filter_internal::FreeArmPairChange{};
    free_motion[j] = filter_internal::FreeArmMotion{};
    unmodelled[j].variance = options.moving_effort_sd_nm * options.moving_effort_sd_nm;
    internal_torque[j].Start(options, ArmPriorSd(options, parameters.effects, j));
    pending[j] = filter_internal::PendingEffort{};  // (its pose and stillness feed the free level)
  }
  std::fill(window_nis.begin(), window_nis.end(), 0.0);
  std::fill(window_dof.begin(), window_dof.end(), 0);
  contact_rates.Start(options);
  chain_step_s = 0.0;
  window_position = window_count = window_dof_sum = check_phase = 0;
  motion_started = advanced = false;
  held_first = held_count = 0;
  newest_step.setZero();
  window_sum = 0.0;
  effect_rows = EffectInputs(options.quasi_static, options.time_gap_s);
  extra_internal_torque_nm.setZero();
  extra_internal_variance_nm2.setZero();
  extra_learned_variance_nm2.setZero();
  held_given_contact = 0.5;
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
    if (sample.tip_fixed) walls[j].Seat();  // a log that starts held: a hold the hint began
  }
  // The file's deflection effects at those loads (their inputs: this row's).
  const ExtraDeflection extra = Deflection();
  for (int j = 0; j < 2; ++j) {
    joint[j].mean[kTip] -= extra.value[j];
    transition[j].predicted_mean = joint[j].mean;
  }
  start_time_s = sample.time_s;
  initialised = true;
}

// h_j(x) = q_tip_j + b_j + s_j·K_j(L)·tau_j + Σ Δq_j(tau_1, tau_2), K from the
// ComplianceEffect and Δq the parameters file's deflection effects; Jets give
// the value and the row ∂h_j/∂(q_tip, tau, b, s, e, beta). The blocks keep no
// cross-covariance, so a coupling effect's ∂Δq_j/∂tau_i (i ≠ j) is not a row
// entry: the other joint's tau enters at its estimate, a consider input whose
// variance (∂Δq_j/∂tau_i)²·P_i(tau, tau) is added to the encoder's noise
// (coupling_variance; 0 without a coupling effect), as is what the effects'
// parameters' σ put there.
void ComplianceFilter::Impl::EncoderModel(double depth_m, Eigen::Vector2d* predicted, Vector* h,
                                          Eigen::Vector2d* coupling_variance) const {
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
  coupling_variance->setZero();
  if (deflection_effects.empty()) return;
  const ExtraDeflection extra = Deflection();
  // The effects' parameters' σ at the state's loads (ConsideredVariance).
  models::JointState<double> inputs = effect_inputs;
  for (int j = 0; j < 2; ++j) inputs.external_torque_nm[j] = joint[j].mean[kTorque];
  *coupling_variance = extra_effects.ConsideredVariance(inputs, models::Channel::kDeflection);
  for (int j = 0; j < 2; ++j) {
    const int other = 1 - j;
    (*predicted)[j] += extra.value[j];
    h[j][kTorque] += extra.slope(j, j);
    const double cross = extra.slope(j, other);
    (*coupling_variance)[j] += cross * cross * joint[other].covariance(kTorque, kTorque);
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
  // One division per update: the gain and the NIS both scale by 1/S.
  double inverse_s = 1.0 / S;
  double nis = innovation * innovation * inverse_s;
  int& rejected = rejections[j][channel];
  if (implausible || !(nis <= gate)) {
    tally->window_nis += std::isfinite(nis) ? std::min(nis, 2.0 * gate) : 2.0 * gate;
    tally->window_dof += 1;
    tally->flags |= kFlagRejected;
    if (++rejected < options.reacquire_after || !std::isfinite(S)) {
      last_gain.setZero();
      return;
    }
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
    inverse_s = 1.0 / S;
    nis = innovation * innovation * inverse_s;
    tally->flags |= kFlagReacquired;
    restart_output[j] = true;
  } else {
    tally->window_nis += nis;
    tally->window_dof += 1;
  }
  rejected = 0;
  Vector k = u * inverse_s;
  // A free tip's encoder and effort say where the tip is and what loads it,
  // not what the instrument is: s, e and beta are "consider" states there
  // (Schmidt–Kalman: their gain is zero, their doubt still flows into P
  // through the Joseph form below). With a gain they drifted over a long
  // free log on tiny correlations with the tip (s 1 → 0.82 over 2 M samples
  // of the clamped sweep; docs/validation.md section 5). A reference still teaches them.
  if (consider & kConsiderScale) k[kScale] = 0.0;
  // e, likewise, while the tip is free; held, until the hold's load has
  // pressed the shaft against a wall (clearance_needs_a_wall says why), and
  // where the load may not teach it (ClearanceLearnable).
  if (consider & kConsiderClearance) k[kClearance] = 0.0;
  // β is a consider state of a held tip's encoder and effort too, but for
  // samples with a reference. A held tip cannot tell β from the load: across
  // a clamped sweep the encoders fix s (the slope), e (wall to wall) and only
  // tip − s·K·β. The one handle on β is where the shaft leaves its wall,
  // which the dead zone's smooth S(tau/w) stands in for; the EKF read it
  // sharply and wrongly (in a clamped-beam Monte Carlo trial, β 0.013 N·m
  // against a true −0.019, and the held tip 270 encoder counts off with a σ
  // of 48; the clamped study's NEES 7.8, with this 1.9; docs/decisions/
  // 0007-filter-effort-offset-tare-and-clearance-from-a-wall.md). A reference (the tip
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
  last_gain = k;
  tally->nis += nis;
  tally->dof += 1;
}

void ComplianceFilter::Impl::Repair(int j, const FilterSample& sample, bool full_check,
                                    StepTally* tally) {
  FilterJointState& s = joint[j];
  // (A projection of the whole mean onto the wall instead, along P·d, was
  // measured and not taken: docs/decisions/wall-constraint.md.)
  ConfineToClearance(delta[j], &s.mean[kClearance], &s.mean[kBacklash]);
  s.mean[kScale] = std::clamp(s.mean[kScale], kMinScale, kMaxScale);
  // A calibration offset of spread σ_β is not many σ_β away: beyond the bound
  // the effort's change is the load's, which a held tip's β would otherwise
  // take (effort_offset_bound_sd).
  const double offset_bound = options.effort_offset_bound_sd * uncertainty[j].effort_offset_sd_nm;
  if (offset_bound > 0.0) s.mean[kOffset] = std::clamp(s.mean[kOffset], -offset_bound, offset_bound);
  // One sum is finite exactly when every entry is (a NaN or an infinity
  // carries through; a sum beyond the double range needs the repair too),
  // and it vectorises where allFinite() tests 42 entries one by one.
  if (!std::isfinite(s.mean.sum() + s.covariance.sum())) {
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
  // one block every sixteenth step, so on each every 32nd (kFullCheckPeriod).
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
Eigen::Vector2d ComplianceFilter::instrument_prior_sd(int joint) const {
  return {impl_->uncertainty[joint].clearance_sd_rad, impl_->options.compliance_scale_sd};
}
const FilterJointState& ComplianceFilter::joint_state(int joint) const {
  return impl_->joint[joint];
}
const FilterTransition& ComplianceFilter::transition(int joint) const {
  return impl_->transition[joint];
}

}  // namespace pliant::estimation
