#pragma once
// What `pliant diagnose` shows a person (docs/diagnose.md): a self-contained
// HTML report of a Diagnosis (estimation/diagnosis.h) — tables of the residual
// before and after, the ranked candidate effects and channels, and plots drawn
// with plot.h and embedded as PNG data URIs — and the machine-readable summary
// printed by --json.
//
//   const auto d = estimation::Diagnose(log, "divot.csv", params, options);
//   experiments::WriteDiagnosisReport("out/report", log, d, {"divot.csv", "params.json"});
//   std::cout << experiments::DiagnosisSummaryJson(d).dump(2) << "\n";

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pliant/estimation/diagnosis.h"
#include "pliant/io/log.h"

namespace pliant::experiments {

/// Where the diagnosis came from, printed at the top of the report.
struct DiagnosisReportSources {
  std::string log_path;
  std::string parameters_path;
};

/// The files WriteDiagnosisReport wrote.
struct DiagnosisReportFiles {
  std::string html;                  ///< REPORT_DIR/index.html, self-contained
  std::string summary_json;          ///< REPORT_DIR/summary.json (DiagnosisSummaryJson)
  std::vector<std::string> figures;  ///< REPORT_DIR/figures/*.png, the same plots as files
  /// Pictures that could not be drawn ("NAME: why"): the report says they are
  /// missing; the text, the tables and summary.json are written all the same.
  std::vector<std::string> missing_figures;
};

/// The machine-readable summary, keys in this order:
///   {"rms_before", "rms_after" (mm at the tip, held out), "missing_effect" (name or null),
///    "effects": [{"name", "description", "channels", "score", "p_value", "size", "size_sd",
///                 ...}, …] best first,
///    "channels": [{"name", "lag", "score", ...}, …] best first, ...}
/// Fields after the listed ones (units, joint, AIC, fitted parameters, the
/// residual statistics) are extra detail; a consumer may rely on the listed ones.
nlohmann::ordered_json DiagnosisSummaryJson(const estimation::Diagnosis& diagnosis);

/// The plots of the report (residual against time, against the best channels,
/// the analogues of the paper's Figs. 5, 7 and 8), as PNG files in `dir`.
/// `log` must be the log the diagnosis was made from (series rows index it).
/// A plot that cannot be drawn (gnuplot missing or failing, nothing to plot)
/// is listed in `missing` ("NAME: why") when given, else thrown as
/// std::runtime_error.
std::vector<std::string> WriteDiagnosisFigures(const std::string& dir, const io::Log& log,
                                               const estimation::Diagnosis& diagnosis,
                                               std::vector<std::string>* missing = nullptr);

/// The report's HTML with the given PNG files embedded (no file is written).
std::string DiagnosisReportHtml(const io::Log& log, const estimation::Diagnosis& diagnosis,
                                const DiagnosisReportSources& sources,
                                const std::vector<std::string>& figure_paths,
                                const std::vector<std::string>& missing_figures = {});

/// Writes REPORT_DIR/index.html, summary.json and figures/ (creating the
/// directory). Each file is written atomically: a run killed midway leaves the
/// previous report's files whole.
DiagnosisReportFiles WriteDiagnosisReport(const std::string& dir, const io::Log& log,
                                          const estimation::Diagnosis& diagnosis,
                                          const DiagnosisReportSources& sources);

}  // namespace pliant::experiments
