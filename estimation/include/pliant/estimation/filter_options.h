#pragma once
// The online filter's options (filter.h): noise levels, priors, gates, the
// mismatch test and the switches of its model, each with why it is set as it
// is. FilterOptions::IsValid (filter_options.cpp) checks them before a filter
// is built.

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Core>

namespace pliant::estimation {

/// Noise levels, gates and the mismatch test. Defaults: a Classic PSM at
/// 1.5 kHz (reference/dvrk.md) with the simulator's sensor noise.
struct FilterOptions {
  double sample_period_s = 1.0 / 1500.0;  ///< used when t does not give one
  // Measurement noise (standard deviations).
  double encoder_noise_rad = 7.7e-6 / 3.4641016151377544;  ///< one count / √12
  double effort_noise_nm = 0.01;
  /// On a log (FilterLog, `pliant filter --effort-noise-from-log`):
  /// effort_noise_nm raised to the log's own white noise where that is larger
  /// (EffortNoiseForLog, which notes it either way). Off by default: told the
  /// noise of a log three times noisier than assumed, the filter rejects no
  /// held row (2,246 of 22,400 with 0.01 N·m) but without tip_fixed believes
  /// each push later (joint 1 3.31 → 4.68 mrad; docs/decisions/effort-noise.md).
  bool effort_noise_from_log = false;
  double reference_noise_rad = 5e-5;   ///< a sample's reference_rad (an optical tracker)
  /// A log's q1_ref, q2_ref columns as measurements of the tip (σ
  /// reference_noise_rad). Off: they only score the output. A validation
  /// log's tracker is what the corrected joints are compared with; fused with
  /// a σ it does not have (a tracker of 0.3 mrad read as 0.05), it was
  /// rejected on most rows and shrank q_sd 30-fold below the error.
  bool fuse_log_reference = false;
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
  /// covered 91 % (docs/decisions/0006-filter-load-follows-the-motor.md).
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
  /// off by 2.1 σ for the whole hold; docs/decisions/
  /// 0007-filter-effort-offset-tare-and-clearance-from-a-wall.md). false: e learns from
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
  /// it, 0.05 with it: DeflectionModelError(); docs/decisions/
  /// 0005-filter-shaft-damping-and-deflection-error.md).
  /// 0 (the default): none; the simulator's instrument has 0.02.
  double shaft_damping_nm_s_per_rad = 0.0;
  double acceleration_filter_time_s = 0.004;
  /// κ: the error of the fitted inertial torque as a fraction of it, effort
  /// variance (κ·J·θ̈)² with the tip held (where J·θ̈ is taken out). Why:
  /// the fit misreads the sharp accelerations of a stepped arm (the clamped
  /// sweeps' 0.25 mm steps) by a share of J·θ̈ that the white effort noise
  /// did not allow, and each step's misread moved s and the held tip
  /// (clamped study: joint 1 covered 88.6 %, with κ 0.3 94.9 %; docs/
  /// decisions/0006-filter-load-follows-the-motor.md). 0: the fit is exact.
  double inertial_torque_error = 0.3;
  /// With motor inertia (J > 0), run the filter's state that many samples
  /// behind the newest one that the fitted acceleration's lag (under a
  /// constant jerk, MotorMotion::LagSeconds: 11.7 ms, 18 samples, at the
  /// defaults) lines up with the effort it is taken out of; Step() carries the
  /// estimate forward to the newest sample (CarryEstimate). Why: the effort
  /// holds J·θ̈ now, the fit knows θ̈ of ~12 ms ago; in the clamped-beam sweeps
  /// (8 Hz arm oscillation after each step) that misfit was 2–3 times the
  /// effort noise, correlated over a move, and dragged the compliance scale
  /// and the held tip (docs/decisions/0002-filter-inertial-torque-alignment.md).
  /// The count of samples is the lag over sample_period_s: a log at another
  /// rate than the PSM's 1.5 kHz needs that period set to line up.
  /// false: process each sample as it comes (the inertial torque then lags).
  bool align_inertial_torque = true;
  /// ε, the relative error of the deflection model, as encoder variance
  /// (ε·K·tau)²: what the effort model lacks. Calibrated on the simulator,
  /// its motor inertia given: with its shaft damping given too, 0.05 puts the
  /// paper's pushes and continuous loads inside their NEES bands; without,
  /// the damping is part of what ε covers, and 0.08 keeps the paper's pushes
  /// inside (docs/decisions/0005-filter-shaft-damping-and-deflection-error.md;
  /// 0.075 without bound_held_load_rate). NaN (the default): DeflectionModelError() picks
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
  /// 2.05, inside its band (docs/decisions/0003-filter-compliance-scale-learns-on-the-wall.md).
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
  /// σ_w per joint (N·m): how well the parameters know the dead-zone width,
  /// the take-up's shape. NaN (the default): the parameters' covariance of
  /// "jointN.deadzone_width_nm" when they carry one, else 0 (exact). The
  /// take-up then teaches e no better than δ·σ_w/w (ClearanceLearnable).
  Eigen::Vector2d deadzone_width_sd_nm{kFromParameters, kFromParameters};
  /// σ_β per joint (N·m): a constant offset the bias torque tau0 may miss.
  /// 0 (the default): off, the bias torque is taken as exact. NaN: the
  /// parameters' covariance of "jointN.bias_torque.coefficients[0]" (the
  /// Fourier mean) when they carry one, else kDefaultEffortOffsetSdNm.
  /// β's mean moves only with a reference (q_ref): to the encoder and the
  /// effort it is a consider state, whose doubt flows into q_tip through
  /// s·K(L). Off by default: learned, β made the divot and clamped-beam tips
  /// worse and their corrected angles jumpy; as a consider state it is worse
  /// still on those logs (divot 0.277 mm against 0.037 off, with σ_β from
  /// identification; docs/decisions/
  /// 0007-filter-effort-offset-tare-and-clearance-from-a-wall.md). Turn it
  /// on with a reference, or to study its doubt.
  Eigen::Vector2d effort_offset_sd_nm{0.0, 0.0};
  double effort_offset_rate_nm = 0.0;     ///< σ_β̇, N·m/√s (0: a constant offset)
  /// τβ per joint (s): finite makes β a first-order Gauss–Markov process
  /// (AR(1) at each step, ρ = exp(−dt/τβ)) that keeps σ_β as its stationary
  /// σ: an effort noise correlated over τβ (a current loop's filter, a drive's
  /// ripple), which a white noise model averages down over a hold as if each
  /// sample were new. As a consider state β's mean stays 0 and its doubt flows
  /// into the held tip. Infinity (the default): a constant offset. On a log,
  /// effort_colour_from_log sets it with σ_β where the log shows such noise.
  /// docs/decisions/coloured-effort-noise.md.
  Eigen::Vector2d effort_offset_correlation_s{std::numeric_limits<double>::infinity(),
                                              std::numeric_limits<double>::infinity()};
  /// On a log (FilterLog): where the efforts over the log's still stretches
  /// hold noise correlated over more than a sample (EffortNoiseColourFromStill)
  /// and β is otherwise off (σ_β 0, no tare, no fused reference), β carries
  /// it: σ_β and τβ per joint from the log, said in the summary's notes.
  bool effort_colour_from_log = true;
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
  // Contact, for samples without the tip_fixed hint (docs/decisions/contact-prior.md).
  /// true: without tip_fixed, contact is the exception. The external load is
  /// 0 (no contact) or a slab N(·, σ_c²) (contact), a two-state Markov chain
  /// with rates λ_on, λ_off; each effort update ends with the Gaussian-sum
  /// collapse of the two (FilterEstimate::contact_probability). The effort's
  /// unmodelled internal torque (inertia, friction, the bias table's error)
  /// is effort noise σ_u, learned from the log's no-contact rows. false: the
  /// whole effort residual is load (a held tip's model, for every sample).
  bool infer_contact = true;
  double contact_start_rate_hz = 0.1;  ///< λ_on, 1/s: a contact every 10 s on average
  double contact_end_rate_hz = 0.5;    ///< λ_off, 1/s: a contact lasts 2 s on average
  /// true: λ_on and λ_off above are the prior (worth one episode of each kind)
  /// of rates learned from the log's own contacts, over the last
  /// contact_rate_memory_s of the chain's time (docs/decisions/contact-rates.md).
  /// Continuous logs only. false: the rates stay fixed.
  bool learn_contact_rates = true;
  double contact_rate_memory_s = 60.0;
  double contact_load_sd_nm = 1.0;     ///< σ_c, N·m: the spread of a contact's load
  /// σ_u² = σ_rest² + m·σ_moving², m = min(1, |θ̇|/unmodelled_effort_speed):
  /// at rest the bias table's own error (σ_rest, fixed); moving, the arm's
  /// inertia and friction besides (σ_moving, learned from the log's moving
  /// no-contact rows; this its prior, generous: the filter doubts a moving
  /// arm's effort until the log shows how well the bias table explains it).
  double unmodelled_effort_sd_nm = 0.05;         ///< σ_rest, N·m
  double moving_effort_sd_nm = 0.3;              ///< σ_moving's prior, N·m
  double unmodelled_effort_speed_rad_s = 0.1;    ///< the speed from which the arm counts as moving
  /// ν: a moving arm's unmodelled torque is Student-t with ν degrees of
  /// freedom (heavy tails: a spike of inertia or stiction is not a contact).
  double moving_effort_dof = 4.0;
  /// The memory of σ_moving's estimate, s.
  double unmodelled_effort_memory = 2.0;
  /// The moving arm's own torque, learned online from no-contact rows (RLS):
  /// J·θ̈ + f·tanh(θ̇/v_f) + c·θ̇ + τ_b, each coefficient from 0 with these prior σ;
  /// the past fades with internal_torque_memory_s.
  double internal_inertia_sd_kg_m2 = 0.3;
  double internal_coulomb_sd_nm = 0.3;
  double internal_viscous_sd_nm_s = 0.3;
  double internal_bias_error_sd_nm = 0.1;  ///< τ_b: the bias table's mean error along the path
  double coulomb_speed_rad_s = 0.05;  ///< v_f
  double internal_torque_memory_s = 30.0;
  /// The free level (continuous logs without the hint): where the free arm
  /// settles, its effort's residual beyond the learned torque (the bias
  /// table's error at that pose, σ_rest at the start) is learned as a field
  /// over the pose, so that a load that comes while the arm stands there is
  /// told from the table's error by its change, not by its size against σ_rest
  /// (docs/decisions/contact-free-level.md). The field's correlation lengths
  /// over the joints' angles (rad) and the insertion (m), and its drift in
  /// time at one pose (N·m/√s).
  bool free_level = true;
  double free_level_length_rad = 0.1;
  double free_level_depth_length_m = 0.02;
  double free_level_drift_nm = 0.001;
  // Never diverge (docs/decisions/reinitialise.md).
  /// A step of more than this between two rows is a time gap: the tip and the
  /// load are re-initialised (kFlagReinitialised), s.
  double time_gap_s = 0.1;
  /// One row per pose (a log with "# timing: quasi-static"): t is a pose index,
  /// read for nothing; each row is a static measurement of the same
  /// instrument (the tip of a free row and every row's load start again from
  /// their priors; s, e, β and the shaft's offset carry over; without the
  /// tip_fixed hint a contact goes on from pose to pose, judged by whether the
  /// load follows the encoder: docs/decisions/contact-prior.md).
  bool quasi_static = false;
  /// Joints the log records (LogHeader::JointRecorded): an unrecorded joint
  /// keeps its prior, flags nothing missing, and its output is NaN.
  bool joint_recorded[2] = {true, true};
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

}  // namespace pliant::estimation
