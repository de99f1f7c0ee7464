// pliant params: "what is my compliance at 12 cm?" — the parameters at one
// depth, each with its σ from the file's covariance.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "pliant/estimation/identification_report.h"
#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"

namespace pliant::cli {
namespace {

struct ParamsOptions {
  std::string path;
  double depth_m = 0.0;
  bool json = false;
};

void RunParams(const ParamsOptions& options) {
  const auto parameters = io::ReadParameters(options.path);
  if (!(options.depth_m > 0.0 && options.depth_m <= 0.3)) {
    throw io::InputError("--depth", 0, 0, "depth " + std::to_string(options.depth_m) + " m is outside 0–0.3 m",
                         "give the insertion depth in metres, e.g. --depth 0.12 for 12 cm");
  }
  const auto at = estimation::QueryParametersAtDepth(parameters, options.depth_m);
  if (options.json) {
    std::printf("%s\n", estimation::DepthJson(at).dump(2).c_str());
  } else {
    std::printf("%s", estimation::DepthTable(at).c_str());
    if (!parameters.covariance) std::printf("  (the file has no covariance: σ shown as 0)\n");
  }
}

}  // namespace

Command AddParamsCommand(CLI::App& app) {
  auto options = std::make_shared<ParamsOptions>();
  CLI::App* sub = app.add_subcommand("params", "Show the parameters at one insertion depth, with σ");
  sub->add_option("params", options->path, "Parameters file (JSON)")->required();
  sub->add_option("--depth", options->depth_m, "Insertion depth L (m)")->required();
  sub->add_flag("--json", options->json, "Print JSON");
  return [options] { RunParams(*options); };
}

}  // namespace pliant::cli
