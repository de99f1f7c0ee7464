#pragma once
// Catalogue effects fitted on the held-tip rows of logs, jointly with what
// they trade off against in the base model (each joint's compliance scale and
// clearance): the one fit that `pliant diagnose --add` and
// `pliant identify --effect` share (docs/identification.md, docs/diagnose.md).
//
//   const auto fit = FitEffectsOnLogs({{&log, "divot.csv"}}, identified,
//                                     {"deflection_coupling"}, {});
//   const auto with = WithFittedEffects(identified, fit.fitted, "pliant identify on divot.csv");
//
// The σ count each segment (a push, a clamp) as one draw: a clustered sandwich
// over the segments, never below the white-noise covariance.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pliant/estimation/diagnosis.h"
#include "pliant/io/log.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

/// Effects as fitted, with the base model's refit beside them.
struct FittedEffects {
  std::vector<EffectFinding> effects;  ///< in the order asked, values ± sd
  /// compliance_share1, compliance_share2 (K → (1 + s_j)·K), clearance1,
  /// clearance2 (δ → δ + d_j, rad), fitted with the effects; empty when off.
  std::optional<EffectFinding> recalibration;
  /// Over the recalibration's 4 parameters (when present), then each effect's.
  Eigen::MatrixXd covariance;
};

struct NamedLog {
  const io::Log* log = nullptr;
  std::string path;
};

struct LogEffectFit {
  FittedEffects fitted;
  std::vector<std::string> logs;  ///< the logs with held-tip rows, which the fit used
  std::size_t samples = 0;        ///< compared samples over those logs
  int segments = 0;               ///< their segments: the clusters of the σ
  /// Held-out RMS error at the tip (mm, cross-validated by segment): the model
  /// as given, with its compliance scale and clearance refitted alone, and
  /// with the effects and the refit.
  double rms_given_mm = 0.0;
  double rms_refit_mm = 0.0;
  double rms_with_effects_mm = 0.0;
  std::vector<std::string> notes;  ///< what the logs cannot tell, per log
};

/// Fits the catalogue effects `names` on the tip_fixed rows of `logs` (logs
/// without any are skipped), each joint's compliance scale and clearance
/// refitted with them (options.recalibrate_base). Throws io::InputError when
/// no log has a held tip, or a name is not in the catalogue.
LogEffectFit FitEffectsOnLogs(const std::vector<NamedLog>& logs,
                              const models::ModelParameters& parameters,
                              const std::vector<std::string>& names, DiagnoseOptions options);

/// The parameters with a fit: each joint's K(L) scaled by 1 + s_j and δ_j
/// widened by d_j, the effects replacing any of the same name in `effects`
/// (values and sd), and the covariance extended by the effects' parameters
/// ("EFFECT.PARAMETER") and the refit's (propagated into the law's
/// coefficients and δ). `provenance` ("pliant identify on a.csv") goes into
/// the sources and the description.
models::ModelParameters WithFittedEffects(const models::ModelParameters& parameters,
                                          const FittedEffects& fitted,
                                          const std::string& provenance);

}  // namespace pliant::estimation
