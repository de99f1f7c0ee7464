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
#include "pliant/estimation/filter_process_model.h"
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
  double f_offset_offset = 1.0;     ///< ∂β+/∂β: exp(−dt/τβ) (effort_offset_correlation_s)
  FilterStateVector process_noise = FilterStateVector::Zero();  ///< diag Q
  /// < 1: the tip was seated and SeatingBound(P, this) came before F·P·Fᵀ + Q.
  double seating_bound_weight = 1.0;
  bool predicted = false;           ///< false on the first sample (prior only)
};

/// Why these options cannot filter with these parameters ("" when they can):
/// FilterOptions::motor_inertia_kg_m2 beside a file's joint_inertia would
/// take J·θ̈ out of a held tip's effort twice.
std::string OptionsAgainstParameters(const models::ModelParameters& parameters,
                                     const FilterOptions& options);

class ComplianceFilter {
 public:
  /// Throws std::invalid_argument when the parameters fail
  /// models::ValidateParameters or the options fail IsValid or
  /// OptionsAgainstParameters (with the reason).
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
  /// The prior σ of joint j's clearance error e (rad) and compliance scale s:
  /// how far the file's δ and K may be off before the log says so.
  Eigen::Vector2d instrument_prior_sd(int joint) const;
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


/// The standard deviation of a named parameter ("joint1.backlash_rad") from
/// the parameters' covariance; NaN when they carry none or not that name.
double ParameterStandardDeviation(const models::ModelParameters& parameters,
                                  const std::string& name);
/// An option's σ when it is given (finite), else the parameters' covariance
/// of the named parameter, else the fallback: how FilterOptions' NaN
/// ("from the parameters") σ are resolved, by the filter and the baselines.
double ResolvedStandardDeviation(double option_sd, const models::ModelParameters& parameters,
                                 const std::string& name, double fallback);

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
