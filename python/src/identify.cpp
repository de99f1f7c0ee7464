// Identification from log files (docs/identification.md): the paper's
// procedure or the joint smoother, as `pliant identify` runs them, with the
// report `pliant identify --json` prints.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "pliant/estimation/free_motion_fit.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/estimation/identify_logs.h"
#include "pliant/io/file_checksum.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"

namespace pliant::python {
namespace {

models::ComplianceForm LawNamed(const std::string& name) {
  models::ComplianceForm form;
  if (models::ComplianceFormNamed(name, &form)) return form;
  throw io::InputError("law", 0, 0, "unknown compliance law '" + name + "'",
                       "use 'inverse_cubic', 'direct_cubic' or 'beam_series'");
}

py::tuple Identify(const std::vector<std::string>& logs, const std::string& method,
                   const std::string& law, const std::optional<Parameters>& prior,
                   int harmonics, bool held_friction, const std::vector<std::string>& effects,
                   bool skip_bad_rows) {
  if (logs.empty()) {
    throw io::InputError("logs", 0, 0, "no log given", "give at least one log file");
  }
  estimation::IdentifyLogsOptions options;
  options.method = method;
  options.law = LawNamed(law);
  options.bias_harmonics = harmonics;
  options.held_friction = held_friction;
  options.effects = effects;
  options.skip_bad_rows = skip_bad_rows;
  estimation::IdentifiedLogs fit;
  {
    py::gil_scoped_release unlocked;
    fit = estimation::IdentifyLogFiles(logs, prior ? *prior : estimation::PaperPrior(), options);
  }
  auto report = estimation::IdentificationJson(fit.result, fit.data,
                                               estimation::CompareLaws(fit.result));
  estimation::AddEffectFitsJson(fit.effects, &report);
  return py::make_tuple(fit.result.parameters, ToPython(report));
}

// The arm's dynamics on the logs' free motion, added to `parameters`
// (identify --effect joint_inertia --effect joint_friction).
py::tuple IdentifyArmDynamics(const std::vector<std::string>& logs, const Parameters& parameters,
                              bool skip_bad_rows) {
  std::vector<io::Log> read;
  estimation::FreeMotionFit fit;
  {
    py::gil_scoped_release unlocked;
    for (const auto& path : logs) read.push_back(io::ReadLog(path, {skip_bad_rows}));
    std::vector<estimation::NamedLog> named;
    for (std::size_t i = 0; i < read.size(); ++i) named.push_back({&read[i], logs[i]});
    fit = estimation::FitEffectsOnFreeMotion(named, parameters,
                                             estimation::FreeMotionEffectNames());
  }
  auto with = estimation::WithFittedEffects(
      parameters, fit.fitted,
      "pliant.identify_arm_dynamics on the free motion of " + estimation::JoinedPaths(fit.logs));
  io::AddSourceLogs(logs, &with);
  return py::make_tuple(with, ToPython(estimation::FreeMotionFitJson(fit)));
}

}  // namespace

void BindIdentify(py::module_& m) {
  m.def("identify_arm_dynamics", &IdentifyArmDynamics, py::arg("logs"), py::arg("parameters"),
        py::arg("skip_bad_rows") = false,
        "The arm's own dynamics — joint_inertia (kg·m²) and joint_friction — fitted on the free "
        "motion of log files (rows with no held tip where a joint moves), as `pliant identify "
        "--effect joint_inertia --effect joint_friction` does (docs/identification.md). "
        "parameters: the arm's identified Parameters (their bias table is read). Returns "
        "(Parameters with the effects added, report): the report is `--json`'s "
        "'free_motion_fit'. The filter takes their σ as the prior of the arm torque it learns.");
  m.def("identify", &Identify, py::arg("logs"), py::arg("method") = "auto",
        py::arg("law") = "inverse_cubic", py::arg("prior") = py::none(),
        py::arg("harmonics") = 2, py::arg("held_friction") = true,
        py::arg("effects") = std::vector<std::string>{}, py::arg("skip_bad_rows") = false,
        "Identifies compliance K(L) (rad/(N·m)), backlash δ (rad) and bias torque τ0(q) (N·m) "
        "from log files, as `pliant identify` does (docs/identification.md).\n\n"
        "logs: paths of canonical logs (free-tip rows feed the bias, tip_fixed rows the "
        "compliance and backlash). method: 'auto' (as the command: 'quasi_static' when a "
        "log records a single joint, else 'smoother'), 'smoother' (one "
        "Ceres problem, full covariance), 'quasi_static' (clamp by clamp with the held "
        "friction; held_friction=False: the paper's form) or 'paper' (the paper's procedure). "
        "law: 'inverse_cubic', 'direct_cubic' or "
        "'beam_series'. prior: Parameters the priors are centred on (default: the paper's). "
        "harmonics: Fourier harmonics of the bias torque (smoother). effects: catalogue effects "
        "fitted beside the base with their σ, as --effect (docs/effects.md). Returns (Parameters, "
        "report): the report is the dict `pliant identify --json` prints (each parameter ± σ, "
        "K(L) at three depths, fit RMS, warnings).");
}

}  // namespace pliant::python
