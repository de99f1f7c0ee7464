// Parallel efficiency of `pliant montecarlo`'s thread pool: the same 200
// trials of experiments/studies/divot_study.json on 1 thread (the baseline)
// and on 2 threads, in one run. Recorded in docs/validation-studies.md, section 8.
//   build/bench/montecarlo_bench --benchmark_counters_tabular=true
// trials_per_s is per wall second; efficiency = (2-thread rate) / (2 × 1-thread
// rate). On a shared machine other jobs take cores: cpu_per_trial_ms shows
// the work itself, which does not depend on the split.
#include <benchmark/benchmark.h>

#include <ctime>

#include "pliant/experiments/montecarlo.h"

namespace {

using namespace pliant::experiments;

void Trials(benchmark::State& state) {
  static const Study study = ReadStudy(PLIANT_SOURCE_DIR "/experiments/studies/divot_study.json");
  std::vector<int> trials(200);
  for (int k = 0; k < 200; ++k) trials[k] = k;
  double done = 0.0, cpu_s = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();  // process CPU time, all threads
    RunTrials(study, trials, static_cast<int>(state.range(0)), [&](const TrialResult& r) {
      benchmark::DoNotOptimize(r.tip_error_mm[0]);
      done += 1.0;
    });
    cpu_s += double(std::clock() - start) / CLOCKS_PER_SEC;
  }
  state.counters["trials_per_s"] = benchmark::Counter(done, benchmark::Counter::kIsRate);
  state.counters["cpu_per_trial_ms"] = 1e3 * cpu_s / done;
}

BENCHMARK(Trials)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
