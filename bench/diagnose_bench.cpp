// Speed of Diagnose() on a 60 s log at the dVRK's 1.5 kHz (issue 6: "seconds,
// not minutes"), beside the online filter over the same log as the baseline.
//   build/bench/diagnose_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "../tests/diagnostics/diagnosis_support.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/estimation/filter_log.h"

namespace {

struct Fixture {
  pliant::experiments::Scenario scenario;
  pliant::io::Log log;
};

// The test divot at every controller period, its 12 pushes slowed to fill ~60 s,
// with friction hidden.
const Fixture& SixtySecondLog() {
  static const Fixture fixture = [] {
    Fixture f;
    f.scenario = pliant::testing::ShortDivot(R"({"joint_friction":{"coulomb1":0.05,"coulomb2":0.05}})",
                                             {"log.every_n_periods=1", "experiment.hold_s=1.6"});
    f.log = pliant::experiments::Simulate(f.scenario, 1).log;
    return f;
  }();
  return fixture;
}

void BM_Diagnose(benchmark::State& state) {
  const Fixture& f = SixtySecondLog();
  const auto model = pliant::testing::ModelOf(f.scenario);
  for (auto _ : state) {
    auto d = pliant::estimation::Diagnose(f.log, "divot.csv", model, {});
    benchmark::DoNotOptimize(d);
  }
  state.counters["rows"] = double(f.log.Rows());
  state.counters["log_s"] = f.log.Value(f.log.Rows() - 1, 0);
}

void BM_FilterBaseline(benchmark::State& state) {
  const Fixture& f = SixtySecondLog();
  const pliant::io::StandardColumns columns(f.log.header);
  for (auto _ : state) {
    pliant::estimation::ComplianceFilter filter(pliant::testing::ModelOf(f.scenario));
    for (std::size_t r = 0; r < f.log.Rows(); ++r)
      benchmark::DoNotOptimize(
          filter.Step(pliant::estimation::SampleFromRow(columns, &f.log.values[r * f.log.Columns()], false)));
  }
  state.counters["rows"] = double(f.log.Rows());
}

}  // namespace

BENCHMARK(BM_FilterBaseline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Diagnose)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
