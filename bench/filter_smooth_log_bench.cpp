// `pliant filter` and `pliant filter --smooth` on one long log, side by side:
// FilterLog without and with the smoother (the checkpointed pass of
// estimation/src/smoothed_pass.h), each run in a child process so that its
// peak resident memory is its own (getrusage of the child). Reports the wall
// time (manual time), peak_rss_MB, and for the smoothed pass time_ratio, its
// time over the plain filter's of the same run.
//
// The log: $PLIANT_LONG_LOG if set (bench/long_log_memory.sh simulates a
// 10⁷-row one), else $PLIANT_BENCH_ROWS rows (default 10⁶) of the synthetic
// divot push at 1.5 kHz written to TMPDIR. Run:
//   build/bench/filter_smooth_log_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../tests/estimation/filter_synthetic.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/io/log_writer.h"

namespace {

namespace fs = std::filesystem;
using pliant::estimation::FilterSample;

std::size_t RowsWanted() {
  const char* rows = std::getenv("PLIANT_BENCH_ROWS");
  return rows ? std::size_t(std::atof(rows)) : 1'000'000;
}

// The synthetic divot push (20 s), repeated with time running on.
std::string WriteSyntheticLog(std::size_t rows) {
  pliant::estimation::testing::SyntheticOptions options;
  options.duration_s = 20.0;
  options.load_noise_nm = 0.1;
  const auto run = pliant::estimation::testing::MakeSyntheticRun(
      pliant::models::testing::PaperParameters(), pliant::estimation::FilterOptions{}, options);
  pliant::io::LogHeader header;
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "q1_true", "q2_true", "tip_fixed"};
  const std::string path =
      (fs::temp_directory_path() / ("pliant_smooth_bench_" + std::to_string(getpid()) + ".csv"))
          .string();
  pliant::io::LogWriter writer(path, header);
  for (std::size_t k = 0; k < rows; ++k) {
    const std::size_t i = k % run.samples.size();
    const FilterSample& s = run.samples[i];
    const double row[] = {double(k) / 1500.0, s.encoder_rad[0], s.encoder_rad[1],
                          s.insertion_depth_m, s.effort_nm[0], s.effort_nm[1],
                          run.truth[i][0], run.truth[i][1], s.tip_fixed ? 1.0 : 0.0};
    writer.Write(row);
  }
  writer.Commit();
  return path;
}

struct Log {
  std::string path;
  bool owned = false;
  ~Log() {
    if (owned) fs::remove(path);
  }
};

const Log& TheLog() {
  static const Log log = [] {
    if (const char* given = std::getenv("PLIANT_LONG_LOG")) return Log{given, false};
    return Log{WriteSyntheticLog(RowsWanted()), true};
  }();
  return log;
}

struct Run {
  double seconds = 0.0;
  double peak_rss_mb = 0.0;
};

// FilterLog in a child process: its wall time and its peak resident memory.
Run FilterInChild(bool smooth) {
  const std::string out = TheLog().path + (smooth ? ".smoothed.csv" : ".filtered.csv");
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    try {
      pliant::estimation::FilterLog(TheLog().path, out, pliant::models::testing::PaperParameters(),
                                    {}, smooth, "");
    } catch (...) {
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  Run run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_rss_mb = double(usage.ru_maxrss) / 1024.0;  // kB on Linux
  fs::remove(out);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) run.seconds = -1.0;
  return run;
}

double plain_seconds = 0.0;  // the baseline of the same run

void BM_FilterLog(benchmark::State& state) {
  for (auto _ : state) {
    const Run run = FilterInChild(false);
    if (run.seconds < 0) state.SkipWithError("FilterLog failed");
    state.SetIterationTime(run.seconds);
    state.counters["peak_rss_MB"] = run.peak_rss_mb;
    plain_seconds = run.seconds;
  }
}

void BM_FilterLogSmoothed(benchmark::State& state) {
  for (auto _ : state) {
    const Run run = FilterInChild(true);
    if (run.seconds < 0) state.SkipWithError("FilterLog --smooth failed");
    state.SetIterationTime(run.seconds);
    state.counters["peak_rss_MB"] = run.peak_rss_mb;
    state.counters["time_ratio"] = plain_seconds > 0 ? run.seconds / plain_seconds : 0.0;
  }
}

BENCHMARK(BM_FilterLog)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_FilterLogSmoothed)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
