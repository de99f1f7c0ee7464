// pliant diagnose: where the model fails on a log, which catalogue effect
// explains it, and the error with it added — an HTML report and, with --json,
// the summary on stdout (docs/diagnose.md).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/effect_catalogue.h"
#include "pliant/experiments/diagnosis_report.h"
#include "pliant/io/atomic_file.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_plausibility.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"
#include "pliant/io/progress.h"

namespace pliant::cli {
namespace {

struct DiagnoseCommandOptions {
  std::string params_path;
  std::string log_path;
  std::string report_dir;
  bool json = false;
  estimation::DiagnoseOptions diagnose;
};

// Checked before the (slow) diagnosis so a typo costs nothing.
void CheckEffectNames(const std::vector<std::string>& names, const char* option) {
  for (const auto& name : names) {
    if (estimation::EffectCatalogue::Global().Contains(name)) continue;
    std::string known;
    for (const auto& k : estimation::CandidateEffectNames())
      known += (known.empty() ? "" : ", ") + k;
    throw io::InputError(option, 0, 0, "unknown effect '" + name + "'",
                         "use one of: " + known + " (docs/effects.md)");
  }
}

void PrintHuman(const estimation::Diagnosis& d, const std::string& html) {
  std::printf("pliant diagnose: residual against %s over %zu rows\n", d.reference.c_str(),
              d.series.row.size());
  std::printf("  held-out RMS error at the tip: %.3f mm -> %.3f mm", d.rms_before_mm,
              d.rms_after_mm);
  if (!d.added_effects.empty()) {
    std::string names;
    for (const auto& n : d.added_effects) names += (names.empty() ? "" : " + ") + n;
    std::printf(" (with %s)", names.c_str());
  }
  std::printf("\n  missing effect: %s\n", d.missing_effect ? d.missing_effect->c_str() : "none");
  std::printf("  candidate effects, best first:\n");
  for (std::size_t i = 0; i < d.effects.size(); ++i) {
    const auto& e = d.effects[i];
    char p[32];
    std::snprintf(p, sizeof p, e.p_value > 0.0 ? "%.2g" : "< 1e-300", e.p_value);
    std::printf("    %zu. %-26s removes %5.1f %% of the error  p %-8s  size %.3g ± %.2g %s%s\n",
                i + 1, e.name.c_str(), 100.0 * e.score, p, e.size, e.size_sd, e.size_unit.c_str(),
                e.missing ? "  <- missing" : "");
  }
  std::printf("  channels that explain the residual, best first:\n");
  for (std::size_t i = 0; i < d.channels.size() && i < 3; ++i) {
    const auto& c = d.channels[i];
    std::printf("    %zu. %-10s joint %d, lag %3d samples: %4.1f %% of the variance\n", i + 1,
                c.name.c_str(), c.joint, c.lag, 100.0 * c.score);
  }
  std::printf("  report: %s\n", html.c_str());
}

void RunDiagnose(DiagnoseCommandOptions o) {
  CheckEffectNames(o.diagnose.added_effects, "--add");
  CheckEffectNames(o.diagnose.candidates, "--candidate");
  if (o.report_dir.empty()) {
    const bool piped = o.log_path == io::kStandardStream;
    o.report_dir =
        (piped ? "stdin" : std::filesystem::path(o.log_path).stem().string()) + "_diagnosis";
  }
  if (std::filesystem::exists(o.report_dir) && !std::filesystem::is_directory(o.report_dir)) {
    throw io::InputError(o.report_dir, 0, 0, "is a file, and the report is a directory",
                         "give -o a directory name (it is created if missing)");
  }
  io::CheckOutputDirectory(o.report_dir, "-o");
  const auto parameters = io::ReadParameters(o.params_path);
  io::CheckLogPlausibilityAndWarn(o.log_path);
  std::optional<io::Progress> progress(std::in_place, "pliant diagnose");
  const io::Log log = io::ReadLog(o.log_path);
  const auto diagnosis = estimation::Diagnose(log, o.log_path, parameters, o.diagnose);
  const auto files =
      experiments::WriteDiagnosisReport(o.report_dir, log, diagnosis, {o.log_path, o.params_path});
  progress.reset();  // the line is erased before the summary
  if (!o.json) return PrintHuman(diagnosis, files.html);
  auto summary = experiments::DiagnosisSummaryJson(diagnosis);
  summary["report"] = files.html;
  std::cout << summary.dump(2) << std::endl;
}

}  // namespace

Command AddDiagnoseCommand(CLI::App& app) {
  auto o = std::make_shared<DiagnoseCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "diagnose",
      "Where the model fails on a log, the catalogue effect that explains it, and the error "
      "with it added: an HTML report (docs/diagnose.md)");
  sub->add_option("--params", o->params_path, "Parameters file (JSON, docs/parameters.md)")
      ->required();
  sub->add_option("log", o->log_path, "Log with tip_fixed segments or q1_ref/q2_ref (CSV)")
      ->required();
  sub->add_option("--add", o->diagnose.added_effects,
                  "Catalogue effect to add to the model and refit with (repeatable)");
  sub->add_option("-o,--output", o->report_dir,
                  "Report directory (index.html, summary.json, figures/); default "
                  "LOGNAME_diagnosis in the current directory");
  sub->add_flag("--json", o->json, "Print the machine-readable summary instead of the text");
  sub->add_option("--candidate", o->diagnose.candidates,
                  "Try only these candidate effects (repeatable; default: every candidate)");
  sub->add_option("--reference", o->diagnose.reference,
                  "Where the tip was: auto (q*_ref, else tip_fixed, else q*_true), q*_ref, "
                  "tip_fixed or q*_true")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "q*_ref", "tip_fixed", "q*_true"}));
  sub->add_option("--max-lag", o->diagnose.max_lag_samples,
                  "Residual-channel correlation over ± this many samples")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  sub->add_option("--folds", o->diagnose.folds, "Cross-validation folds, by segment")
      ->capture_default_str()
      ->check(CLI::Range(2, 100));
  return [o] { RunDiagnose(*o); };
}

}  // namespace pliant::cli
