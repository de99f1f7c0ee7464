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
#include "pliant/io/file_checksum.h"
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
  std::string write_params_path;  ///< --write-params: the parameters with the --add effects
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
  std::printf("\n  of which the sensors' noise alone: %.3f mm (no model goes below it)",
              d.noise_floor_mm);
  std::printf("\n  with the model's compliance scale and clearance refitted: %.3f mm (what each "
              "candidate is scored against)\n",
              d.rms_recalibrated_mm);
  std::printf("  missing effect: %s\n", d.missing_effect ? d.missing_effect->c_str() : "none");
  for (const auto& note : d.notes) std::printf("  note: %s\n", note.c_str());
  for (const auto& e : d.added) {
    std::printf("  added %s, fitted:", e.name.c_str());
    for (std::size_t i = 0; i < e.parameters.size() && i < e.parameter_names.size(); ++i)
      std::printf(" %s = %.4g ± %.2g", e.parameter_names[i].c_str(), e.parameters[i],
                  i < e.parameter_sd.size() ? e.parameter_sd[i] : 0.0);
    std::printf("\n");
  }
  std::printf("  candidate effects, best first:\n");
  for (std::size_t i = 0; i < d.effects.size(); ++i) {
    const auto& e = d.effects[i];
    char p[32];
    std::snprintf(p, sizeof p, e.p_value > 0.0 ? "%.2g" : "< 1e-300", e.p_value);
    std::printf("    %zu. %-26s removes %5.1f %% (%5.1f %% given its rival)  p %-8s  size %.3g ± "
                "%.2g %s%s\n",
                i + 1, e.name.c_str(), 100.0 * e.score, 100.0 * e.unique_score, p, e.size,
                e.size_sd, e.size_unit.c_str(), e.missing ? "  <- missing" : "");
    if (!e.indistinguishable_from.empty()) {
      std::string others;
      for (const auto& o : e.indistinguishable_from) others += (others.empty() ? "" : ", ") + o;
      std::printf("       cannot tell it from %s on this log; to separate them: %s\n",
                  others.c_str(), e.separating_experiment.c_str());
    }
  }
  std::printf("  channels that explain the residual, best first:\n");
  for (std::size_t i = 0; i < d.channels.size() && i < 3; ++i) {
    const auto& c = d.channels[i];
    std::printf("    %zu. %-10s joint %d, lag %3d samples: %4.1f %% of the variance%s%s\n", i + 1,
                c.name.c_str(), c.joint, c.lag, 100.0 * c.score, c.remark.empty() ? "" : " — ",
                c.remark.c_str());
  }
  std::printf("  report: %s\n", html.c_str());
}

void RunDiagnose(DiagnoseCommandOptions o) {
  CheckEffectNames(o.diagnose.added_effects, "--add");
  CheckEffectNames(o.diagnose.candidates, "--candidate");
  estimation::CheckEffectOptions(o.diagnose, o.log_path);
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
  if (!o.write_params_path.empty()) io::CheckOutputFile(o.write_params_path, "--write-params");
  const auto parameters = io::ReadParameters(o.params_path);
  io::CheckLogPlausibilityAndWarn(o.log_path);
  std::optional<io::Progress> progress(std::in_place, "pliant diagnose");
  const io::Log log = io::ReadLog(o.log_path);
  const auto diagnosis = estimation::Diagnose(log, o.log_path, parameters, o.diagnose);
  const auto files =
      experiments::WriteDiagnosisReport(o.report_dir, log, diagnosis, {o.log_path, o.params_path});
  if (!o.write_params_path.empty()) {
    // The added effects were fitted on this log: the file says so.
    models::ModelParameters written =
        estimation::WithDiagnosedEffects(parameters, diagnosis, o.log_path);
    io::AddSourceLogs({o.log_path}, &written);
    io::WriteParameters(o.write_params_path, written);
  }
  progress.reset();  // the line is erased before the summary
  if (!o.json) {
    PrintHuman(diagnosis, files.html);
    if (!o.write_params_path.empty())
      std::printf("  wrote %s: the parameters with the added effects and the refitted compliance "
                  "scale and clearance (pliant correct and filter apply them)\n",
                  o.write_params_path.c_str());
  } else {
    auto summary = experiments::DiagnosisSummaryJson(diagnosis);
    summary["report"] = files.html;
    if (!o.write_params_path.empty()) summary["parameters_written"] = o.write_params_path;
    std::cout << summary.dump(2) << std::endl;
  }
  // A picture that could not be drawn is a warning: the diagnosis stands.
  for (const auto& missing : files.missing_figures) {
    std::fprintf(stderr, "warning: the report's picture %s — the report says it is missing\n",
                 missing.c_str());
  }
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
  CLI::Option* add = sub->add_option("--add", o->diagnose.added_effects,
                                     "Catalogue effect to add to the model and refit with (repeatable)");
  sub->add_option("--write-params", o->write_params_path,
                  "With --add: write the parameters file with the added effects as fitted (values "
                  "± sd) and the refitted compliance scale and clearance, for pliant correct and "
                  "filter (atomically)")
      ->needs(add);
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
