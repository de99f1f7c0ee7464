// One step of the filter's state (filter.h): prediction (or a release, or a
// re-initialisation), the efforts with the contact chain, the encoders, the
// references, then the repairs and the mismatch window.
#include <algorithm>
#include <cmath>
#include <limits>

#include "filter_impl.h"
#include "pliant/models/effects/shaft_damping.h"

namespace pliant::estimation {

using namespace filter_internal;

void ComplianceFilter::Impl::StepState(const FilterSample& sample) {
  StepTally tally;
  const double previous_depth = depth;
  if (std::isfinite(sample.insertion_depth_m)) {
    depth = sample.insertion_depth_m;
  } else {
    tally.flags |= kFlagMissing;
  }
  for (int j = 0; j < 2; ++j) {  // (a joint the log does not record has no range to leave)
    const auto& jp = parameters.joints[j];
    if (options.joint_recorded[j] && (depth < jp.depth_min_m || depth > jp.depth_max_m))
      tally.flags |= kFlagDepthOutOfRange;
  }
  ExtraInternalTorque(sample);  // (and the row's inputs the effects see)
  if (!initialised) {
    Initialise(sample, depth);
    state_clock.Start(sample);
    restart_output[0] = restart_output[1] = true;
    step_dt = options.sample_period_s;
  } else {
    AdvanceState(sample, previous_depth, &tally);
  }
  last_tip_fixed = sample.tip_fixed;
  UpdateMeasurements(sample, &tally);
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
  for (int j = 0; j < 2; ++j) estimate.contact_probability[j] = contact_probability[j];
  state_sample = sample;
  advanced = true;
}

// The internal torque of the parameters' further effects at this row's
// inputs, as the identification fitted them (EffectInputs).
void ComplianceFilter::Impl::ExtraInternalTorque(const FilterSample& sample) {
  if (parameters.effects.empty()) return;  // (the common case: nothing to evaluate)
  effect_inputs = effect_rows.Update(
      sample.time_s, Eigen::Vector3d(sample.encoder_rad[0], sample.encoder_rad[1], depth),
      sample.effort_nm, sample.velocity_rad_s);
  // The acceleration the learned J·θ̈ reads (MotorMotion), as the state is aligned to it.
  if (!options.quasi_static)
    effect_inputs.acceleration_rad_s2 << motion[0].acceleration_rad_s2, motion[1].acceleration_rad_s2;
  // The file's K(L), not s·K(L): the effects were fitted as shares of the law.
  effect_inputs.compliance_rad_per_nm << ComplianceAtDepth(0), ComplianceAtDepth(1);
  extra_internal_torque_nm = extra_effects.InternalTorque(effect_inputs);
  extra_internal_variance_nm2 = extra_effects.ConsideredVariance(
      effect_inputs, models::Channel::kInternalTorque, &extra_learned_variance_nm2);
  for (int j = 0; j < 2; ++j) {
    if (!std::isfinite(extra_internal_torque_nm[j])) extra_internal_torque_nm[j] = 0.0;
  }
}

// The prediction from the last sample to this one. What the process model
// cannot bridge is re-initialised (Reinitialise): an encoder step faster than
// any joint moves (a pose change between rows, or the first sample after
// missing ones), a time gap, and every row of a quasi-static log (but for the
// branch of a contact that goes on without the hint: PredictPoseBranches).
void ComplianceFilter::Impl::AdvanceState(const FilterSample& sample, double previous_depth,
                                          StepTally* tally) {
  const bool released =
      sample.tip_fixed && last_tip_fixed && std::abs(depth - previous_depth) > kMaxHeldDepthChange;
  const double gap_s = sample.time_s - state_clock.last_time;
  // A hold the hint ends: what the pair windows knew of it is no free arm's.
  if (last_tip_fixed && !sample.tip_fixed) {
    for (auto& window : pair_window) window = filter_internal::PairWindow{};
  }
  Eigen::Vector2d increment;
  // A quasi-static log's t is a pose index: the encoder's step is judged per row, not per second.
  FilterSample timed = sample;
  if (options.quasi_static) timed.time_s = state_clock.last_time + 1.0;
  double dt = state_clock.Advance(timed, options.sample_period_s, &increment, implausible_jump);
  const bool gap = options.quasi_static || gap_s > options.time_gap_s;
  // A quasi-static log's t is a pose index: the process noise is one nominal period's.
  if (gap) dt = options.sample_period_s;
  step_dt = dt;
  // A held load follows the motor through the incremental compliance, the
  // deflection effects' own slope ∂Δq_j/∂tau_j included (a coupling's cross
  // slope is left to the encoder updates).
  const ExtraDeflection extra = Deflection();
  for (int j = 0; j < 2; ++j) {
    bend_rate_rad_s[j] = options.quasi_static ? 0.0 : increment[j] / dt;
    if (!options.joint_recorded[j]) continue;  // an unrecorded joint keeps its prior
    if (released) {
      Release(j, dt, increment[j]);
      restart_output[j] = true;
      continue;
    }
    const bool jump = implausible_jump[j] && std::isfinite(sample.encoder_rad[j]);
    contact_onset[j] = ContactOnsetVariance(sample, j, dt);
    const double held_pose = HeldPoseShare(sample, j, previous_depth, jump);
    if (held_pose > 0.0) {
      PredictPoseBranches(j, sample, dt, increment[j], extra.slope(j, j), held_pose);
      continue;
    }
    Predict(j, dt, sample.tip_fixed, sample.tip_fixed && !last_tip_fixed, increment[j],
            extra.slope(j, j), HeldShare(sample, j));
    if (jump || gap) {
      // A held tip stays only through a hold: one that begins here may be a
      // pose away from the free tip (a new clamp). Within a hold an encoder
      // jump is left to the gate (a glitch) and its re-acquisition.
      const bool held_tip_stays = sample.tip_fixed && last_tip_fixed;
      Reinitialise(j, sample, held_tip_stays);
      // The quasi-static log's every row re-initialises: a flag there says nothing.
      if (jump || !options.quasi_static) tally->flags |= kFlagReinitialised;
    }
  }
}

// The slab's onset (the contact chain's mixing, filter_contact.cpp): the
// share of this step's contact probability that is a new contact brings a
// load of spread σ_c. Only without the tip_fixed hint.
double ComplianceFilter::Impl::ContactOnsetVariance(const FilterSample& sample, int j, double dt) {
  if (!options.infer_contact || sample.tip_fixed) return 0.0;
  // The chain's clock runs with the arm: a still arm neither starts nor ends
  // a contact, but at a tenth of the rate (the tissue may still move).
  double speed = 0.0;
  for (int k = 0; k < 2; ++k) speed = std::max(speed, std::abs(motion[k].velocity_rad_s));
  const double moving = std::min(1.0, speed / options.unmodelled_effort_speed_rad_s);
  const double chain_dt = options.quasi_static ? dt : dt * (0.1 + 0.9 * moving);
  chain_step_s = chain_dt;
  const ContactPrior prior = MixContact(options, contact_rates, contact_probability[j], chain_dt);
  branch_last[j] = contact_probability[j];
  branch_continuing[j] = prior.continuing;
  branch_ended[j] = prior.ended;
  contact_prior[j] = prior.probability;
  const double sd = options.contact_load_sd_nm;
  return (1.0 - prior.continuing) * sd * sd;
}

void ComplianceFilter::Impl::UpdateMeasurements(const FilterSample& sample, StepTally* tally) {
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
  const bool unloaded = InUnloadedStart(options, sample.time_s - start_time_s);
  if (!options.quasi_static && InfersContact(sample)) {
    arm_friction = ArmFriction(options.coulomb_speed_rad_s,
                               {motion[0].velocity_rad_s, motion[1].velocity_rad_s});
  }
  for (int j = 0; j < 2; ++j) {
    if (options.joint_recorded[j]) UpdateEffort(sample, j, unloaded, tally);
  }
  ShareContact();
  for (int j = 0; j < 2; ++j) FinishEffort(sample, j, unloaded, tally);
  // Encoders, linearised at the state the efforts just updated.
  Eigen::Vector2d predicted, coupling_variance;
  Vector h[2];
  EncoderModel(depth, &predicted, h, &coupling_variance);
  for (int j = 0; j < 2; ++j) {
    if (!options.joint_recorded[j]) continue;
    if (!std::isfinite(sample.encoder_rad[j])) {
      tally->flags |= kFlagMissing;
      continue;
    }
    const double deflection = options.deflection_model_error * h[j][kScale];
    h[j][kScale] *= sure_fraction[j];
    ScalarUpdate(j, kEncoderChannel, h[j], sample.encoder_rad[j] - predicted[j],
                 options.encoder_noise_rad * options.encoder_noise_rad + deflection * deflection +
                     coupling_variance[j],
                 tally, false, ConsiderFor(sample, j, unloaded));
    UpdateBranches(j, h[j]);  // both branches see the encoder through the shared gain
  }
  for (int j = 0; j < 2; ++j) {
    const double ref = sample.reference_rad[j];
    if (!std::isfinite(ref)) continue;  // most logs have no reference: not "missing"
    ScalarUpdate(j, kReferenceChannel, Vector::Unit(kTip), ref - joint[j].mean[kTip],
                 options.reference_noise_rad * options.reference_noise_rad, tally);
    UpdateBranches(j, Vector::Unit(kTip));
  }
}

// Efforts: tau_meas − tau0(q_enc, L) = tau + beta (tau0 is evaluated at the
// measured angle, an input, so its row is the unit vectors of tau and beta).
void ComplianceFilter::Impl::UpdateEffort(const FilterSample& sample, int j, bool unloaded,
                                          StepTally* tally) {
  const bool mixture = InfersContact(sample);
  // Told: held, or, in the unloaded start, that nothing touches the
  // instrument (the chain goes on from there free, not in contact).
  if (!mixture) contact_probability[j] = unloaded ? 0.0 : 1.0;
  if (unloaded) {  // the load is known: 0, with no doubt, whatever the effort says
    joint[j].mean[kTorque] = 0.0;
    joint[j].covariance.row(kTorque).setZero();
    joint[j].covariance.col(kTorque).setZero();
  }
  const double effort = sample.effort_nm[j];
  const bool usable = std::isfinite(effort) && std::abs(effort) < options.effort_limit_nm;
  if (!std::isfinite(effort)) tally->flags |= kFlagMissing;
  if (std::isfinite(effort) && !usable) tally->flags |= kFlagEffortSaturated;
  if (!usable) {
    last_pose[j].valid = false;
    pair_window[j].Restart();
    if (mixture) {  // the chain's prediction alone
      contact_probability[j] = contact_prior[j];
      CollapseContact(&joint[j], contact_probability[j]);
      ClearBranches(j);  // (the spread stays in P: the doubt is kept)
    }
    return;
  }
  const double q =
      std::isfinite(sample.encoder_rad[j]) ? sample.encoder_rad[j] : joint[j].mean[kTip];
  const double tau0 = models::BiasTorqueAt(parameters.joints[j], q, depth);
  // The inertial torque, with the tip held only. With a free tip the load
  // is ~0 and the effort serves to pin b; there the flicker of the estimated
  // acceleration (one count ≈ 0.07 rad/s², 0.006 N·m) walked b across the
  // clearance during the long free-tip rests of a divot log and moved the
  // tip by δ. With it, the shaft's damping, in proportion to how firmly the
  // load the filter is sure of holds the shaft on its wall. The fitted J·θ̈
  // is also what the effort's variance allows a share of to be misread
  // (HeldEffortVariance).
  const double inertial_torque = sample.tip_fixed ? motion[j].InertialTorque(options) : 0.0;
  const double inertial =
      sample.tip_fixed ? inertial_torque +
                             models::ShaftDampingTorque(options.shaft_damping_nm_s_per_rad,
                                                        bend_rate_rad_s[j], step_hold[j])
                       : 0.0;
  const double noise = options.effort_noise_nm * options.effort_noise_nm;
  // Unmodelled internal torque counts as effort noise (FilterOptions::moving_effort_sd_nm).
  // Moving as a free arm moves (FreeArmMotion): a pushed tip's encoder moves
  // by the load's bending, which is no free motion and no internal torque.
  const double moving =
      options.quasi_static
          ? 0.0
          : std::min(1.0, std::abs(FreeSpeed(j, sample, effort - tau0)) /
                              options.unmodelled_effort_speed_rad_s);
  const double rest = noise + options.unmodelled_effort_sd_nm * options.unmodelled_effort_sd_nm;
  // The moving arm's own torque, as far as the log has taught it, is taken
  // out; what it has not taught is effort noise.
  InternalTorque& arm = internal_torque[j];
  // A quasi-static log has no dynamics, and its table error is σ_rest's.
  // (Only the mixture reads or teaches the arm's torque: a held row skips it.)
  if (options.quasi_static) {
    arm.regressor.setZero();
  } else if (mixture) {
    arm.SetMotion(motion[j].acceleration_rad_s2, arm_friction.row(j));
  }
  const FilterJointState& s = joint[j];
  // The free arm's pose (FreeSpeed's z, this row's) and how still it stands
  // there: where the free level is and whether this row may teach it.
  double pose_rad = 0.0, still = 0.0;
  if (mixture && arm.level.on) {  // (the other joint's pose and stillness: its last row's)
    pose_rad = free_motion[j].z_rad;
    const double speed = std::tanh(free_motion[j].velocity_rad_s / options.coulomb_speed_rad_s);
    still = 1.0 - speed * speed;
    pending[j].pose_rad = pose_rad, pending[j].still = still;
    arm.level.Predict(LevelPose(sample), step_dt, ArmStill(), arm.LevelEquilibrium());
  }
  const double arm_torque = mixture ? arm.Torque() : 0.0;
  // With the level on, σ_rest is the level's equilibrium (InternalTorque::Variance).
  const double settled = arm.level.on ? noise : rest;
  const double variance =
      extra_internal_variance_nm2[j] -
      (mixture && !sample.tip_fixed ? extra_learned_variance_nm2[j] : 0.0) +
      (sample.tip_fixed ? HeldEffortVariance(options, inertial_torque)
       : mixture        ? settled + moving * unmodelled[j].variance + arm.Variance()
                        : noise);
  const double residual =
      effort - tau0 - inertial - arm_torque - extra_internal_torque_nm[j] - s.mean[kOffset];
  double log_likelihood_ratio = 0.0, held_evidence = 0.0, level_weight = 0.0, free_variance = 0.0;
  filter_internal::PoseTransitions transitions;
  if (mixture) {
    // The evidence for contact is a residual beyond what the unmodelled
    // internal torque explains, whatever the load did before: a contact's load
    // is drawn from the slab N(0, σ_c²); the chain alone carries persistence.
    // (Scored against the slab's tracked load, a smooth internal torque looked
    // like a contact that is followed well: bag rows with p ≈ 0.9 at
    // residuals below σ_u.)
    free_variance = s.covariance(kOffset, kOffset) + variance;
    const double sd_c = options.contact_load_sd_nm;
    // A moving arm's unmodelled torque is heavy-tailed (a spike of inertia or
    // stiction is not a contact); a settled arm's is the table's error and noise.
    const double dof = moving > 0.5 ? options.moving_effort_dof
                                    : std::numeric_limits<double>::infinity();
    // The log-likelihood ratio of contact; the posterior is shared by both
    // joints (ShareContact): a contact is the tip's, not one joint's. (A
    // continuous log scores both joints' levels at once there, LevelEvidence.)
    transitions = PoseChangeEvidence(sample, j, residual, free_variance);
    held_evidence =
        options.quasi_static ? (transitions.valid ? transitions.held - transitions.free : 0.0)
                             : filter_internal::HeldWindowEvidence(transitions);
    // A load's level, like the table's error, holds over many rows: the rows
    // of a pair window (as long as the last one closed) are one look at it.
    const double look_s =
        std::max(filter_internal::kPairWindowS, pair_window[j].closed_duration_s);
    level_weight = options.quasi_static ? 1.0 : std::min(1.0, step_dt / look_s);
    log_likelihood_ratio =
        ContactLogLikelihoodRatio(residual, sd_c * sd_c + free_variance, residual, free_variance,
                                  dof, held_evidence, level_weight);
  }
  pending[j] = PendingEffort{true,       mixture,       residual,      variance,
                             moving,     rest,          arm_torque,    still,
                             pose_rad,   log_likelihood_ratio,         held_evidence,
                             level_weight,              free_variance, transitions};
}

// The effort's update once the contact is known: what the no-contact rows
// teach of the arm's own torque, the Kalman update, the mixture's collapse.
void ComplianceFilter::Impl::FinishEffort(const FilterSample& sample, int j, bool unloaded,
                                          StepTally* tally) {
  PendingEffort& e = pending[j];
  if (!e.update) return;
  e.update = false;
  if (e.mixture) {
    const double free_share = 1.0 - contact_probability[j];
    unmodelled[j].Learn(free_share * e.moving *
                            -std::expm1(-step_dt / options.unmodelled_effort_memory),
                        e.residual, e.rest);
    if (!options.quasi_static) {
      free_pair_change[j].Learn(1.0 - contact_probability[j] * held_given_contact);
      InternalTorque& arm = internal_torque[j];
      arm.AddLevelRow(ArmStill(), e.residual + arm.level.Torque(), LevelPose(sample));
      internal_torque[j].Learn(e.moving, e.residual + e.arm_torque,
                               e.rest + unmodelled[j].variance, contact_probability[j], step_dt,
                               options.internal_torque_memory_s);
    }
  }
  if (e.mixture) {
    UpdateEffortBranches(sample, j, unloaded, tally);
    return;
  }
  ClearBranches(j);
  ScalarUpdate(j, kEffortChannel, Vector::Unit(kTorque) + Vector::Unit(kOffset),
               e.residual - joint[j].mean[kTorque], e.variance, tally, false,
               ConsiderFor(sample, j, unloaded));
}

// The speed of z = q_enc − s·K(L)·r (FreeArmMotion), r the effort less the
// bias, the further effects' internal torque and the learned offset.
double ComplianceFilter::Impl::FreeSpeed(int j, const FilterSample& sample, double effort_less_bias) {
  const FilterJointState& s = joint[j];
  const double r = effort_less_bias - extra_internal_torque_nm[j] - s.mean[kOffset];
  free_motion[j].Advance(step_dt, sample.encoder_rad[j] - s.mean[kScale] * ComplianceAtDepth(j) * r);
  return free_motion[j].velocity_rad_s;
}

// Where the free level is: both joints' free-arm angles z (the last computed)
// and the insertion. The bias table's error is a function of the whole pose.
Eigen::Vector3d ComplianceFilter::Impl::LevelPose(const FilterSample& sample) const {
  return Eigen::Vector3d(pending[0].pose_rad, pending[1].pose_rad, sample.insertion_depth_m);
}

// How still the whole arm stands (a joint the log does not record counts as
// still): one joint's effort carries the others' motion through the arm's
// coupled dynamics, which the per-joint torque does not model.
double ComplianceFilter::Impl::ArmStill() const {
  double still = 1.0;
  for (int k = 0; k < 2; ++k) still *= options.joint_recorded[k] ? pending[k].still : 1.0;
  return still;
}

}  // namespace pliant::estimation
