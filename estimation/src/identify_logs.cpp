// The base identification of log files (identify_logs.h): the CLI's and the
// Python module's one path from the logs read to the fitted parameters.
#include "pliant/estimation/identify_logs.h"

#include <cmath>
#include <stdexcept>

#include "pliant/estimation/effect_inputs.h"
#include "pliant/estimation/identification_quasi_static.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/io/file_checksum.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/progress.h"

namespace pliant::estimation {
namespace {

// Parameters the smoother cannot make usable (K outside its physical band, a
// cubic crossing zero) come from logs that do not determine them: bad input,
// with what to record instead.
IdentificationResult RunSmootherOn(const IdentificationData& data,
                                   const models::ModelParameters& prior,
                                   const JointSmootherOptions& smoother,
                                   const std::vector<std::string>& paths) {
  try {
    return RunJointSmoother(data, prior, smoother);
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    const std::string prefix = "the identified parameters are not usable (";
    if (what.rfind(prefix, 0) != 0) throw;
    throw io::InputError(JoinedPaths(paths), 0, 0,
                         "these logs do not determine the parameters: the fit gives " +
                             what.substr(prefix.size(), what.rfind(')') - prefix.size()),
                         "identify from a clamped-beam log over several depths (and a bias "
                         "sweep), or try another --model law");
  }
}

// The paper's procedure starts from the bias torque measured with the tip
// free (its section 3). Without those rows it would keep the prior's table,
// with no uncertainty, and K and δ would silently take its error (on
// data/clamped_beam.csv: K1 +25 % at 48σ, δ negative).
void RequireBiasSweep(const IdentificationData& data, const std::vector<std::string>& paths) {
  for (int j = 0; j < 2; ++j) {
    bool held = false, free = false;
    for (const auto& s : data.samples) {
      if (!std::isfinite(s.effort_nm[j])) continue;
      (s.tip_fixed ? held : free) = true;
    }
    if (!held || free) continue;
    throw io::InputError(JoinedPaths(paths), 0, 0,
                         "the paper's procedure starts from a bias sweep (rows with the tip free), "
                         "and these logs have none for joint " + std::to_string(j + 1) +
                             ": its bias torque would be the prior's, with no uncertainty, and K "
                             "and delta would take its error",
                         "add the bias-sweep log (e.g. data/bias_sweep.csv), or use --method "
                         "smoother, which holds the bias at its prior and carries its "
                         "uncertainty into K and delta");
  }
}

}  // namespace

void LogKinds::Add(const io::Log& log, const std::string& path) {
  if (!(log.header.JointRecorded(1) && log.header.JointRecorded(2))) single_joint.push_back(path);
}

std::string ResolveIdentifyMethod(const std::string& requested, const LogKinds& kinds,
                                  const std::vector<std::string>& paths) {
  const bool one_joint = !kinds.single_joint.empty();
  // The smoother models the take-up, the bias's shape and every row's load;
  // the clamp-by-clamp fit is for what it cannot take. On poses of both
  // joints the clamp-by-clamp fit put K 2–8 % and δ 1–4 mrad off at 20–140 σ
  // on two other generators, where the smoother covered
  // (docs/decisions/identify-auto-on-poses-of-both-joints.md).
  if (requested == "auto") return one_joint ? "quasi_static" : "smoother";
  if (requested == "smoother" && one_joint) {
    throw io::InputError(JoinedPaths(paths), 0, 0,
                         "the joint smoother needs both joints recorded in every log, and " +
                             JoinedPaths(kinds.single_joint) +
                             (kinds.single_joint.size() == 1 ? " records" : " record") +
                             " one joint only",
                         "use the method auto or quasi_static (clamp by clamp, a joint at a time)");
  }
  if (requested != "paper" && requested != "smoother" && requested != "quasi_static") {
    throw io::InputError("method", 0, 0, "unknown method '" + requested + "'",
                         "use auto, paper, smoother or quasi_static");
  }
  return requested;
}

IdentificationResult IdentifyLogs(const IdentificationData& data,
                                  const models::ModelParameters& prior, const std::string& method,
                                  const IdentifyLogsOptions& options,
                                  const std::vector<std::string>& paths) {
  io::Progress progress("pliant identify: " + method + " fit");  // (Ceres gives no share done)
  if (method == "quasi_static") {
    QuasiStaticOptions quasi;
    quasi.held_friction = options.held_friction;
    try {
      return RunQuasiStaticIdentification(data, prior, quasi);
    } catch (const std::invalid_argument& e) {  // what the logs or the law lack: bad input
      const std::string what = e.what(), dash = " \u2014 ";
      const auto split = what.find(dash);
      throw io::InputError(JoinedPaths(paths), 0, 0, what.substr(0, split),
                           split == std::string::npos ? "see docs/identification.md"
                                                      : what.substr(split + dash.size()));
    }
  }
  if (method == "paper") {
    RequireBiasSweep(data, paths);
    PaperProcedureOptions paper;
    paper.law = options.law;
    return RunPaperProcedure(data, prior, paper);
  }
  JointSmootherOptions smoother;
  smoother.law = options.law;
  smoother.bias_harmonics = options.bias_harmonics;
  return RunSmootherOn(data, prior, smoother, paths);
}

IdentifiedLogs IdentifyLogFiles(const std::vector<std::string>& paths,
                                const models::ModelParameters& prior,
                                const IdentifyLogsOptions& options) {
  CheckIdentifyEffectNames(options.effects);
  IdentifiedLogs out;
  std::vector<io::Log> logs;  // (kept only for the effects' fits)
  LogKinds kinds;
  for (const auto& path : paths) {
    const io::Log log = io::ReadLog(path, {options.skip_bad_rows});
    kinds.Add(log, path);
    AppendSamples(log, path, {}, &out.data);
    if (!options.effects.empty()) logs.push_back(log);
  }
  const std::string method = ResolveIdentifyMethod(options.method, kinds, paths);
  const auto fit = [&](const IdentificationData& data) {
    IdentificationResult result = IdentifyLogs(data, prior, method, options, paths);
    result.parameters.description = "identified by pliant identify (" + result.method + ", " +
                                    models::ComplianceFormName(options.law) + ") from " +
                                    std::to_string(paths.size()) + " log(s)";
    return result;
  };
  out.result = fit(out.data);
  out.effects = FitEffects(options.effects, logs, paths, &out.result);
  const models::ModelParameters named = out.effects.any()
                                            ? WithOnlyTheNamed(out.result.parameters, options.effects)
                                            : models::ModelParameters{};
  if (out.effects.any() && ReadsTheEffort(named)) {
    // The base's bias table took up what the effect puts in the effort at the
    // calibration's poses, which the effect beside it would count twice.
    IdentificationData without;
    for (std::size_t i = 0; i < logs.size(); ++i) {
      AppendSamples(WithoutInternalTorque(logs[i], named), paths[i], {}, &without);
    }
    out.result = fit(without);
    out.effects = FitEffects(options.effects, logs, paths, &out.result);
    out.data = std::move(without);
  }
  // Which logs: a diagnosis of one of them then says that what this fit took
  // up does not show in its residual (docs/diagnose.md).
  out.result.parameters.identified_from = io::SourceLogs(paths);
  return out;
}

std::string JoinedPaths(const std::vector<std::string>& paths) {
  std::string joined;
  for (const auto& path : paths) joined += (joined.empty() ? "" : ", ") + path;
  return joined;
}

}  // namespace pliant::estimation
