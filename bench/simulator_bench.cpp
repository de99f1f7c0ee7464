// Real-time factor of the simulator (simulated seconds per wall second, one
// thread) on each of the paper's scenarios, run in full as the scenario files
// describe them. Recorded in docs/validation-studies.md (section 9).
//   build/bench/simulator_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <ctime>
#include <string>

#include "pliant/experiments/scenario.h"
#include "pliant/experiments/simulator.h"

namespace {

void Scenario(benchmark::State& state, const std::string& name) {
  const auto scenario = pliant::experiments::ReadScenario(
      std::string(PLIANT_SOURCE_DIR) + "/experiments/scenarios/" + name + ".json");
  double simulated_s = 0.0, periods = 0.0, steps = 0.0, cpu_s = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    const auto result = pliant::experiments::Simulate(scenario, 1);
    cpu_s += double(std::clock() - start) / CLOCKS_PER_SEC;
    simulated_s += result.stats.simulated_s;
    periods += double(result.stats.controller_periods);
    steps += double(result.stats.integrator_steps);
    benchmark::DoNotOptimize(result.log.values.data());
  }
  // kIsRate divides by the wall time: simulated seconds per second.
  state.counters["real_time_factor"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  // The same per CPU second: what one unshared core gives (the 2-core build
  // machine is often busy, which stretches the wall time).
  state.counters["rtf_cpu"] = simulated_s / cpu_s;
  state.counters["simulated_s"] = simulated_s / double(state.iterations());
  state.counters["steps_per_period"] = steps / periods;
}

BENCHMARK_CAPTURE(Scenario, bias_sweep, std::string("bias_sweep"))
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(Scenario, clamped_beam, std::string("clamped_beam"))
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(Scenario, divot, std::string("divot"))
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(Scenario, free_motion, std::string("free_motion"))
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
