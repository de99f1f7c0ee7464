#pragma once
// The online filter's process model, piece by piece: the state's layout, the
// shaft in its clearance, the held load's growth, the motor's motion. Each
// piece is evaluated by the filter (filter_predict.cpp), the RTS smoother and
// the dense baselines in bench/ alike (filter_process_model.cpp defines them);
// filter.h is the filter's contract and includes this.

#include <Eigen/Core>

#include "pliant/estimation/filter_options.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// States per joint block, and their order.
constexpr int kFilterJointStates = 6;
enum FilterStateIndex {
  kStateTip = 0, kStateTorque, kStateBacklash, kStateScale, kStateClearance, kStateEffortOffset
};
using FilterStateVector = Eigen::Matrix<double, kFilterJointStates, 1>;
using FilterStateMatrix = Eigen::Matrix<double, kFilterJointStates, kFilterJointStates>;

/// Whether a held tip's load has pressed a joint's shaft against a wall since
/// the tip was seated (FilterOptions::clearance_needs_a_wall). The shaft's start
/// in its clearance is uniform, which the filter's Gaussian cannot hold: until
/// a wall is reached the travel says as much about the start as about the
/// clearance. From a wall on, the start is known.
struct ClearanceWalls {
  /// A load holds the shaft on its wall from this hold g (BacklashHold) up.
  static constexpr double kPressedHold = 0.99;
  bool pressed = false;
  /// This step's load may teach e (ClearanceLearnable).
  bool learnable = false;
  /// A hold the tip_fixed hint began (or a release began anew): its shaft's
  /// start is the uniform one below. Never set without the hint, whose
  /// contacts have no seat to forget from.
  bool seated = false;
  void Seat() {
    pressed = learnable = false;
    seated = true;
  }
  /// hold: BacklashHold of the load the filter is sure of; learns: whether
  /// that load may teach e (ClearanceLearnable). True at the first press
  /// since a seat: the tip's variance then gains ForgottenStartVariance, so
  /// that it forgets where the shaft started.
  bool Observe(double hold, bool learns) {
    const bool first = !pressed && hold >= kPressedHold;
    pressed = pressed || first;
    learnable = learns;
    return first && seated;
  }
  /// The encoder may teach e: a wall was pressed since the seat, and this
  /// step's load may teach it.
  bool TeachClearance() const { return pressed && learnable; }
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
/// Whether a held tip's encoder may teach the clearance error e at this sure
/// load (N·m), for a dead-zone width w ± σ_w (N·m) and clearance δ (rad) whose
/// error e has variance P_ee (rad²). Inside the take-up the shaft's place
/// δ·S(τ/w) moves with w: S(τ/w) ≈ τ/w there, so a width off by σ_w moves it by
/// the share σ_w/w of the way, as an error of δ·σ_w/w in e would, on every
/// sample alike. The take-up then teaches e until P_ee is down to
/// (δ·σ_w/w)², and no further. From |load| ≥ w + m·σ_w on (m = load_margin_sd)
/// the shaft is on its wall whatever the width, and e always learns. σ_w = 0
/// (a width known exactly): always (docs/decisions/
/// take-up-teaches-the-clearance-as-far-as-its-width-is-known.md).
bool ClearanceLearnable(const FilterOptions& options, double sure_load_nm, double width_nm,
                        double width_sd_nm, double clearance_rad, double clearance_variance_rad2);
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

}  // namespace pliant::estimation
