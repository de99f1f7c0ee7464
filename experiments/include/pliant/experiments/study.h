#pragma once
// A Monte Carlo accuracy study (docs/montecarlo.md): which instruments, noise
// and contacts to draw, how many trials, and the seed. Read from JSON
// (experiments/studies/*.json); unknown keys and bad values are io::InputError
// at their line, naming the key.
//
// Trial k's random stream depends on (seed, k) alone (TrialStream), so a trial
// draws the same instrument, noise and contact whichever thread or MPI rank
// runs it.
//
//   const auto study = pliant::experiments::ReadStudy("experiments/studies/divot_study.json");
//   TrialStream stream(study.seed, 7);
//   const TrialDraw draw = DrawTrial(study, stream);

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "pliant/experiments/scenario.h"
#include "pliant/models/parameters.h"

namespace pliant::experiments {

/// One sampled quantity. Every distribution consumes exactly one uniform
/// number u of the trial's stream and returns its quantile at u (Boost.Math),
/// so adding or changing one distribution never shifts the others' draws.
struct Distribution {
  enum class Kind { kConstant, kUniform, kNormal, kLogNormal };
  Kind kind = Kind::kConstant;
  double a = 0.0;  ///< constant: value; uniform: min; normal: mean; lognormal: median
  double b = 0.0;  ///< uniform: max; normal: sd; lognormal: sd of the log
  double lower = -1e300, upper = 1e300;  ///< the quantity's physical range: draws are clamped to it
  /// The quantile at u in (0, 1), clamped to [lower, upper].
  double Quantile(double u) const;
  bool Varies() const {
    return kind == Kind::kUniform ? b > a : kind != Kind::kConstant && b > 0.0;
  }
};

/// The quantities a trial draws, in the order it draws them (their names are
/// the CSV columns and the keys of the sensitivity breakdown).
enum SampledQuantity {
  kComplianceScale1,  ///< true K1(L) = scale · nominal K1(L)
  kComplianceScale2,
  kBacklash1Rad,      ///< true δ1
  kBacklash2Rad,
  kBiasOffset1Nm,     ///< added to the true tau0_1(q): the nominal bias misses it
  kBiasOffset2Nm,
  kEffortNoiseSdNm,   ///< the effort sensor's noise
  kDepthM,            ///< insertion depth of the push
  kDirectionDeg,      ///< push direction in the (tau1, tau2) plane
  kPeakTorqueNm,      ///< divot: the push's peak; clamped beam: the sweep's effort limit
  kSpeedRadS,
  /// Where each shaft starts in its clearance, a share of the drawn clearance
  /// in [−1, 1] (0: the middle, the simulator's default). Drawn after the
  /// simulation seed and the NEES pick, and only when not constant, so that
  /// a study without it draws what it drew before.
  kShaftStart1,
  kShaftStart2,
  kSampledQuantities
};

/// "compliance_scale1", "backlash1_rad", … (CSV column names).
const char* SampledQuantityName(int quantity);

struct Study {
  std::string name;  ///< the file's stem
  std::string description;
  std::string scenario_path;             ///< resolved against the study file's folder
  std::vector<std::string> scenario_set;  ///< "key=value" overrides of the scenario
  /// The base scenario, overrides applied: a divot (one push per trial) or a
  /// clamped beam (one sweep per trial at the drawn depth, stepping until
  /// |effort| reaches the drawn peak torque; direction and speed unused).
  Scenario scenario;
  Distribution quantities[kSampledQuantities];
  /// Identify each trial's parameters on a simulated calibration of its own
  /// instrument first; else use the nominal ones.
  bool identify = false;
  /// How: the joint smoother (`pliant identify`'s method on timed logs), or
  /// the paper's procedure, whose σ are its lines' scatter and cover the
  /// truth on none of its numbers (docs/validation.md section 2).
  enum class IdentifyMethod { kSmoother, kPaper };
  IdentifyMethod identify_method = IdentifyMethod::kSmoother;
  /// The calibration's experiments (e.g. a short bias sweep and a clamped
  /// beam), each simulated with the trial's truth; their files' texts enter
  /// the fingerprint.
  std::vector<Scenario> calibration;
  /// A free-motion experiment of the study's arm (its `joint` is the
  /// scenario's; none or one): simulated once, the arm's dynamics are
  /// identified on it as a lab identifies its own arm (`pliant identify
  /// --effect joint_inertia --effect joint_friction`, IdentifyArmDynamics) and
  /// every trial's parameters carry them, with their σ.
  std::vector<Scenario> arm_calibration;
  std::vector<models::EffectParameters> arm_effects;
  /// The filter's and smoother's deflection-model error ε
  /// (estimation::FilterOptions::deflection_model_error); NaN: the filter's
  /// default for the arm (0.04 with the shaft's damping, else 0.08).
  double deflection_model_error = std::numeric_limits<double>::quiet_NaN();
  /// FilterOptions::load_follows_motor and inertial_torque_error (κ); the
  /// filter's defaults (true; NaN: 0.3) unless the study's "filter" sets them.
  bool load_follows_motor = true;
  /// FilterOptions::infer_contact (the filter's default, true, unless the
  /// study's "filter" sets it).
  bool infer_contact = true;
  /// false: the filter and smoother are not told which rows hold the tip (the
  /// log's tip_fixed column stays the truth the trial scores against), as
  /// online in a control loop, where nobody says the tip is held.
  bool tip_fixed_hint = true;
  double inertial_torque_error = std::numeric_limits<double>::quiet_NaN();
  /// FilterOptions' prior σ of the arm torque the filter learns without the
  /// hint (J kg·m², Coulomb N·m, viscous N·m·s/rad); NaN: the filter's (0.3 each).
  double internal_inertia_sd_kg_m2 = std::numeric_limits<double>::quiet_NaN();
  double internal_coulomb_sd_nm = std::numeric_limits<double>::quiet_NaN();
  double internal_viscous_sd_nm_s = std::numeric_limits<double>::quiet_NaN();
  /// FilterOptions::unloaded_start_s: the seconds at each simulated log's start
  /// with the tip free, the arm still and no load (0: none).
  double unloaded_start_s = 0.0;
  int trials = 100;
  std::uint64_t seed = 1;
  /// FNV-1a 64 of the study (without "trials") and of the scenario file's
  /// text: a results directory belongs to one fingerprint.
  std::uint64_t fingerprint = 0;
};

/// The arm's dynamics identified on the study's arm_calibration (empty
/// without one): the catalogue effects estimation::FittedFromFreeMotion.
std::vector<models::EffectParameters> IdentifyArmDynamics(const Study& study);

/// Reads a study file; throws io::InputError naming the file, line and key.
Study ReadStudy(const std::string& path);
Study ParseStudy(const std::string& text, const std::string& file);

/// SplitMix64 (Steele, Lea, Flood 2014): the trial's stream starts at
/// state = mix(mix(seed) + k·0x9E3779B97F4A7C15) and each draw advances the
/// state by that constant and returns mix(state).
class TrialStream {
 public:
  TrialStream(std::uint64_t study_seed, std::uint64_t trial);
  std::uint64_t Next();
  /// (Next() >> 11)·2⁻⁵³ + 2⁻⁵⁴: in (0, 1), never 0 or 1.
  double Uniform();

 private:
  std::uint64_t state_;
};

struct TrialDraw {
  double values[kSampledQuantities] = {};
  std::uint64_t simulation_seed = 0;  ///< the simulator's noise seed
  double nees_pick = 0.0;             ///< in (0, 1): which held sample gives the NEES
};

/// Draws the trial's quantities (in SampledQuantity order), then the two numbers above.
TrialDraw DrawTrial(const Study& study, TrialStream& stream);

}  // namespace pliant::experiments
