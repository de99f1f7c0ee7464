// pliant params: "what is my compliance at 12 cm?" — the parameters at one
// depth, each with its σ from the file's covariance; the dVRK's own
// compensation file read and written; two files compared side by side.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/io/atomic_file.h"
#include "pliant/io/dvrk_compensation.h"
#include "pliant/io/input_error.h"
#include "pliant/io/output_path.h"
#include "pliant/io/parameters_json.h"

namespace pliant::cli {
namespace {

struct ParamsOptions {
  std::string path;
  double depth_m = std::nan("");  ///< NaN: not given
  bool json = false;
  std::string dvrk_out;
  std::string compare;
};

void CheckDepth(const ParamsOptions& options, bool required) {
  if (std::isnan(options.depth_m)) {
    if (!required) return;
    throw io::InputError("--depth", 0, 0, "--depth is required (unless --dvrk-out is given)",
                         "give the insertion depth in metres, e.g. --depth 0.12 for 12 cm");
  }
  if (!(options.depth_m > 0.0 && options.depth_m <= 0.3)) {
    throw io::InputError("--depth", 0, 0, "depth " + std::to_string(options.depth_m) + " m is outside 0–0.3 m",
                         "give the insertion depth in metres, e.g. --depth 0.12 for 12 cm");
  }
}

models::ModelParameters Read(const std::string& path, bool json) {
  bool dvrk = false;
  auto parameters = io::ReadAnyParameters(path, &dvrk);
  if (dvrk) {
    std::fprintf(json ? stderr : stdout,
                 "%s: the dVRK's compensation file (mtsPSMCompensation): K(L), tau0 and δ read "
                 "from it; tau_min and the depth range are the paper's\n",
                 path.c_str());
  }
  return parameters;
}

std::string WithSd(double value, double sd) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g ± %.2g", value, sd);
  return text;
}

// One row of the comparison: both values, their difference, and the
// difference in σ of the difference when either file knows its σ.
void CompareRow(const char* name, double a, double a_sd, double b, double b_sd) {
  const double sd = std::hypot(a_sd, b_sd);
  char in_sd[48] = "σ unknown";
  if (sd > 0.0) std::snprintf(in_sd, sizeof in_sd, "%+.1f σ", (a - b) / sd);
  std::printf("  %-4s %24s %24s %12.4g  %s\n", name, WithSd(a, a_sd).c_str(),
              WithSd(b, b_sd).c_str(), a - b, in_sd);
}

void Compare(const ParamsOptions& options, const models::ModelParameters& first) {
  const auto second = Read(options.compare, false);
  const auto a = estimation::QueryParametersAtDepth(first, options.depth_m);
  const auto b = estimation::QueryParametersAtDepth(second, options.depth_m);
  std::printf("at L = %.4f m (K in rad/(N·m), δ in rad)\n  first:  %s\n  second: %s\n",
              options.depth_m, options.path.c_str(), options.compare.c_str());
  std::printf("  %-4s %24s %24s %12s  %s\n", "", "first", "second", "first−second",
              "in σ of the difference");
  for (int j = 0; j < 2; ++j) {
    const auto &x = a.joints[j], &y = b.joints[j];
    CompareRow(j == 0 ? "K1" : "K2", x.compliance_rad_per_nm, x.compliance_sd,
               y.compliance_rad_per_nm, y.compliance_sd);
  }
  for (int j = 0; j < 2; ++j) {
    const auto &x = a.joints[j], &y = b.joints[j];
    CompareRow(j == 0 ? "δ1" : "δ2", x.backlash_rad, x.backlash_sd, y.backlash_rad, y.backlash_sd);
  }
}

void RunParams(const ParamsOptions& options) {
  const bool writing = !options.dvrk_out.empty();
  CheckDepth(options, !writing);
  io::CheckOutputFile(options.dvrk_out, "--dvrk-out");
  const auto parameters = Read(options.path, options.json);
  if (writing) {
    std::vector<std::string> notes;
    const auto dvrk = io::ParametersToDvrk(parameters, &notes);
    io::WriteFileAtomically(options.dvrk_out, io::DvrkCompensationText(dvrk));
    for (const auto& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    std::fprintf(stderr, "wrote %s (the dVRK's mtsPSMCompensation file)\n",
                 options.dvrk_out.c_str());
    if (std::isnan(options.depth_m)) return;
  }
  if (!options.compare.empty()) return Compare(options, parameters);
  const auto at = estimation::QueryParametersAtDepth(parameters, options.depth_m);
  if (options.json) {
    std::printf("%s\n", estimation::DepthJson(at).dump(2).c_str());
  } else {
    std::printf("%s", estimation::DepthTable(at).c_str());
    if (!parameters.covariance) std::printf("  (the file has no covariance: σ shown as 0)\n");
    for (int j = 0; parameters.covariance && j < 2; ++j) {
      if (!at.joints[j].in_covariance)
        std::printf("  (joint %d's law is not in the file's covariance: it was not identified, "
                    "and its σ shown as 0 is not known)\n", j + 1);
    }
  }
}

}  // namespace

Command AddParamsCommand(CLI::App& app) {
  auto options = std::make_shared<ParamsOptions>();
  CLI::App* sub = app.add_subcommand(
      "params", "Show the parameters at one insertion depth, with σ; read or write the dVRK's "
                "compensation file; compare two files");
  sub->add_option("params", options->path,
                  "Parameters file (pliant's JSON, or the dVRK's mtsPSMCompensation JSON)")
      ->required();
  sub->add_option("--depth", options->depth_m,
                  "Insertion depth L (m); required unless --dvrk-out is given");
  sub->add_flag("--json", options->json, "Print JSON");
  sub->add_option("--dvrk-out", options->dvrk_out,
                  "Write the parameters as the dVRK's mtsPSMCompensation file");
  sub->add_option("--compare", options->compare,
                  "Another parameters file (either format): K1, K2, δ1, δ2 at --depth side by side");
  return [options] { RunParams(*options); };
}

}  // namespace pliant::cli
