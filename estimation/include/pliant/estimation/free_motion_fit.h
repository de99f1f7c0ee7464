#pragma once
// The arm's own dynamics — the catalogue effects that read only the joints'
// motion (joint_friction, joint_inertia) — fitted where nothing touches the
// instrument, so that the effort's load is exactly zero and the effort
// beyond the bias table is the arm's own torque. `pliant identify --effect`
// fits them here when its logs hold free motion; the parameters file then
// carries them with σ, and the filter takes those σ as the doubt of the
// arm's torque it learns online (docs/decisions/arm-dynamics-from-free-motion.md).
//
//   const auto fit = FitEffectsOnFreeMotion({{&log, "bag.csv"}}, identified,
//                                           {"joint_inertia", "joint_friction"});
//   const auto with = WithFittedEffects(identified, fit.fitted, "pliant identify on bag.csv");
//
// Per row and joint: τ − τ₀(q, L) − (the file's other internal effects) =
// Σ effects(p, row) + the table's error along the path, in the catalogue's
// bias law (bias_torque_fourier from 0 with its prior: a nuisance, not
// written). The σ count each block of rows as one
// draw (a clustered sandwich, never below the white-noise covariance): the
// blocks are ten correlation times of the residual long, at least 1 s, so
// that neighbouring blocks' errors are nearly independent.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/effect_fit.h"
#include "pliant/io/log.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

struct FreeMotionFit {
  FittedEffects fitted;            ///< the effects, values ± sd, and their covariance
  std::vector<std::string> logs;   ///< the logs with free motion, which the fit used
  std::size_t rows = 0;            ///< free rows over those logs
  int blocks = 0;                  ///< the sandwich's clusters
  double block_s = 0.0;            ///< their length, s
  double correlation_s = 0.0;      ///< the residual's correlation time, s
  Eigen::Vector2d rms_before_nm{0.0, 0.0};  ///< τ − τ₀ about its mean, RMS per joint
  Eigen::Vector2d rms_after_nm{0.0, 0.0};   ///< … − the effects and the table's error
  std::vector<std::string> notes;
};

/// Whether the effect reads nothing of a row but the joints' motion
/// (velocity, acceleration; ChannelsOf) and adds to the effort: such an
/// effect is fitted from free motion, where its torque is all the effort
/// holds beyond the bias table.
bool FittedFromFreeMotion(const std::string& name);

/// Whether the effect reads nothing of a row but the joints' acceleration
/// (joint_inertia, joint_inertia_coupling): a held tip hardly accelerates the
/// arm, so the diagnosis of held rows does not propose it.
bool ReadsOnlyTheAcceleration(const std::string& name);
/// The catalogue's effects that FittedFromFreeMotion, in its order (the arm's
/// dynamics: joint_friction, joint_inertia, and any a user registers alike).
std::vector<std::string> FreeMotionEffectNames();

/// Seconds of rows in `log` where the tip is not held (no tip_fixed = 1) and
/// a joint moves faster than 0.05 rad/s: 0 for a quasi-static log.
double FreeMotionSeconds(const io::Log& log);

/// Fits `names` (each FittedFromFreeMotion) on the free rows of the logs with
/// free motion. Throws io::InputError when no log has a second of it.
FreeMotionFit FitEffectsOnFreeMotion(const std::vector<NamedLog>& logs,
                                     const models::ModelParameters& parameters,
                                     const std::vector<std::string>& names);

}  // namespace pliant::estimation
