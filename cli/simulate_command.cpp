// pliant simulate: runs a scenario (experiments/scenarios/*.json) through the
// CVODE simulator and writes a canonical log, optionally the matching figure.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "pliant/experiments/paper_figures.h"
#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/output_path.h"
#include "pliant/io/progress.h"
#include "summary_stream.h"

namespace pliant::cli {
namespace {

struct SimulateOptions {
  std::string scenario_path;
  std::string output_path;
  std::uint64_t seed = 1;
  std::vector<std::string> overrides;
  std::string figure_path;
};

void RunSimulate(const SimulateOptions& options) {
  io::CheckOutputFile(options.output_path, "-o");
  io::CheckOutputFile(options.figure_path, "--figure");
  const auto scenario = experiments::ReadScenario(options.scenario_path, options.overrides);
  const auto start = std::chrono::steady_clock::now();
  std::optional<io::Progress> progress(std::in_place, "pliant simulate");
  const auto result = experiments::Simulate(scenario, options.seed);
  progress.reset();  // the line is erased before the summary
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  io::WriteLog(options.output_path, result.log);
  std::FILE* out = SummaryStream(options.output_path);
  std::fprintf(out, "pliant simulate: %s (%s), seed %llu -> %s\n", scenario.name.c_str(),
              experiments::ExperimentName(scenario.type),
              static_cast<unsigned long long>(options.seed), options.output_path.c_str());
  std::fprintf(out, "  %zu rows, %zu holds, %zu segments; %.1f s simulated in %.2f s (%.0fx real time)\n",
              result.log.Rows(), result.holds.size(), result.segments.size(),
              result.stats.simulated_s, wall_s, result.stats.simulated_s / wall_s);
  std::fprintf(out, "  CVODE: %ld steps, %ld right-hand sides, %ld contact events\n",
              result.stats.integrator_steps, result.stats.rhs_evaluations,
              result.stats.contact_events);
  if (!options.figure_path.empty()) {
    experiments::PlotExperiment(scenario, result, options.figure_path);
    std::fprintf(out, "  figure -> %s\n", options.figure_path.c_str());
  }
}

}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* sub = app.add_subcommand(
      "simulate", "Simulate one of the paper's experiments (docs/simulator.md) into a log");
  sub->add_option("scenario", options->scenario_path,
                  "Scenario file (JSON), e.g. experiments/scenarios/clamped_beam.json")
      ->required();
  sub->add_option("-o,--output", options->output_path, "Output log (CSV), written atomically")
      ->required();
  // CLI11 reads "-1" into an unsigned seed as 18446744073709551615: only digits pass.
  const CLI::Validator whole_number(
      [](std::string& text) {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        return digits ? std::string() : "the seed is a whole number from 0 to 2^64 - 1";
      },
      "SEED");
  sub->add_option("--seed", options->seed, "Seed of the noise: the same seed, the same log")
      ->capture_default_str()
      ->check(whole_number);
  sub->add_option("--set", options->overrides,
                  "Override a scenario value before it is checked: key=value with a dotted key "
                  "and a JSON value, e.g. --set experiment.depths_m=[0.1,0.2] (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--figure", options->figure_path,
                  "Also draw the experiment's figure (.png or .svg; needs gnuplot)");
  return [options] { RunSimulate(*options); };
}

}  // namespace pliant::cli
