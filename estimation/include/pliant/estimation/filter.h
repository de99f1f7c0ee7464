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
//   q_enc_j  = q_tip_j + b_j + s_j·K_j(L)·tau_j + D_j(tau_1, tau_2)   (ComplianceEffect;
//            D_j: the parameters file's deflection effects at the row's inputs)
//            variance σ_enc² + (ε·K_j(L)·tau_j)² + (∂D_j/∂tau_i)²·P_i(tau, tau),
//            i ≠ j, ε = deflection_model_error
//   tau_meas_j − tau0_j(q_enc, L) − J·θ̈_j − (the file's internal-torque effects)
//            = tau_j + beta_j  (bias torque; J·θ̈ with the tip held, MotorMotion)  σ_effort
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
// Jacobians come from ceres::Jet. The joints share no state, so the filter
// runs two blocks of 6 states with sequential scalar updates (Joseph form);
// q12_cov is zero. A deflection effect that couples the joints (D_1 reads
// tau_2) takes the other joint's tau at its estimate, a consider input whose
// variance is the last term of the encoder's (docs/filter.md, "The model").
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

#include "pliant/estimation/filter_options.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// One control period's input. NaN marks a missing value.
struct FilterSample {
  double time_s = 0.0;
  Eigen::Vector2d encoder_rad{0.0, 0.0};      ///< q1, q2
  double insertion_depth_m = 0.15;            ///< q3
  Eigen::Vector2d effort_nm{0.0, 0.0};        ///< tau1, tau2
  Eigen::Vector2d reference_rad{kMissing, kMissing};  ///< q1_ref, q2_ref
  bool tip_fixed = false;                     ///< the tip is clamped or in a divot
  /// v1, v2 (rad/s) where the log has them, for the file's effects (EffectInputs).
  Eigen::Vector2d velocity_rad_s{kMissing, kMissing};

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
  /// The process model could not bridge this step (an encoder step faster than
  /// any joint moves, a time gap beyond FilterOptions::time_gap_s, the first
  /// sample after missing ones): a free tip restarted at the encoder with the
  /// prior's doubt, the load's doubt widened (docs/decisions/reinitialise.md).
  kFlagReinitialised = 1u << 8,
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
  /// The probability that something touches the instrument, per joint: 1 with
  /// the tip_fixed hint, else the contact chain's (FilterOptions::infer_contact).
  Eigen::Vector2d contact_probability{1.0, 1.0};
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
  /// A hold the tip_fixed hint began (or a release began anew): its shaft's
  /// start is the uniform one below. Never set without the hint, whose
  /// contacts have no seat to forget from.
  bool seated = false;
  void Seat() {
    pressed = false;
    seated = true;
  }
  /// hold: BacklashHold of the load the filter is sure of. True at the
  /// first press since a seat: the tip's variance then gains
  /// ForgottenStartVariance, so that it forgets where the shaft started.
  bool Observe(double hold) {
    const bool first = !pressed && hold >= kPressedHold;
    pressed = pressed || first;
    return first && seated;
  }
  /// The encoder may teach e.
  bool TeachClearance() const { return pressed; }
  /// The tip's added variance at the first press, rad², from the start's
  /// prior variance (δ² + σ_δ²)/3. The start is uniform in ±(δ + e); the
  /// Gaussian prior on b held it as information about the held tip (tip + b
  /// is the encoder), which put the tip near the middle when the shaft began
  /// near a wall of a wide clearance (1.5 kHz family study: joint 2 covered
  /// 91 %). From the wall on the tip is the encoder less the wall and the
  /// bend; a hundred of the start's variances leave the start about 1 % of
  /// its weight (docs/decisions/forget-the-start-at-the-wall.md).
  static double ForgottenStartVariance(double start_variance_rad2) {
    return 100.0 * start_variance_rad2;
  }
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

/// The shaft confined to its cannula: the clearance's error e (rad) to [−δ, δ]
/// (a clearance is never negative nor twice the nominal δ, rad), then the
/// shaft's place b (rad) to ±(δ + e). The filter's and the dense baselines' one wall.
void ConfineToClearance(double nominal_clearance_rad, double* clearance_error_rad,
                        double* backlash_rad);

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
  double pole_dt_s = -1.0, pole = 0.0;  ///< θ = e^(−dt/options.acceleration_filter_time_s)
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
