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
#include "pliant/io/file_checksum.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"

namespace pliant::python {
namespace {

py::object DiagnoseLog(const Parameters& parameters, const std::string& log_path,
                       const std::vector<std::string>& add,
                       const std::vector<std::string>& candidates, const std::string& reference,
                       int max_lag, int folds, const std::optional<std::string>& report_dir,
                       const std::optional<std::string>& write_params) {
  if (write_params) io::CheckOutputFile(*write_params, "write_params");
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
    if (write_params) {  // as --write-params: the added effects were fitted on this log
      models::ModelParameters written =
          estimation::WithDiagnosedEffects(parameters, diagnosis, log_path);
      io::AddSourceLogs({log_path}, &written);
      io::WriteParameters(*write_params, written);
      summary["parameters_written"] = *write_params;
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
        py::arg("write_params") = py::none(),
        "Where the model fails on a log, the catalogue effect it lacks, and the error with it "
        "added (docs/diagnose.md), as `pliant diagnose --json`.\n\n"
        "log: path of a log with tip_fixed segments or q1_ref/q2_ref. add: effects to add to "
        "the model; candidates: effects to try (default: every candidate). reference: 'auto', "
        "'q*_ref', 'tip_fixed' or 'q*_true'. max_lag: residual–channel lags (samples); folds: "
        "cross-validation folds by segment. report_dir: also write the HTML report there. "
        "write_params: also write the parameters with the added effects and the refitted "
        "compliance scale and clearance there, as --write-params (correct and filter apply "
        "them). "
        "Returns the summary dict: rms_before, rms_after (held-out tip RMS, mm), "
        "missing_effect (name or None), effects and channels, best first.");
}

}  // namespace pliant::python
