// pliant correct: the paper's correction (or its dead-zone form) applied to a
// log, streamed row by row, written atomically with q1_corr and q2_corr added.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "pliant/estimation/log_correction.h"
#include "pliant/estimation/log_tare.h"
#include "pliant/io/log_plausibility.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"
#include "summary_stream.h"

namespace pliant::cli {
namespace {

struct CorrectOptions {
  std::string params_path;
  std::string model_name = "paper";
  std::string input_path;
  std::string output_path;
  std::string tare;
  bool skip_bad_rows = false;
};

void PrintSummary(const CorrectOptions& options, const estimation::LogCorrectionSummary& s) {
  std::FILE* out = SummaryStream(options.output_path);
  std::fprintf(out, "pliant correct: %zu rows, %s model -> %s\n", s.rows,
               options.model_name.c_str(), options.output_path.c_str());
  if (s.skipped_rows > 0)
    std::fprintf(out, "  skipped %zu bad rows (--skip-bad-rows)\n", s.skipped_rows);
  if (s.depth_clamped_rows > 0) {
    std::fprintf(stderr,
                 "warning: %zu rows have an insertion depth outside the parameters' valid range; "
                 "K(L) used the nearest valid depth for them\n",
                 s.depth_clamped_rows);
  }
  if (s.reference.empty() || s.corrected.count() == 0) return;
  std::fprintf(out, "  tip error against %s over %zu rows:\n", s.reference.c_str(),
               s.corrected.count());
  std::fprintf(out, "    %-20s RMS %7.3f mm   max %7.3f mm\n", "uncorrected", s.uncorrected.RmsMm(),
               s.uncorrected.MaxMm());
  const std::string label = "corrected (" + options.model_name + ")";
  std::fprintf(out, "    %-20s RMS %7.3f mm   max %7.3f mm\n", label.c_str(), s.corrected.RmsMm(),
               s.corrected.MaxMm());
}

void RunCorrect(const CorrectOptions& options) {
  io::CheckOutputFile(options.output_path, "-o");
  auto parameters = io::ReadParameters(options.params_path);
  io::CheckLogPlausibilityAndWarn(options.input_path, {options.skip_bad_rows});
  const auto tare = options.tare.empty()
                        ? estimation::LogTare{}
                        : estimation::TareOnLog(options.input_path, options.tare, &parameters);
  const estimation::ComplianceCorrector corrector(
      parameters, *estimation::ParseCorrectionModel(options.model_name));
  const std::string note = tare.Note();
  const auto summary = estimation::CorrectLog(
      options.input_path, options.output_path, corrector,
      options.model_name + " model, parameters " + options.params_path +
          (note.empty() ? "" : ", " + note),
      {options.skip_bad_rows});
  PrintSummary(options, summary);
  std::printf("%s", tare.Words().c_str());
  if (!corrector.extra_effects().empty()) {
    std::string names;
    for (const auto& n : corrector.extra_effects().Names()) names += (names.empty() ? "" : ", ") + n;
    std::printf("  effects from the parameters file: %s\n", names.c_str());
  }
}

}  // namespace

Command AddCorrectCommand(CLI::App& app) {
  auto options = std::make_shared<CorrectOptions>();
  CLI::App* sub = app.add_subcommand(
      "correct", "Correct joints 1-2 of a log for compliance and backlash (adds q1_corr, q2_corr)");
  sub->add_option("--params", options->params_path, "Parameters file (JSON, docs/parameters.md)")
      ->required();
  sub->add_option("--model", options->model_name,
                  "paper: equation (2) with its tau_min switch; deadzone: continuous dead-zone")
      ->check(CLI::IsMember({"paper", "deadzone"}))
      ->capture_default_str();
  sub->add_option("input", options->input_path, "Input log (CSV, docs/log-format.md)")
      ->required();
  sub->add_option("-o,--output", options->output_path, "Output log, written atomically")
      ->required();
  sub->add_option("--tare", options->tare,
                  "Tare the parameters' bias torque on the log's unloaded rows: auto (the longest "
                  "run with a steady load) or T0:T1 (rows with t in that range, s; "
                  "docs/real-data.md)");
  sub->add_flag("--skip-bad-rows", options->skip_bad_rows,
                "Drop and count rows with NaN/Inf/empty required values instead of stopping");
  return [options] { RunCorrect(*options); };
}

}  // namespace pliant::cli
