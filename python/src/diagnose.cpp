// Missing-effect discovery (docs/diagnose.md): estimation::Diagnose on a log
// file, returning the summary `pliant diagnose --json` prints, and the HTML
// report when asked for a directory.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/experiments/diagnosis_report.h"
#include "pliant/io/log_reader.h"

namespace pliant::python {
namespace {

py::object DiagnoseLog(const Parameters& parameters, const std::string& log_path,
                       const std::vector<std::string>& add,
                       const std::vector<std::string>& candidates, const std::string& reference,
                       int max_lag, int folds, const std::optional<std::string>& report_dir) {
  estimation::DiagnoseOptions options;
  options.added_effects = add;
  options.candidates = candidates;
  options.reference = reference;
  options.max_lag_samples = max_lag;
  options.folds = folds;
  nlohmann::ordered_json summary;
  {
    py::gil_scoped_release unlocked;
    const io::Log log = io::ReadLog(log_path);
    const auto diagnosis = estimation::Diagnose(log, log_path, parameters, options);
    summary = experiments::DiagnosisSummaryJson(diagnosis);
    if (report_dir) {
      const auto files = experiments::WriteDiagnosisReport(*report_dir, log, diagnosis,
                                                           {log_path, parameters.description});
      summary["report"] = files.html;
    }
  }
  return ToPython(summary);
}

}  // namespace

void BindDiagnose(py::module_& m) {
  m.def("diagnose", &DiagnoseLog, py::arg("parameters"), py::arg("log"),
        py::arg("add") = std::vector<std::string>{},
        py::arg("candidates") = std::vector<std::string>{}, py::arg("reference") = "auto",
        py::arg("max_lag") = 30, py::arg("folds") = 5, py::arg("report_dir") = py::none(),
        "Where the model fails on a log, the catalogue effect it lacks, and the error with it "
        "added (docs/diagnose.md), as `pliant diagnose --json`.\n\n"
        "log: path of a log with tip_fixed segments or q1_ref/q2_ref. add: effects to add to "
        "the model; candidates: effects to try (default: every candidate). reference: 'auto', "
        "'q*_ref', 'tip_fixed' or 'q*_true'. max_lag: residual–channel lags (samples); folds: "
        "cross-validation folds by segment. report_dir: also write the HTML report there. "
        "Returns the summary dict: rms_before, rms_after (held-out tip RMS, mm), "
        "missing_effect (name or None), effects and channels, best first.");
}

}  // namespace pliant::python
