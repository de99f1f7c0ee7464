// pliant correct: the paper's correction (or its dead-zone form) applied to a
// log, streamed row by row, written atomically with q1_corr and q2_corr added.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"

namespace pliant::cli {
namespace {

struct CorrectOptions {
  std::string params_path;
  std::string model_name = "paper";
  std::string input_path;
  std::string output_path;
  bool skip_bad_rows = false;
};

// Where the log says the tip really was: simulated truth first, else a tracker.
struct ReferenceColumns {
  int q1 = -1, q2 = -1;
  const char* name = nullptr;
};

ReferenceColumns FindReference(const io::StandardColumns& c) {
  if (c.q1_true >= 0 && c.q2_true >= 0) return {c.q1_true, c.q2_true, "q*_true"};
  if (c.q1_ref >= 0 && c.q2_ref >= 0) return {c.q1_ref, c.q2_ref, "q*_ref"};
  return {};
}

void RunCorrect(const CorrectOptions& options) {
  const auto model = estimation::ParseCorrectionModel(options.model_name);
  const auto parameters = io::ReadParameters(options.params_path);
  const estimation::ComplianceCorrector corrector(parameters, *model);

  io::LogReader reader(options.input_path, {options.skip_bad_rows});
  io::LogHeader header = reader.header();
  const io::StandardColumns in(header);
  const std::size_t input_columns = header.columns.size();
  const int q1_corr = header.AddColumn("q1_corr");
  const int q2_corr = header.AddColumn("q2_corr");
  header.metadata.emplace_back("correction", options.model_name + " model, parameters " +
                                                 options.params_path);
  io::LogWriter writer(options.output_path, header);

  const ReferenceColumns reference = FindReference(in);
  estimation::TipErrorStatistics uncorrected, corrected;
  std::vector<double> row(header.columns.size());
  std::size_t rows = 0, clamped = 0;
  while (const double* values = reader.Next()) {
    std::copy(values, values + input_columns, row.begin());
    const Eigen::Vector3d q(values[in.q1], values[in.q2], values[in.q3]);
    const auto result =
        corrector.Correct(q, Eigen::Vector2d(values[in.tau1], values[in.tau2]));
    row[q1_corr] = result.corrected_rad[0];
    row[q2_corr] = result.corrected_rad[1];
    writer.Write(row.data());
    ++rows;
    clamped += result.depth_clamped;
    if (reference.name) {
      const Eigen::Vector2d truth(values[reference.q1], values[reference.q2]);
      uncorrected.Add(q, truth);
      corrected.Add(Eigen::Vector3d(row[q1_corr], row[q2_corr], q[2]), truth);
    }
  }
  writer.Commit();

  std::printf("pliant correct: %zu rows, %s model -> %s\n", rows, options.model_name.c_str(),
              options.output_path.c_str());
  if (reader.skipped_rows() > 0) {
    std::printf("  skipped %zu bad rows (--skip-bad-rows)\n", reader.skipped_rows());
  }
  if (clamped > 0) {
    std::fprintf(stderr,
                 "warning: %zu rows have an insertion depth outside the parameters' valid range; "
                 "the depth was clamped to it for K(L)\n",
                 clamped);
  }
  if (reference.name && corrected.count() > 0) {
    std::printf("  tip error against %s over %zu rows:\n", reference.name, corrected.count());
    std::printf("    %-22s RMS %8.3f mm   max %8.3f mm\n", "uncorrected", uncorrected.RmsMm(),
                uncorrected.MaxMm());
    const std::string label = "corrected (" + options.model_name + ")";
    std::printf("    %-22s RMS %8.3f mm   max %8.3f mm\n", label.c_str(), corrected.RmsMm(),
                corrected.MaxMm());
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
  sub->add_flag("--skip-bad-rows", options->skip_bad_rows,
                "Drop and count rows with NaN/Inf/empty required values instead of stopping");
  return [options] { RunCorrect(*options); };
}

}  // namespace pliant::cli
