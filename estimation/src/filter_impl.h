// The online filter's internals (filter.h), shared by filter.cpp (model,
// updates, state step) and filter_alignment.cpp (the inertial alignment:
// samples held back, the estimate carried to the newest one).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>
#include <ceres/jet.h>

#include "pliant/estimation/extra_effects.h"
#include "pliant/estimation/filter.h"
#include "filter_contact_chain.h"
#include "filter_internal_torque.h"
#include "pliant/models/effects/compliance.h"
#include "pliant/estimation/effect_inputs.h"
#include "pliant/models/travel_since_reversal.h"

namespace pliant::estimation {
namespace filter_internal {

// One slot per state of a joint block, (q_tip, tau, b, s, e, beta). Both joints are
// evaluated in one pass with each joint's inputs seeded in its own block's
// slots: no built-in part of the model couples the joints, so each output's
// derivatives are with respect to its own joint's states. (The parameters
// file's deflection effects may couple them: filter_deflection.cpp.)
using StateJet = ceres::Jet<double, kFilterJointStates>;
constexpr int kTip = kStateTip, kTorque = kStateTorque, kBacklash = kStateBacklash,
              kScale = kStateScale, kClearance = kStateClearance, kOffset = kStateEffortOffset;
using Vector = FilterStateVector;
using Matrix = FilterStateMatrix;
enum Channel { kEncoderChannel = 0, kEffortChannel = 1, kReferenceChannel = 2 };
constexpr int kMaxScalarsPerStep = 6;   // 2 encoders, 2 efforts, 2 references
constexpr double kMaxJointSpeed = 5.0;  // rad/s: a larger encoder increment is not motion
constexpr double kMinScale = 0.05, kMaxScale = 20.0;
// A held tip cannot change its insertion: a larger depth change between two
// tip-fixed samples means it was released and held again elsewhere (a log of
// hold means, which skips the transit between clamps).
constexpr double kMaxHeldDepthChange = 2e-4;  // m
constexpr int kExactQuantileDof = 1000;  // Wilson–Hilferty beyond (relative error < 1e-5)

struct StepTally {
  double nis = 0.0;         // accepted scalars
  int dof = 0;
  double window_nis = 0.0;  // accepted + rejected (capped), for the mismatch test
  int window_dof = 0;
  std::uint32_t flags = 0;
};

// What the filter does not know about the instrument, per joint: σ_δ, σ_β, σ_w.
struct InstrumentUncertainty {
  double clearance_sd_rad = 0.0, width_sd_nm = 0.0;
  double effort_offset_sd_nm = 0.0;
};

// Joint j's prior covariance for a clearance δ (filter.cpp).
Matrix PriorCovariance(const FilterOptions& o, double delta, const InstrumentUncertainty& u);

// The parameters file's deflection effects at the state's loads
// (filter_deflection.cpp): Σ Δq_j (rad) and its slope ∂Δq_j/∂τ_i (rad/N·m),
// from the effects' own code with ceres::Jet.
struct ExtraDeflection {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  Eigen::Matrix2d slope = Eigen::Matrix2d::Zero();  // (j, i): ∂Δq_j/∂τ_i
};

// The evidence for contact from the slab's innovation (and its variance) and the
// no-contact residual (its scale², Student-t with free_dof degrees of freedom,
// Gaussian when free_dof is infinite): level_weight·[log p(r | contact) −
// log p(r | free)] + held_log_evidence (a pose pair's, QuasiStaticTransitions),
// within ±700.
double ContactLogLikelihoodRatio(double contact_innovation, double contact_variance,
                                 double free_residual, double free_variance, double free_dof,
                                 double held_log_evidence, double level_weight);
// A quasi-static log's two consecutive poses at one depth: their
// log-likelihoods under the four moves of the contact chain between them
// (filter_contact.cpp, QuasiStaticTransitions). Invalid: no such pair.
struct PoseTransitions {
  bool valid = false;
  double held = 0.0;     // contact → contact: the load followed the encoder
  double onset = 0.0;    // free → contact: a new load beside the table's error
  double release = 0.0;  // contact → free: the residual is the table's error
  double free = 0.0;     // free → free: the table's error stayed
};
PoseTransitions QuasiStaticTransitions(const FilterOptions& o, double residual,
                                       double residual_change, double encoder_change,
                                       double scale_compliance, double scale_sd,
                                       double clearance_rad, double internal_torque_change,
                                       double free_variance, double noise_rows = 2.0);
// P(contact) after a pose pair, from the last pose's posterior `probability`
// and the four moves' log-likelihoods summed over the joints.
double ContactAfterPosePair(const FilterOptions& o, const ContactRates& rates, double probability,
                            const PoseTransitions& evidence);
// An effort's update waiting for the shared contact probability (ShareContact).
struct PendingEffort {
  bool update = false, mixture = false;
  double residual = 0.0, variance = 0.0, moving = 0.0, rest = 0.0, arm_torque = 0.0, still = 0.0;
  double pose_rad = 0.0, log_likelihood_ratio = 0.0, held_evidence = 0.0, level_weight = 0.0, free_variance = 0.0;
  PoseTransitions transitions;  // a quasi-static pose pair, or a continuous log's closed window
};
// A quasi-static log's last pose, per joint, for QuasiStaticTransitions; in a
// continuous log, the means over a pair window's rows (PairWindow).
struct LastPose {
  bool valid = false;
  double encoder_rad = 0.0;
  double residual_nm = 0.0;
  double depth_m = 0.0;
  double internal_torque_nm = 0.0;  // the parameters' further effects' (held friction)
  InternalTorque::Vector4 arm_regressor = InternalTorque::Vector4::Zero();
  double rows = 1.0;  // a window's, whose mean it is
};
// A continuous log's rows in windows that do not overlap (each row's noise
// counted once): the means of two consecutive windows are a pose pair. A
// window lasts kPairWindowS at least, and until the encoder has moved by
// `min_travel_rad` (a bend that would show above the pair's noise:
// WindowTravel) or kMaxPairWindowS has passed. Means, because a row's θ̈
// (and so its inertial doubt) flickers with the encoder's counts while a
// window's mean is the change of its speed; their effort noise is σ_e²/n
// (docs/decisions/contact-pair-windows.md).
constexpr double kPairWindowS = 0.05, kMaxPairWindowS = 1.0;
struct PairWindow {
  int rows = 0;
  double start_s = 0.0, first_encoder_rad = 0.0;
  double closed_duration_s = 0.0;  // the last closed window's
  LastPose sum, previous;  // this window's sums (depth: its first row's); the last window's means
  void Restart() { rows = 0, previous.valid = false; }
  // Adds a row; true when it closes a window whose means follow a previous
  // window's at one depth (then `previous` is the earlier, `closed` this one).
  bool Add(const LastPose& row, double time_s, double min_travel_rad, LastPose* closed);
};
// log[(e^(held − free) + 1)/2]: a contact holds the tip (the load follows
// the bend) or, with even odds, moves with the arm (its load changes as a
// free arm's effort would).
double HeldWindowEvidence(const PoseTransitions& t);
// How fast the arm moves as a free arm would: the speed of z = q_enc − s·K(L)·r,
// r the effort residual. A held tip's motor moves only as the load bends the
// shaft, so z stands still while a pushed tip's encoder moves; a free arm's
// z moves with it. A fading-memory linear fit (Morrison's degree-1 filter,
// critically damped α-β) with time constant kFreeMotionTimeS.
struct FreeArmMotion {
  bool started = false;
  double z_rad = 0.0, level_rad = 0.0, velocity_rad_s = 0.0;  // the last z, its tracked level
  double theta_dt_s = -1.0, theta = 0.0;  // e^(−dt/T) for the last dt (rarely changes)
  void Advance(double dt, double z_rad);
};
// The Gaussian-sum collapse of the slab posterior and its tau = 0 conditional.
void CollapseContact(FilterJointState* state, double probability);
// σ_moving², the moving arm's unmodelled internal torque (FilterOptions::
// moving_effort_sd_nm), learned from moving no-contact rows.
struct UnmodelledEffort {
  double variance = 0.0;  // N·m²
  void Learn(double weight, double residual, double rest_variance);
};

// Time and encoder increments between consecutive samples: a step of no time
// is one sample period, and at most 1 s; an increment faster than any joint
// can move (or from a NaN) is not motion: 0, and flagged implausible.
struct SampleClock {
  double last_time = 0.0;
  Eigen::Vector2d last_encoder{0.0, 0.0};

  void Start(const FilterSample& s) {
    last_time = s.time_s;
    for (int j = 0; j < 2; ++j) {
      last_encoder[j] = std::isfinite(s.encoder_rad[j])     ? s.encoder_rad[j]
                        : std::isfinite(s.reference_rad[j]) ? s.reference_rad[j]
                                                            : 0.0;
    }
  }
  double Advance(const FilterSample& s, double period, Eigen::Vector2d* increment,
                 bool implausible[2]) {
    double dt = s.time_s - last_time;
    if (!(dt > 0.0)) dt = period;
    dt = std::min(dt, 1.0);
    if (std::isfinite(s.time_s)) last_time = s.time_s;
    for (int j = 0; j < 2; ++j) {
      (*increment)[j] = s.encoder_rad[j] - last_encoder[j];
      implausible[j] = std::abs((*increment)[j]) > kMaxJointSpeed * dt;
      if (!(std::abs((*increment)[j]) <= kMaxJointSpeed * dt)) (*increment)[j] = 0.0;
      if (std::isfinite(s.encoder_rad[j])) last_encoder[j] = s.encoder_rad[j];
    }
    return dt;
  }
};

}  // namespace filter_internal

struct ComplianceFilter::Impl {
  using StepTally = filter_internal::StepTally;
  using Channel = filter_internal::Channel;
  using Vector = filter_internal::Vector;
  using StateJet = filter_internal::StateJet;
  using InstrumentUncertainty = filter_internal::InstrumentUncertainty;
  using SampleClock = filter_internal::SampleClock;
  Impl(const models::ModelParameters& p, const FilterOptions& o);

  FilterEstimate Step(const FilterSample& sample);
  bool StepHeldSample();
  void Reset();
  void AdvanceMotion(const FilterSample& sample);
  void StepState(const FilterSample& sample);
  void AdvanceState(const FilterSample& sample, double previous_depth, StepTally* tally);
  void ExtraInternalTorque(const FilterSample& sample);
  void PrepareDeflectionEffects();
  filter_internal::ExtraDeflection DeflectionAt(double torque1_nm, double torque2_nm) const;
  filter_internal::ExtraDeflection Deflection() const {
    return DeflectionAt(joint[0].mean[kStateTorque], joint[1].mean[kStateTorque]);
  }
  double ContactOnsetVariance(const FilterSample& sample, int j, double dt);
  void UpdateMeasurements(const FilterSample& sample, StepTally* tally);
  void UpdateEffort(const FilterSample& sample, int j, bool unloaded, StepTally* tally);
  filter_internal::PoseTransitions PoseChangeEvidence(const FilterSample& sample, int j, double residual,
                                     double free_variance);
  void Reinitialise(int j, const FilterSample& sample, bool held_tip_stays);
  double FreeSpeed(int j, const FilterSample& sample, double effort_less_bias);
  void ShareContact();
  double HeldShare(const FilterSample& sample, int j) const;
  // Without the hint, past the unloaded start: the contact is inferred.
  bool InfersContact(const FilterSample& sample) const {
    return options.infer_contact && !sample.tip_fixed &&
           !InUnloadedStart(options, sample.time_s - start_time_s);
  }
  double LevelEvidence(double per_joint) const;
  Eigen::Vector3d LevelPose(const FilterSample& sample) const;  // the free level's pose
  double ArmStill() const;
  void LearnHold();
  double WindowTravel(int j, const filter_internal::LastPose& now, double time_s);
  void FinishEffort(const FilterSample& sample, int j, bool unloaded, StepTally* tally);
  void UpdateEffortBranches(const FilterSample& sample, int j, bool unloaded, StepTally* tally);
  void PredictBranchGap(int j, double encoder_increment, double load_step);
  double HeldPoseShare(const FilterSample& sample, int j, double previous_depth, bool jump) const;
  void PredictPoseBranches(int j, const FilterSample& sample, double dt, double encoder_increment,
                           double extra_compliance, double held);
  void UpdateBranches(int j, const Vector& h) {
    if (!branched[j]) return;
    branch_gap[j] -= last_gain * h.dot(branch_gap[j]);
    branch_spread[j] -= last_gain * h.dot(branch_spread[j]);
  }
  void ClearBranches(int j) {
    has_pose_other[j] = false;
    if (!branched[j]) return;
    branched[j] = false;
    branch_gap[j].setZero();
    branch_spread[j].setZero();
  }
  FilterEstimate Output(const FilterSample& newest);

  void Initialise(const FilterSample& sample, double depth);
  void Predict(int j, double dt, bool tip_fixed, bool seated, double encoder_increment,
               double extra_compliance, double held_share);
  void Release(int j, double dt, double encoder_increment);
  void EncoderModel(double depth, Eigen::Vector2d* predicted, Vector* h,
                    Eigen::Vector2d* coupling_variance) const;
  /// Which states an update may not move (Schmidt–Kalman consider states),
  /// a mask of these bits (ScalarUpdate says why for each).
  enum Consider : unsigned {
    kLearnAll = 0,
    kConsiderScale = 1,
    kConsiderClearance = 2,
    kConsiderOffset = 4,
  };
  unsigned ConsiderFor(const FilterSample& sample, int j, bool unloaded) const {
    if (std::isfinite(sample.reference_rad[j]) && sample.tip_fixed) return kLearnAll;
    // The unloaded start's effort teaches β; nothing else does without a reference.
    const unsigned offset = unloaded ? 0u : unsigned(kConsiderOffset);
    if (!sample.tip_fixed) return kConsiderScale | kConsiderClearance | offset;
    const bool travelling = options.clearance_needs_a_wall && !walls[j].TeachClearance();
    return (travelling ? unsigned(kConsiderClearance) : 0u) | offset;
  }
  void ScalarUpdate(int j, Channel channel, const Vector& h, double innovation,
                    double variance, StepTally* tally, bool implausible = false,
                    unsigned consider = kLearnAll);
  void Repair(int j, const FilterSample& sample, bool full_check, StepTally* tally);
  void UpdateWindow(StepTally* tally);
  /// K_j(L) at the current depth, rad/N·m, evaluated again only when the depth changes.
  double ComplianceAtDepth(int j) {
    if (depth != compliance_depth) {
      compliance_depth = depth;
      for (int i = 0; i < 2; ++i) {
        compliance_at_depth[i] = models::ComplianceAt(parameters.joints[i], depth);
      }
    }
    return compliance_at_depth[j];
  }

  models::ModelParameters parameters;
  FilterOptions options;
  // The parameters file's further effects (held friction, …): their torques are taken out of
  // each effort, as pliant correct does, their parameters' σ is the effort's further noise
  // (ConsideredVariance; the arm dynamics' share apart). This state step's:
  ExtraEffects extra_effects;
  EffectInputs effect_rows;  // (made again with the options in Reset)
  Eigen::Vector2d extra_internal_torque_nm{0.0, 0.0}, extra_internal_variance_nm2{0.0, 0.0},
      extra_learned_variance_nm2{0.0, 0.0};
  // The row's inputs the effects see (EffectInputs: angles, depth, time,
  // velocity, the effort's rate, travel); the deflection effects get the
  // state's τ on top (filter_deflection.cpp).
  models::JointState<double> effect_inputs;
  // The file's deflection effects: their index in extra_effects and their
  // parameters as Jet constants (sized once: Step never allocates).
  struct DeflectionEffect {
    std::size_t index = 0;
    std::vector<EffectJet> parameters;
  };
  std::vector<DeflectionEffect> deflection_effects;
  models::ComplianceEffect compliance;
  std::array<StateJet, 8> compliance_coefficients;  // constants (zero derivatives)
  double delta[2];
  double width[2];
  InstrumentUncertainty uncertainty[2];
  double gate;
  std::vector<double> window_threshold;  // by total dof in the window
  std::vector<double> window_nis;        // ring buffer, one entry per sample
  std::vector<int> window_dof;

  FilterJointState joint[2];
  FilterTransition transition[2];
  int rejections[2][3] = {};
  bool initialised = false;
  SampleClock state_clock;  // between the samples the state steps through
  double depth = 0.15;
  double compliance_depth = std::numeric_limits<double>::quiet_NaN();  // NaN: not yet evaluated
  double compliance_at_depth[2] = {0.0, 0.0};
  bool last_tip_fixed = false;
  bool implausible_jump[2] = {false, false};  // encoder moved faster than any joint can
  double step_dt = 0.0;  // the state's last step, s (a nominal period across a gap)
  // The contact chain (FilterOptions::infer_contact): its probability after
  // the last effort, its prediction for this step, and the load variance the
  // onset of a new contact adds to this step's prediction.
  double contact_probability[2] = {1.0, 1.0};
  double contact_prior[2] = {1.0, 1.0};
  double contact_onset[2] = {0.0, 0.0};
  filter_internal::ContactRates contact_rates;  // shared by the joints, as the contact is
  double chain_step_s = 0.0;  // this step's chain time (ContactOnsetVariance)
  // The state is the mixture of a contact branch and a free one; what they
  // differ by in mean (contact − free) is kept, so that a contact recognised
  // late brings the load and the tip its branch has followed (IMM's two
  // estimates, sharing one covariance). The contact prior's make-up this step:
  // the last posterior p, the share w1 of the contact prior that goes on
  // from the contact branch, and the share u of the free prior that does.
  Vector branch_gap[2];
  // The branches' spread in the state's covariance, P = P_w + E·Eᵀ with
  // E = √(p(1 − p))·D at the last collapse, carried through the same linear
  // maps as P since, so that the next effort's update takes it out again
  // (each branch's own covariance is P_w) instead of adding it once more.
  Vector branch_spread[2];
  bool branched[2] = {true, true};  // D or E may be non-zero (false: both are 0, nothing to carry)
  double branch_last[2] = {}, branch_continuing[2] = {}, branch_ended[2] = {};
  filter_internal::Matrix pose_other[2]; bool has_pose_other[2] = {};  // a held pose's free tip's P
  Vector last_gain;  // ScalarUpdate's last gain (0: rejected)
  // Given a contact, the chance that it holds the tip (its load follows the
  // bend) rather than moving with the arm: the pair windows' evidence
  // (HeldWindowEvidence's two laws), persisting as the contact chain does.
  double held_given_contact = 0.5;
  filter_internal::LastPose last_pose[2];  // quasi-static logs only
  filter_internal::PairWindow pair_window[2];  // continuous logs only
  filter_internal::FreeArmPairChange free_pair_change[2];  // continuous logs only
  filter_internal::FreeArmMotion free_motion[2];  // without the tip_fixed hint
  filter_internal::PendingEffort pending[2];
  filter_internal::UnmodelledEffort unmodelled[2];
  filter_internal::InternalTorque internal_torque[2];
  Eigen::Matrix2d arm_friction = Eigen::Matrix2d::Zero();  // ArmFriction, this step's
  MotorMotion motion[2];  // for the inertial torque in the effort, from the newest sample
  // The motor's rate over the state's own step (rad/s): the shaft's bend rate
  // with the tip held, in step with the effort it is taken out of.
  double bend_rate_rad_s[2] = {0.0, 0.0};
  // The hold g of the sure load at this step's prediction (0 before one, or
  // after a release): the backlash step's and the damping term's.
  double step_hold[2] = {0.0, 0.0};
  ClearanceWalls walls[2];  // a wall pressed since the tip was seated
  double start_time_s = 0.0;  // the first sample's, for unloaded_start_s
  bool motion_started = false;
  SampleClock motion_clock;  // between the newest samples
  Eigen::Vector2d newest_step{0.0, 0.0};  // the newest sample's encoder change (0 when not motion)
  // The inertial alignment: samples received but not yet in the state, oldest
  // first (a fixed ring: Step never allocates).
  static constexpr int kHeldCapacity = 64;
  int alignment_steps = 0;
  std::array<FilterSample, kHeldCapacity> held{};
  int held_first = 0, held_count = 0;
  FilterSample state_sample;      // the sample the state is at
  FilterEstimate state_estimate;  // and its estimate
  bool advanced = false;
  OutputStepLimiter limiter;
  double output_count_rad = 0.0;       // one encoder count
  bool restart_output[2] = {true, true};  // the output jumps to the estimate this step
  int window_position = 0;
  // Steps between two full Cholesky tests of a block's covariance: the
  // rounding the Joseph form leaves builds up over thousands of steps, not 32
  // (21 ms at 1.5 kHz).
  static constexpr int kFullCheckPeriod = 32;
  int check_phase = 0;  // block 0 is tested at phase 0, block 1 at phase 16
  int window_count = 0, window_dof_sum = 0;
  double window_sum = 0.0;
};

}  // namespace pliant::estimation
