#pragma once
// The base identification of log files as `pliant identify` and
// `pliant.identify` both run it: which method `auto` means for the logs, the
// logs each method needs, and a fit the logs cannot determine as bad input
// (io::InputError naming the logs: exit 2, pliant.InputError in Python).

#include <string>
#include <vector>

#include "pliant/estimation/identification.h"
#include "pliant/estimation/identification_data.h"
#include "pliant/estimation/identify_effects.h"
#include "pliant/io/log.h"

namespace pliant::estimation {

struct IdentifyLogsOptions {
  std::string method = "auto";  ///< auto, paper, smoother or quasi_static
  models::ComplianceForm law = models::ComplianceForm::kInverseCubic;
  int bias_harmonics = 2;     ///< the joint smoother's Fourier harmonics of the bias torque
  bool held_friction = true;  ///< quasi_static: fit the held friction (false: the paper's form)
  std::vector<std::string> effects;  ///< catalogue effects fitted beside the base (identify_effects.h)
  bool skip_bad_rows = false;        ///< drop rows with NaN/Inf/empty required values
};

/// What `auto` reads of the logs: which record one joint only.
struct LogKinds {
  std::vector<std::string> single_joint;  ///< paths of the logs that record one joint

  void Add(const io::Log& log, const std::string& path);
};

/// The method for these logs: `requested` unless it is "auto", which is the
/// clamp-by-clamp quasi-static fit when one of the logs records a single joint
/// (the joint smoother needs both joints of every log), else the joint
/// smoother, on poses (`# timing: quasi-static`) as on samples in time. The joint smoother asked for on a log of one joint is
/// io::InputError.
std::string ResolveIdentifyMethod(const std::string& requested, const LogKinds& kinds,
                                  const std::vector<std::string>& paths);

/// The fit by `method` (resolved). io::InputError naming `paths` when the
/// logs cannot determine the parameters, or when the paper's procedure has
/// no bias sweep to start from.
IdentificationResult IdentifyLogs(const IdentificationData& data,
                                  const models::ModelParameters& prior, const std::string& method,
                                  const IdentifyLogsOptions& options,
                                  const std::vector<std::string>& paths);

/// A base fit of log files with the effects named beside it.
struct IdentifiedLogs {
  IdentificationResult result;  ///< its parameters say what fitted them and from which logs
  IdentificationData data;      ///< what the base fit read (the report's and the figures')
  EffectFits effects;
};

/// What `pliant identify LOGS…` does before it writes: reads the logs at
/// `paths`, fits the base model by the method `auto` or options.method
/// chooses, then options.effects. Where one of those acts on the effort, the
/// base fit's bias table took up what the effect puts there at the
/// calibration's poses: the base is fitted once more on the efforts without
/// it, then the effects. The parameters record the logs (identified_from).
IdentifiedLogs IdentifyLogFiles(const std::vector<std::string>& paths,
                                const models::ModelParameters& prior,
                                const IdentifyLogsOptions& options);

/// "a.csv, b.csv": logs (or any names) as an error message lists them.
std::string JoinedPaths(const std::vector<std::string>& paths);

}  // namespace pliant::estimation
