#pragma once
// The online filter: an extended Kalman filter that treats compliance and
// backlash of PSM joints 1 (yaw) and 2 (pitch) as states, fuses encoders and
// efforts every control period, and returns corrected joint angles with their
// covariance. docs/filter.md derives it; this header is the contract.
//
// State, per joint j (both joints in one filter, 12 states):
//   q_tip_j   rad    corrected (tip-consistent) joint angle
//   tau_j     N·m    external torque
//   b_j       rad    backlash offset inside the clearance, |b_j| <= delta_j + e_j
//   s_j       1      compliance scale: the shaft's compliance is s_j·K_j(L)
//   e_j       rad    clearance error: the instrument's clearance is delta_j + e_j
//                    (constant, prior 0 ± σ_δ; learned when the shaft crosses it)
//   beta_j    N·m    effort offset: the bias torque misses a constant beta_j
//                    (prior 0 ± σ_β; a held tip cannot tell it from the load,
//                    so its variance flows into q_tip through K)
//
// Process (period dt):
//   q_tip+ = q_tip                           while the tip is fixed (no noise)
//   q_tip+ = q_tip + (q_enc,k − q_enc,k−1)    otherwise, + noise σ_free²·dt
//   tau+   = tau + noise σ_τ̇²·dt            (random walk; with the tip held, while
//            the load holds the shaft on its wall, no faster than the motor bends
//            it: HeldLoadProcessVariance, bound_held_load_rate)
//   b+     = BacklashHysteresisStep(b, tau, delta + e, w, r, g)  (models/effects/
//            backlash_hysteresis.h: a load only pushes b toward the wall it points at;
//            g = S(SureLoad(tau)/w)², a constant in the Jacobian; r = 1 − e^(−dt/T) while
//            the joint moves, 0 at rest: BacklashRelax)
//            + noise ((1 − g)·u + c·g·(1 − g)·δ²/3 + σ_pinned²·dt), variance ≤ δ²/3
//            with the tip free (BoundBacklashVariance; not bounded held),
//            g as above, u = σ_b²·dt (tip held, r = 0) or (1 − (1 − r)²)·δ²/3
//            (tip free); c = backlash_transit_noise with the tip held, 2 free
//            (BacklashProcessVariance)
//   s+     = s + noise σ_ṡ²·dt
//   e+     = e;  beta+ = beta + noise σ_β̇²·dt
//   Two tip-fixed samples whose depths differ by more than 0.2 mm: the tip was
//   released and held again elsewhere (a log of hold means skips the transit):
//   q_tip and tau restart from their priors, b relaxes as a free tip's over
//   the encoder increment, s, e and beta carry over.
//   The first tip-fixed sample after a free one (the tip is seated): before
//   predicting, P is replaced by the bound blockdiag(P_rest/ω, P_ττ/(1 − ω))
//   ≥ P (SeatingBound), which drops the tip–load correlation the free tip
//   built (q_tip = q_enc − b − s·K·tau) at a known cost in variance.
// Measurements:
//   q_enc_j  = q_tip_j + b_j + s_j·K_j(L)·tau_j   (ComplianceEffect)
//            variance σ_enc² + (ε·K_j(L)·tau_j)², ε = deflection_model_error
//   tau_meas_j − tau0_j(q_enc, L) − J·θ̈_j = tau_j + beta_j  (bias torque; J·θ̈ with the
//            tip held, MotorMotion)                            σ_effort
//   q_ref_j  = q_tip_j                             (when the log has it) σ_ref
//   With the tip free, s, e and beta are consider states of the encoder and
//   effort updates (Schmidt–Kalman: zero gain, their doubt still carried into
//   P): a free tip is wherever the encoder puts it, so those updates hold no
//   information about the instrument; the prior of compliance and backlash is
//   kept, as issue 5 asks. A reference (q_ref) still teaches them.
//   With the tip held, beta stays a consider state of both: a held tip tells
//   beta from the load only where the shaft leaves its wall, which the smooth
//   dead zone cannot place (docs/filter.md, "The bias offset is a consider
//   state"); on a sample with a reference (the tip known) they teach it.
// Jacobians come from ceres::Jet. The joints share no state and no
// measurement while no coupling effect is on, so the filter runs two blocks
// of 6 states with sequential scalar updates (Joseph form); q12_cov is then
// zero.
//
// Real time: Step() never allocates, never throws, and takes a bounded time
// (no loops that depend on the data). A Filter object is not thread-safe: one
// control thread owns it; distinct objects are independent and may run on
// different threads (they share only immutable parameters they copied).

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// Noise levels, gates and the mismatch test. Defaults: a Classic PSM at
/// 1.5 kHz (reference/dvrk.md) with the simulator's sensor noise.
struct FilterOptions {
  double sample_period_s = 1.0 / 1500.0;  ///< used when t does not give one
  // Measurement noise (standard deviations).
  double encoder_noise_rad = 7.7e-6 / 3.4641016151377544;  ///< one count / √12
  double effort_noise_nm = 0.01;
  double reference_noise_rad = 5e-5;   ///< q1_ref, q2_ref (an optical tracker)
  // Process noise (standard deviations per √s).
  double external_torque_rate_nm = 0.1;   ///< σ_τ̇, N·m/√s
  /// With the tip held, the load is the shaft's bend, held at both ends: it
  /// changes only as the motor moves it (|Δtau| ≤ |Δq_enc|/(s·K(L)) with the
  /// shaft on its wall, less inside the clearance) or as the tissue relaxes.
  /// true: while the load holds the shaft on its wall, the load's process
  /// variance is at most σ_rest²·dt + (m·Δq_enc/(s·K(L)))² + (J·θ̈)²·dt/T_a
  /// (HeldLoadProcessVariance), never above σ_τ̇²·dt; inside the clearance
  /// the encoder moves b too, which may go either way, and σ_τ̇ holds. Why:
  /// through a steady hold, a load free to follow the effort noise made that
  /// noise a regressor of s, which drifted toward 0 (s 0.658 after 19 s at
  /// 1.5 w; with the bound 0.978; docs/filter.md, "A held load moves only as
  /// the motor bends the shaft"). false: σ_τ̇ alone, as a free tip's load has.
  bool bound_held_load_rate = true;
  /// With the tip held, the motor's encoder increment Δq bends the shaft: the
  /// load's prediction is tau + g·Δq/(s·K(L)) (HeldLoadIncrement, g the hold
  /// of the sure load), the motion a known input rather than a random walk to
  /// catch up with. Why: while a push ramps the load, a random-walk tau ran
  /// behind the bend the encoder already showed; the same-sign innovation,
  /// sample after sample, went into s (divot trial 658: s 1.00 → 1.29 in
  /// 0.2 s against a true 1.02; with the input 1.06), and joint 1's interval
  /// covered 91 % (docs/validation.md, Part 4, "The load follows the motor").
  /// false: tau+ = tau, as a free tip's.
  bool load_follows_motor = true;
  /// true: a held tip's encoder teaches the clearance error e only once the
  /// hold's load has pressed the shaft against a wall (ClearanceWalls); until
  /// then e is a consider state. Why: the shaft starts anywhere in its
  /// clearance (uniformly), and until the load presses it against a wall its
  /// travel depends on that start as much as on the clearance. A shaft that
  /// starts on the wall it is pushed against shows no travel whatever its
  /// clearance; the Gaussian stand-in for the start read that as a narrow
  /// clearance (divot trial 505: e −0.84 mrad against a true +1.5, joint 2
  /// off by 2.1 σ for the whole hold; docs/validation.md, Part 4, "The
  /// effort's offset and the clearance's first wall"). false: e learns from
  /// every held sample.
  bool clearance_needs_a_wall = true;
  double held_load_rest_rate_nm = 0.01;   ///< σ_rest, N·m/√s: tissue relaxation, a slow slip
  /// m ≥ 1: the margin on the motor's increment for the error of s·K(L).
  double held_load_motion_margin = 2.0;
  /// The motor's increment is the largest of the recent ones, fading with
  /// this time constant (MotorMotion::increment_peak_rad), s. Why not the
  /// sample's own: a variance set from the very increment the encoder update
  /// then reads counts that increment twice; on logs whose load is a random
  /// walk (the filter's own process model) that taught s from noise (NEES
  /// 4.07 against 2.29 over 100 runs, band 1.63–2.41; filter_test.cpp).
  double held_load_motion_window_s = 0.02;
  /// T_a, s: lets the load absorb, over this time, a misread of the inertial
  /// torque J·θ̈ as large as that torque (the fitted θ̈ lags the effort's).
  double held_load_inertial_time_s = 0.02;
  double backlash_rate_rad = 0.05;        ///< σ_b at no load with the tip held, rad/√s
  /// Time T over which an unloaded shaft forgets its wall while the joint
  /// moves: b relaxes to the middle of the clearance, b+ = b·e^(−dt/T), and its
  /// variance to δ²/3 (BacklashRelax); a joint at rest keeps its offset. Free
  /// tip only: with the tip held the encoders see b.
  double backlash_relax_time_s = 0.05;
  double backlash_pinned_rate_rad = 2e-4; ///< σ_b with the shaft loaded onto a wall, rad/√s
  /// How uncertain the pull of a partial load is, held tip: the hysteresis
  /// step pulls b by g = S² toward δ·S(tau/w), a smooth stand-in for a shaft
  /// that meets its wall at a load the model cannot place inside w; the pull
  /// gets variance this × g·(1 − g)·δ²/3 per sample (0 at no load and on the
  /// wall).
  double backlash_transit_noise = 10.0;
  double compliance_scale_rate = 0.0;     ///< σ_ṡ, 1/√s
  /// σ_free, rad/√s, tip not fixed. Large on purpose: a free tip is wherever
  /// the encoder puts it (less the deflection), and the prior of compliance and
  /// backlash must not be "learned" from encoder increments that contain them.
  double free_tip_rate_rad = 1.0;
  /// The filter's dead-zone width is max(w from the parameters, this × σ_effort).
  double backlash_width_noise_multiple = 10.0;
  /// Motor-side inertia J reflected at joints 1 and 2, kg·m². The effort
  /// accelerates the motor as well as loading the shaft: with the tip held the
  /// filter reads tau_meas − tau0 − J·θ̈ as the load, θ̈ from the encoders
  /// by a fading-memory quadratic fit of this memory time constant
  /// (MotorMotion). 0 (the default): the whole effort
  /// is load, right for logs drawn from the quasi-static model; the simulator's
  /// arm (experiments JointDynamics) has 0.08.
  double motor_inertia_kg_m2 = 0.0;
  /// The shaft's damping c_s, N·m·s/rad (models::ShaftDampingTorque): with the
  /// tip held, a shaft on its wall (hold g) resists being bent, and the
  /// effort carries g·c_s·θ̇ beyond the load, θ̇ the encoder's rate over the
  /// state's step; the filter takes it out with J·θ̈. Why: read as load, it
  /// is deflection that is not there, which ε had to cover (ε 0.08 without
  /// it, 0.05 with it: DeflectionModelError(); docs/validation.md, Part 4,
  /// "The shaft's damping").
  /// 0 (the default): none; the simulator's instrument has 0.02.
  double shaft_damping_nm_s_per_rad = 0.0;
  double acceleration_filter_time_s = 0.004;
  /// κ: the error of the fitted inertial torque as a fraction of it, effort
  /// variance (κ·J·θ̈)² with the tip held (where J·θ̈ is taken out). Why:
  /// the fit misreads the sharp accelerations of a stepped arm (the clamped
  /// sweeps' 0.25 mm steps) by a share of J·θ̈ that the white effort noise
  /// did not allow, and each step's misread moved s and the held tip
  /// (clamped study: joint 1 covered 88.6 %, with κ 0.3 94.9 %; docs/
  /// validation.md, Part 4, "The load follows the motor"). 0: the fit is exact.
  double inertial_torque_error = 0.3;
  /// With motor inertia (J > 0), run the filter's state that many samples
  /// behind the newest one that the fitted acceleration's lag (under a
  /// constant jerk, MotorMotion::LagSeconds: 11.7 ms, 18 samples, at the
  /// defaults) lines up with the effort it is taken out of; Step() carries the
  /// estimate forward to the newest sample (CarryEstimate). Why: the effort
  /// holds J·θ̈ now, the fit knows θ̈ of ~12 ms ago; in the clamped-beam sweeps
  /// (8 Hz arm oscillation after each step) that misfit was 2–3 times the
  /// effort noise, correlated over a move, and dragged the compliance scale
  /// and the held tip (docs/filter.md, "Aligning the inertial torque").
  /// The count of samples is the lag over sample_period_s: a log at another
  /// rate than the PSM's 1.5 kHz needs that period set to line up.
  /// false: process each sample as it comes (the inertial torque then lags).
  bool align_inertial_torque = true;
  /// ε, the relative error of the deflection model, as encoder variance
  /// (ε·K·tau)²: what the effort model lacks. Calibrated on the simulator,
  /// its motor inertia given: with its shaft damping given too, 0.05 puts the
  /// paper's pushes and continuous loads inside their NEES bands; without,
  /// the damping is part of what ε covers, and 0.08 keeps the paper's pushes
  /// inside (docs/validation.md, Part 4, "The shaft's damping"; 0.075 before
  /// bound_held_load_rate). NaN (the default): DeflectionModelError() picks
  /// by shaft_damping_nm_s_per_rad.
  double deflection_model_error = kFromDamping;
  static constexpr double kFromDamping = std::numeric_limits<double>::quiet_NaN();
  static constexpr double kDeflectionErrorWithDamping = 0.04;
  static constexpr double kDeflectionErrorWithoutDamping = 0.08;
  /// ε in use: deflection_model_error, or when NaN 0.04 with the damping
  /// given (> 0) and 0.08 without.
  double DeflectionModelError() const {
    if (!std::isnan(deflection_model_error)) return deflection_model_error;
    return shaft_damping_nm_s_per_rad > 0.0 ? kDeflectionErrorWithDamping
                                            : kDeflectionErrorWithoutDamping;
  }
  /// A load counts only beyond this many of its own standard deviations
  /// (SureLoad): it pulls the shaft toward a wall (the hold g) and teaches the
  /// compliance scale (∂h/∂s = K·tau) with the part of tau the filter is sure
  /// of. Why: at a load within its noise, a pull of random sign reverted a
  /// held, unloaded shaft toward the middle of its clearance, which the
  /// filter then took as knowledge of the tip (NEES 9 on such joints); and a
  /// noisy tau as the regressor of s biased s toward 0 (errors in variables:
  /// s 1 → 0.72 over 40 s of an unloaded joint). 0: every load counts.
  double load_margin_sd = 2.0;
  /// The compliance scale learns from the encoder in proportion to g^n, g =
  /// S(SureLoad/w)² the hold of the sure load on its wall (BacklashHold), n =
  /// this (ScaleLearningFraction). Why: below the width the model's shaft is
  /// still crossing its clearance (b is uncertain and its mean is kept inside
  /// ±(δ + e)), so an encoder that moves beyond what the model's pull allows —
  /// a real shaft already on its wall, loaded — was read as compliance. Traced
  /// in a clamped-beam Monte Carlo trial held near w: with the simulator's
  /// shaft damping (≈ 10⁻⁴ N·m) taken out of the effort, s fell 1.0 → 0.74,
  /// the clearance error went to −δ and the tip 4 mm off; with this gate it
  /// stays under 1 mm. 4 (with ε = 0.075): the identify study's NEES 3.14 →
  /// 2.05, inside its band (docs/validation.md, Part 4, "Coverage by joint").
  /// 0: every sure load teaches s. What it does not stop: through a long
  /// steady hold near w, s still drifts toward 0 (the EKF's errors-in-variables
  /// bias on s·K·tau, which bound_held_load_rate shrinks from 1.5 w up;
  /// docs/filter.md, "Known limitation"; build/bench/filter_steady_hold_bench).
  double scale_hold_exponent = 4.0;
  // Priors.
  double compliance_scale_sd = 0.1;       ///< s starts at 1 ± this
  /// σ_δ per joint (rad): how far the instrument's clearance may lie from the
  /// parameters' backlash_rad. NaN (the default): the parameters' covariance
  /// of "jointN.backlash_rad" when they carry one, else
  /// kDefaultBacklashSdRad. 0: the clearance is known exactly.
  Eigen::Vector2d backlash_sd_rad{kFromParameters, kFromParameters};
  /// σ_β per joint (N·m): a constant offset the bias torque tau0 may miss.
  /// 0 (the default): off, the bias torque is taken as exact. NaN: the
  /// parameters' covariance of "jointN.bias_torque.coefficients[0]" (the
  /// Fourier mean) when they carry one, else kDefaultEffortOffsetSdNm.
  /// β's mean moves only with a reference (q_ref): to the encoder and the
  /// effort it is a consider state, whose doubt flows into q_tip through
  /// s·K(L). Off by default: learned, β made the divot and clamped-beam tips
  /// worse and their corrected angles jumpy; as a consider state it is worse
  /// still on those logs (divot 0.277 mm against 0.037 off, with σ_β from
  /// identification; docs/validation.md Part 4, "The bias offset as a
  /// consider state"). Turn it on with a reference, or to study its doubt.
  Eigen::Vector2d effort_offset_sd_nm{0.0, 0.0};
  double effort_offset_rate_nm = 0.0;     ///< σ_β̇, N·m/√s (0: a constant offset)
  /// β's mean stays within ±this × σ_β. Why: a held tip tells β from the load
  /// only through the deflection; in a clamped-beam Monte Carlo trial, while
  /// β was still learned from the encoder, β took a rising load, 0.18 N·m
  /// (9 σ_β), and the held tip moved 14 mrad in its stead (NEES 14,619; with
  /// this bound, 102). Now only a reference moves β's mean, and the bound
  /// holds it there too. Infinity: no bound.
  double effort_offset_bound_sd = 3.0;
  static constexpr double kFromParameters = std::numeric_limits<double>::quiet_NaN();
  /// Without a covariance: the clearance of one instrument vs another of the
  /// same model (the dVRK files' two joints differ by 1.3 mrad; the Monte
  /// Carlo study's uniform 6–10 mrad has σ 1.15 mrad).
  static constexpr double kDefaultBacklashSdRad = 1e-3;
  /// Without a covariance: twice the effort noise of a Classic PSM; a bias
  /// table identified in free motion misses about this on another day.
  static constexpr double kDefaultEffortOffsetSdNm = 0.02;
  double initial_torque_sd_nm = 1.0;
  /// Seconds from the log's first sample during which nothing touches the
  /// instrument and the arm is at rest, e.g. before it approaches the tissue:
  /// the load is 0 there, so the effort reads tau0 + β and teaches β (the
  /// tare a force-sensing arm takes before contact), while the tip's other
  /// states learn nothing from it. Why: elsewhere the effort cannot tell β
  /// from a load. A free tip read an offset of 3 σ_β as a load that put the
  /// shaft on a wall, and the tip stayed 2–4 σ off through the push that
  /// followed (divot study: joint 1's z² 3.5 for |β| > 1.5 σ_β; with a 0.15 s
  /// tare, 1.1). 0 (the default): no such span. Needs σ_β > 0
  /// (effort_offset_sd_nm) to teach anything; the arm must be still (the
  /// filter reads a free tip's effort without J·θ̈).
  double unloaded_start_s = 0.0;
  double initial_tip_sd_rad = 0.05;
  /// ω in (0, 1] of the seating bound (SeatingBound): when the tip is seated,
  /// every state but the load keeps its covariance × 1/ω and the load's is
  /// × 1/(1 − ω), uncorrelated. Why: a free tip is read as q_enc − b − s·K·tau,
  /// so its estimate carries the load's noise (K·σ_τ̂ ≈ 50 counts); held,
  /// each effort sample would then move the held tip by up to 27 counts while
  /// the filter unlearns that tie. 1: off (the tie is kept).
  double seating_bound_weight = 0.9;
  /// How far the corrected angle may move in one step beyond the encoder's
  /// own change, in encoder counts (one count = √12 · encoder_noise_rad). Why:
  /// a held tip learns where it is when the shaft meets its wall, and the
  /// estimate then moves by up to ~20 counts in a sample; a control loop or
  /// a virtual fixture must not see that as a jump. The output follows the
  /// estimate at this rate and its covariance adds the known gap d = output −
  /// estimate (the mean squared error P + d·dᵀ), flagged kFlagOutputLimited.
  /// The filter's state never sees the limit. Infinity: off.
  double output_step_limit_counts = 2.0;
  // Robustness.
  double gate_probability = 0.9999;  ///< χ²(1) gate on each scalar innovation
  int reacquire_after = 25;          ///< consecutive rejections before re-acquiring
  double effort_limit_nm = 3.316;    ///< |tau_meas| at or beyond: saturated, not used
  // Model mismatch: windowed NIS χ² test.
  int mismatch_window = 300;               ///< samples (0.2 s at 1.5 kHz)
  double mismatch_probability = 0.99;      ///< false-alarm rate per window = 1 − this

  /// True when every value is usable; otherwise false and *error says which
  /// option is wrong and what to do.
  bool IsValid(std::string* error) const;
};

/// One control period's input. NaN marks a missing value.
struct FilterSample {
  double time_s = 0.0;
  Eigen::Vector2d encoder_rad{0.0, 0.0};      ///< q1, q2
  double insertion_depth_m = 0.15;            ///< q3
  Eigen::Vector2d effort_nm{0.0, 0.0};        ///< tau1, tau2
  Eigen::Vector2d reference_rad{kMissing, kMissing};  ///< q1_ref, q2_ref
  bool tip_fixed = false;                     ///< the tip is clamped or in a divot

  static constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
};

/// Bits of FilterEstimate::flags.
enum FilterFlag : std::uint32_t {
  kFlagRejected = 1u << 0,         ///< a measurement failed the χ² gate
  kFlagMissing = 1u << 1,          ///< a NaN measurement (or depth) was skipped
  kFlagDepthOutOfRange = 1u << 2,  ///< q3 outside the parameters' valid depths
  kFlagEffortSaturated = 1u << 3,  ///< |tau| at the effort limit: effort not used
  kFlagModelMismatch = 1u << 4,    ///< windowed NIS beyond its χ² quantile
  kFlagReacquired = 1u << 5,       ///< covariance inflated after repeated rejections
  kFlagRepaired = 1u << 6,         ///< covariance was not positive definite and was repaired
  kFlagOutputLimited = 1u << 7,    ///< corrected angle behind the estimate (output step limit)
};

/// One control period's output.
struct FilterEstimate {
  /// q̂1, q̂2: the filter's q_tip, moved at most output_step_limit_counts
  /// beyond the encoder's change per step (equal to filtered_rad but while
  /// the limit holds it back: kFlagOutputLimited).
  Eigen::Vector2d corrected_rad{0.0, 0.0};
  /// Mean squared error of corrected_rad: the filter's covariance of q_tip
  /// plus d·dᵀ, d = corrected_rad − filtered_rad.
  Eigen::Matrix2d covariance_rad2 = Eigen::Matrix2d::Zero();
  Eigen::Vector2d filtered_rad{0.0, 0.0};    ///< the filter's mean of q_tip, unlimited
  double tip_correction_mm = 0.0;     ///< |uncorrected tip − corrected tip| through the kinematics
  double tip_correction_sd_mm = 0.0;  ///< its standard deviation
  double nis = 0.0;                   ///< normalised innovation squared of the accepted updates
  int nis_dof = 0;                    ///< how many scalar measurements it sums
  double window_nis = 0.0;            ///< sum of NIS over the mismatch window
  double window_threshold = 0.0;      ///< its χ² quantile
  std::uint32_t flags = 0;            ///< FilterFlag bits
  Eigen::Vector2d external_torque_nm{0.0, 0.0};
  Eigen::Vector2d backlash_offset_rad{0.0, 0.0};
  Eigen::Vector2d compliance_scale{1.0, 1.0};
  Eigen::Vector2d clearance_error_rad{0.0, 0.0};  ///< e: clearance − parameters' δ
  Eigen::Vector2d effort_offset_nm{0.0, 0.0};     ///< beta
};

/// States per joint block, and their order.
constexpr int kFilterJointStates = 6;
enum FilterStateIndex {
  kStateTip = 0, kStateTorque, kStateBacklash, kStateScale, kStateClearance, kStateEffortOffset
};
using FilterStateVector = Eigen::Matrix<double, kFilterJointStates, 1>;
using FilterStateMatrix = Eigen::Matrix<double, kFilterJointStates, kFilterJointStates>;

/// The full state of one joint block: x = (q_tip, tau, b, s, e, beta) and its
/// 6×6 covariance. What the smoother stores and what tests inspect.
struct FilterJointState {
  FilterStateVector mean = FilterStateVector::Zero();
  FilterStateMatrix covariance = FilterStateMatrix::Zero();
};

/// One step's transition of a joint block, kept for the RTS smoother:
/// predicted mean x_k|k−1, filtered state, and the process model's F (identity
/// but for b's row, and tau's on a release) and diagonal Q that produced the
/// prediction.
struct FilterTransition {
  FilterStateVector predicted_mean = FilterStateVector::Zero();
  double f_torque_torque = 1.0;     ///< ∂tau+/∂tau: 0 when a release restarts the load
  double f_torque_scale = 0.0;      ///< ∂tau+/∂s: the held load following the motor
  double f_backlash_torque = 0.0;   ///< ∂b+/∂tau
  double f_backlash_backlash = 1.0; ///< ∂b+/∂b
  double f_backlash_clearance = 0.0;  ///< ∂b+/∂e
  FilterStateVector process_noise = FilterStateVector::Zero();  ///< diag Q
  /// < 1: the tip was seated and SeatingBound(P, this) came before F·P·Fᵀ + Q.
  double seating_bound_weight = 1.0;
  bool predicted = false;           ///< false on the first sample (prior only)
};

class ComplianceFilter {
 public:
  /// Throws std::invalid_argument when the parameters fail
  /// models::ValidateParameters or the options fail IsValid (with the reason).
  ComplianceFilter(const models::ModelParameters& parameters, const FilterOptions& options = {});
  ~ComplianceFilter();
  ComplianceFilter(const ComplianceFilter&);
  ComplianceFilter& operator=(const ComplianceFilter&);
  ComplianceFilter(ComplianceFilter&&) noexcept;
  ComplianceFilter& operator=(ComplianceFilter&&) noexcept;

  /// Advances one control period. Never allocates, never throws.
  FilterEstimate Step(const FilterSample& sample) noexcept;

  /// Back to the prior (the next Step initialises from its sample).
  void Reset() noexcept;

  const FilterOptions& options() const;
  /// Joint j's (0 or 1) state after the last Step.
  const FilterJointState& joint_state(int joint) const;
  /// Joint j's transition in the last Step.
  const FilterTransition& transition(int joint) const;

  /// Samples the state runs behind Step's newest sample: the inertial
  /// torque's alignment (FilterOptions::align_inertial_torque), 0 without
  /// motor inertia. Step's estimate is always of its own sample, carried
  /// forward from the state's (CarryEstimate); joint_state() and transition()
  /// are of state_sample().
  int alignment_steps() const;
  /// Whether the last Step (or StepHeldSample) advanced the state by a sample.
  bool advanced() const;
  /// The sample the state is at, and its estimate before carrying and the
  /// output step limit (what the smoother records).
  const FilterSample& state_sample() const;
  const FilterEstimate& state_estimate() const;
  /// Processes the oldest sample the alignment still holds back, with the
  /// acceleration as it is now; false when none is left. For the end of a
  /// log (the smoother); a control loop never needs it.
  bool StepHeldSample() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether a held tip's load has pressed a joint's shaft against a wall since
/// the tip was seated (FilterOptions::clearance_needs_a_wall). The shaft's start
/// in its clearance is uniform, which the filter's Gaussian cannot hold: until
/// a wall is reached the travel says as much about the start as about the
/// clearance. From a wall on, the start is known.
struct ClearanceWalls {
  /// A load holds the shaft on its wall from this hold g (BacklashHold) up.
  static constexpr double kPressedHold = 0.99;
  bool pressed = false;
  void Seat() { pressed = false; }
  /// hold: BacklashHold of the load the filter is sure of.
  void Observe(double hold) { pressed = pressed || hold >= kPressedHold; }
  /// The encoder may teach e.
  bool TeachClearance() const { return pressed; }
};

/// True while the sample at elapsed_s from the log's first lies in the span
/// FilterOptions::unloaded_start_s says the instrument was unloaded.
inline bool InUnloadedStart(const FilterOptions& options, double elapsed_s) {
  return elapsed_s < options.unloaded_start_s;  // NaN: false
}

/// The part of a load estimate tau (N·m, variance in N·m²) that the filter is
/// sure of: tau moved toward 0 by options.load_margin_sd standard deviations,
/// 0 when it would cross zero.
double SureLoad(const FilterOptions& options, double tau_nm, double tau_variance_nm2);
/// The dead-zone width w (N·m) the filter uses for a joint: the parameters'
/// deadzone_width_nm (tau_min_nm when that is 0), never below
/// options.backlash_width_noise_multiple × the effort noise — an identified
/// width of 0.02 N·m under 0.01 N·m of noise would let noise throw the shaft
/// from wall to wall.
double FilterDeadZoneWidth(const FilterOptions& options, const models::JointParameters& joint);
/// The factor on the encoder's ∂h/∂s = K·tau: SureLoad / tau (0 at tau = 0) ×
/// BacklashHold(SureLoad, w)^scale_hold_exponent, w the joint's dead-zone
/// width (N·m): s learns from the sure load alone, and only while that load
/// holds the shaft on its wall.
double ScaleLearningFraction(const FilterOptions& options, double tau_nm, double tau_variance_nm2,
                             double width_nm);

/// The load's process variance (N·m²) in one step of dt with the tip held, under
/// options.bound_held_load_rate: with q_b = min(σ_τ̇²·dt, σ_rest²·dt +
/// (m·Δq/(s·K))² + (J·θ̈)²·dt/T_a), it is (1 − g)·σ_τ̇²·dt + g·q_b for the hold
/// g ∈ [0, 1] of the load on its wall (BacklashHold), the motor's recent
/// increment Δq (rad, MotorMotion::increment_peak_rad), compliance s·K(L)
/// (rad/N·m, floored at 10⁻⁶) and inertial torque J·θ̈ (N·m). σ_τ̇²·dt with
/// the option off.
double HeldLoadProcessVariance(const FilterOptions& options, double dt, double encoder_increment,
                               double compliance_rad_per_nm, double inertial_torque_nm,
                               double hold);

/// The load a held tip's motor adds in one step (N·m): the encoder increment
/// Δq (rad) bends a shaft held on its wall by g·Δq (hold g in [0, 1]; inside
/// the clearance the rest moves b), so tau moves by g·Δq/(s·K(L)), K(L) in
/// rad/N·m. Templated so that the filter's Jacobian (∂/∂s) comes from Jets;
/// shared with the bench's dense baselines.
template <typename T>
T HeldLoadIncrement(double hold, double encoder_increment_rad, const T& scale,
                    double compliance_rad_per_nm) {
  return hold * encoder_increment_rad / (scale * compliance_rad_per_nm);
}

/// The effort's variance (N·m²) with the tip held: σ_effort² + (κ·J·θ̈)²,
/// κ = inertial_torque_error, J·θ̈ the fitted inertial torque (N·m).
double HeldEffortVariance(const FilterOptions& options, double inertial_torque_nm);

/// The fraction r of its wall an unloaded shaft forgets in a step of dt with
/// this encoder increment: 1 − e^(−dt/T), weighted by min(1, |Δq|/3 counts).
double BacklashRelax(const FilterOptions& options, double dt, double encoder_increment);

/// The variance b's process adds in one step of dt (before BoundBacklashVariance),
/// for load saturation S = S(tau/w), relax r (BacklashRelax) and clearance δ:
/// unloaded diffusion, the transit's uncertain pull, and σ_pinned.
double BacklashProcessVariance(const FilterOptions& options, double dt, bool tip_fixed,
                               double relax, double saturation, double delta_rad);

/// How b's variance is kept inside its clearance (b lives in ±(δ + e)) in one
/// prediction: `row_scale` multiplies b's row of F, `process_variance` is the
/// variance b's process adds. Free tip: at most the uniform's (δ² + σ_δ²)/3 =
/// `prior_variance`, whether it came from F·P·Fᵀ (`propagated_variance`, b's
/// diagonal entry before scaling: a noisy load near zero whose sign flips
/// feeds its doubt into b through ∂b+/∂tau sample after sample) or from the
/// process — the scale shrinks b's correlations with it, so the tip, read as
/// q_enc − b, is never more uncertain than the clearance makes it. Held tip:
/// neither is bounded. The encoders see tip + b there, so b's variance stays
/// below the tip's anyway, and b's process noise is what lets a shaft that
/// moves across its clearance move b rather than the held tip: with the tip
/// and b anticorrelated from the free approach (ρ ≈ −1), a cap that withheld
/// the noise once Var b reached δ²/3 froze that correlation, and the encoder
/// then moved the held tip with the shaft — and b the other way
/// (docs/filter.md, "Keeping b in its clearance").
struct BacklashVarianceBound {
  double row_scale = 1.0;
  double process_variance = 0.0;
};
BacklashVarianceBound BoundBacklashVariance(bool tip_fixed, double propagated_variance,
                                            double process_variance, double prior_variance);

/// A covariance bound for the moment a free tip is seated: the load's block
/// (row and column kStateTorque) is made uncorrelated with the rest, the rest
/// scaled by 1/ω and the load's variance by 1/(1 − ω). The result minus P is
/// positive semi-definite for any ω in (0, 1) (the two-block covariance
/// intersection bound), so the filter stays conservative; the mean is kept.
/// ω ≥ 1 leaves P as it is.
void SeatingBound(FilterStateMatrix* covariance, double weight);

/// The motor's velocity and acceleration from encoder increments: a
/// fading-memory quadratic fit to the encoder angle (Morrison's degree-2
/// filter, a critically damped α-β-γ tracker), memory time constant
/// T = options.acceleration_filter_time_s (θ = exp(−dt/T) per sample). Exact
/// on a quadratic angle; under a constant jerk the acceleration is about 2.9 T
/// late (12 ms at the default 4 ms, the same encoder-count flicker as the
/// two 10 ms low-pass stages it replaces, which were 20 ms late).
/// Allocation-free, constant time, no throw.
struct MotorMotion {
  /// How late the acceleration is under a constant jerk, s, for these
  /// options' T and sample period (run on a cubic angle until settled).
  static double LagSeconds(const FilterOptions& options);
  double velocity_rad_s = 0.0;
  double acceleration_rad_s2 = 0.0;
  double position_offset_rad = 0.0;  ///< fitted angle − last encoder reading
  /// The largest |encoder increment| of recent samples (rad), each fading by
  /// e^(−dt/options.held_load_motion_window_s) a sample: how far the motor may
  /// have bent a held shaft in one sample (HeldLoadProcessVariance).
  double increment_peak_rad = 0.0;
  double peak_fade_dt_s = -1.0, peak_fade = 0.0;  ///< e^(−dt/window) for the last dt
  void Advance(const FilterOptions& options, double dt, double encoder_increment);
  /// J·θ̈ (N·m), never beyond the effort limit: no motor accelerates faster
  /// than its largest effort can drive it, and an encoder outlier must not
  /// become a large torque.
  double InertialTorque(const FilterOptions& options) const;
};

/// The standard deviation of a named parameter ("joint1.backlash_rad") from
/// the parameters' covariance; NaN when they carry none or not that name.
double ParameterStandardDeviation(const models::ModelParameters& parameters,
                                  const std::string& name);

/// The output quantities of a joint-block pair, computed the same way for the
/// filter and the smoother: corrected angles, covariance, tip correction.
FilterEstimate MakeEstimate(const FilterJointState& joint1, const FilterJointState& joint2,
                            const Eigen::Vector2d& encoder_rad, double insertion_depth_m);

/// An estimate of the state at sample `from` carried to the newer sample `to`
/// (the inertial alignment): a joint whose tip is held at both stays where it
/// is; otherwise the tip moves with the encoder (the shaft's own change over
/// the alignment's ~12 ms is left to the state's next update: σ_free, the
/// filter's process noise of a free tip, is a bound for the filter, not for
/// this shift, and would give a free tip NEES 0.2 instead of 2). The tip
/// correction is recomputed at `to`'s encoders and `depth_m`.
void CarryEstimate(const FilterSample& from, const FilterSample& to, double depth_m,
                   FilterEstimate* estimate);

/// The corrected angle a control loop sees: it follows the estimate but moves
/// at most `limit_rad[j]` in a step (FilterOptions::output_step_limit_counts
/// beyond the encoder's change), and its MSE adds the gap it leaves.
class OutputStepLimiter {
 public:
  /// The next output toward `estimate` (its filtered_rad and corrected_rad are
  /// the filter's mean on entry). `restart[j]`: joint j's output jumps to the
  /// estimate (first sample, a release, a re-acquisition: the world changed).
  /// Then corrected_rad, covariance_rad2, the tip correction and
  /// kFlagOutputLimited describe the limited output.
  void Apply(const Eigen::Vector2d& limit_rad, const bool restart[2], const Eigen::Vector2d& encoder_rad,
             double insertion_depth_m, FilterEstimate* estimate);

 private:
  Eigen::Vector2d output_{0.0, 0.0};
};

}  // namespace pliant::estimation
