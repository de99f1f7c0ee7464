// pliant montecarlo: a Monte Carlo accuracy study (docs/montecarlo.md) on
// every core, or across machines under mpirun; resumable.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "commands.h"
#include "montecarlo_mpi.h"
#include "pliant/experiments/montecarlo.h"
#include "pliant/experiments/study.h"
#include "pliant/io/output_path.h"

namespace pliant::cli {
namespace {

struct MontecarloCommandOptions {
  std::string study_path;
  experiments::MontecarloOptions run;
};

void PrintSummary(const nlohmann::json& s, const std::string& dir) {
  std::printf("pliant montecarlo: %s, %d trials -> %s/summary.json\n",
              s["study"].get<std::string>().c_str(), s["trials"].get<int>(), dir.c_str());
  std::printf("  tip error (mm)   median     p95     max   largest share of its variance\n");
  for (const auto& [name, m] : s["methods"].items()) {
    const auto& e = m["tip_error_mm"];
    const std::string dominant = m["dominant"].get<std::string>();
    const double share =
        m["regression"].value("variance_share", nlohmann::json::object()).value(dominant, 0.0);
    std::printf("  %-12s %9.4f %7.4f %7.4f   %s (%.0f %%)\n", name.c_str(), e["p50"].get<double>(),
                e["p95"].get<double>(), e["max"].get<double>(),
                dominant.empty() ? "(too few trials)" : dominant.c_str(), 100.0 * share);
  }
  for (const auto& [name, h] : s["honesty"].items()) {
    std::printf("  %-8s NEES mean %.3f (95 %% band [%.3f, %.3f]), NEES <= chi2(2, 0.95): %.1f %%, "
                "95 %% coverage: %.1f %% (picked sample), %.1f %% (held samples: j1 %.1f %%, "
                "j2 %.1f %%)\n",
                name.c_str(), h["nees_mean"].get<double>(), h["nees_band_95"][0].get<double>(),
                h["nees_band_95"][1].get<double>(), 100.0 * h["nees_within_chi2_95"].get<double>(),
                100.0 * h["coverage_95_picked_sample"].get<double>(),
                100.0 * h["coverage_95_held_samples"].get<double>(),
                100.0 * h["coverage_95_held_samples_by_joint"][0].get<double>(),
                100.0 * h["coverage_95_held_samples_by_joint"][1].get<double>());
  }
}

void RunMontecarloCommand(const MontecarloCommandOptions& options) {
  io::CheckOutputDirectory(options.run.output_dir, "-o");
  const auto study = experiments::ReadStudy(options.study_path);
  const bool mpi = LaunchedByMpirun();
  const auto summary = mpi ? RunMontecarloMpi(study, options.run)
                           : experiments::RunMontecarlo(study, options.run);
  if (summary.is_null()) return;  // an MPI rank other than 0
  PrintSummary(summary, options.run.output_dir);
  std::ifstream timing_file(options.run.output_dir + "/timing.json");
  const auto timing = nlohmann::json::parse(timing_file);
  std::printf("  %d trials run now on %d rank(s) × %d thread(s) in %.1f s (%.3f s per trial)\n",
              timing["trials_run"].get<int>(), timing["ranks"].get<int>(),
              timing["threads"].get<int>(), timing["wall_s"].get<double>(),
              timing["seconds_per_trial"].get<double>());
}

}  // namespace

Command AddMontecarloCommand(CLI::App& app) {
  auto options = std::make_shared<MontecarloCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "montecarlo", "Monte Carlo accuracy study of the corrections (docs/montecarlo.md); "
                    "threads here, MPI under mpirun; resumes an interrupted study");
  sub->add_option("study", options->study_path,
                  "Study file (JSON), e.g. experiments/studies/divot_study.json")
      ->required();
  sub->add_option("-o,--output", options->run.output_dir,
                  "Results directory: trials.csv, summary.json, timing.json, plots")
      ->required();
  sub->add_option("--threads", options->run.threads,
                  "Worker threads (default: every core; 1 per rank under mpirun)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--trials", options->run.trials, "Number of trials (default: the study's)")
      ->check(CLI::Range(1, 100000000));
  sub->add_flag("--no-plots", [options](std::int64_t) { options->run.plots = false; },
                "Skip the plots (no gnuplot needed)");
  return [options] { RunMontecarloCommand(*options); };
}

}  // namespace pliant::cli
