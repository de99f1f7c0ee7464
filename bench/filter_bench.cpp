// step() of the online filter, side by side in one run with
//   equation2      — the paper's correction (ComplianceCorrector): the floor,
//   dense_fixed    — a straightforward fixed-size Eigen EKF of the same model
//                    (Jet Jacobians, dense Joseph update; bench/filter_baselines.h),
//   dense_dynamic  — the same with dynamic-size Eigen matrices,
//   contact        — the filter without the tip_fixed hint (contact inferred),
//   deflection     — the filter with one deflection effect in the parameters,
//   friction       — the filter with one internal-torque effect in the parameters,
// on a 1.5 kHz divot-push log drawn from the model. Each benchmark times every
// step on its own (steady_clock, its overhead subtracted) and reports the
// median and the 99th percentile in ns, and the heap allocations per step.
// offline_900k filters and smooths 10 minutes of log (900,000 samples). Run:
//   build/bench/filter_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <vector>

#include "../tests/estimation/filter_synthetic.h"
#include "filter_baselines.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/filter.h"
#include "pliant/estimation/filter_smoother.h"

// Heap allocations are counted while `counting` is set. Every one goes through
// malloc (operator new does, and so does Eigen's allocator for dynamic sizes).
extern "C" void* __libc_malloc(std::size_t);
namespace {
std::atomic<long> allocations{0};
std::atomic<bool> counting{false};
}  // namespace
extern "C" void* malloc(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace {

using pliant::estimation::FilterSample;
using Clock = std::chrono::steady_clock;

const std::vector<FilterSample>& Samples() {
  static const std::vector<FilterSample> samples = [] {
    pliant::estimation::testing::SyntheticOptions so;
    so.duration_s = 20.0;
    so.load_noise_nm = 0.1;
    return pliant::estimation::testing::MakeSyntheticRun(
               pliant::models::testing::PaperParameters(), pliant::estimation::FilterOptions{}, so)
        .samples;
  }();
  return samples;
}

double ClockOverheadNs() {
  static const double overhead = [] {
    std::vector<double> d(100000);
    for (auto& v : d) {
      const auto a = Clock::now();
      const auto b = Clock::now();
      v = std::chrono::duration<double, std::nano>(b - a).count();
    }
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return d[d.size() / 2];
  }();
  return overhead;
}

// Runs `step(sample)` once per iteration over the log (time continuing past
// its end), timing each call on its own.
template <typename Step>
void TimeSteps(benchmark::State& state, Step&& step) {
  const auto& samples = Samples();
  const double overhead = ClockOverheadNs();
  std::vector<double> ns;
  ns.reserve(4'000'000);
  std::size_t k = 0;
  const double dt = 1.0 / 1500.0;
  allocations = 0;
  counting = true;
  for (auto _ : state) {
    FilterSample s = samples[k % samples.size()];
    s.time_s = double(k) * dt;
    const auto a = Clock::now();
    step(s);
    const auto b = Clock::now();
    if (ns.size() < ns.capacity()) ns.push_back(std::chrono::duration<double, std::nano>(b - a).count() - overhead);
    ++k;
  }
  counting = false;
  std::sort(ns.begin(), ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
  state.counters["p99_ns"] = ns[std::size_t(0.99 * double(ns.size()))];
  state.counters["p99/median"] = ns[std::size_t(0.99 * double(ns.size()))] / ns[ns.size() / 2];
  state.counters["allocs_per_step"] = double(allocations.load()) / double(k);
}

void BM_Equation2(benchmark::State& state) {
  const pliant::estimation::ComplianceCorrector corrector(
      pliant::models::testing::PaperParameters(), pliant::estimation::CorrectionModel::kPaper);
  TimeSteps(state, [&](const FilterSample& s) {
    benchmark::DoNotOptimize(corrector.Correct(
        Eigen::Vector3d(s.encoder_rad[0], s.encoder_rad[1], s.insertion_depth_m), s.effort_nm));
  });
}

void BM_FilterStep(benchmark::State& state) {
  pliant::estimation::ComplianceFilter filter(pliant::models::testing::PaperParameters());
  TimeSteps(state, [&](const FilterSample& s) { benchmark::DoNotOptimize(filter.Step(s)); });
}

// With motor inertia: the state runs the inertial alignment's 18 samples
// behind, and each Step carries its estimate to the newest sample. What that
// costs on top of BM_FilterStep (the dense baselines have no alignment).
void BM_FilterStepAligned(benchmark::State& state) {
  pliant::estimation::FilterOptions options;
  options.motor_inertia_kg_m2 = 0.08;
  pliant::estimation::ComplianceFilter filter(pliant::models::testing::PaperParameters(), options);
  TimeSteps(state, [&](const FilterSample& s) { benchmark::DoNotOptimize(filter.Step(s)); });
}

// With the effort's correlated noise carried as a Gauss–Markov effort offset
// β (σ 10 mN·m over 20 ms, as `pliant filter` sets it where a log's still
// stretches show it: docs/decisions/coloured-effort-noise.md): β's decay
// and its share of every update. What that costs on top of BM_FilterStep.
void BM_FilterStepColouredEffort(benchmark::State& state) {
  pliant::estimation::FilterOptions options;
  options.effort_offset_sd_nm.setConstant(0.01);
  options.effort_offset_correlation_s.setConstant(0.02);
  pliant::estimation::ComplianceFilter filter(pliant::models::testing::PaperParameters(), options);
  TimeSteps(state, [&](const FilterSample& s) { benchmark::DoNotOptimize(filter.Step(s)); });
}

// The same log without the tip_fixed hint, as online: contact is inferred
// (FilterOptions::infer_contact, the two-hypothesis collapse) and the arm's
// own torque learned (a 4×4 information update per joint). What the contact
// model costs on top of BM_FilterStep (the dense baselines have none).
void BM_FilterStepContact(benchmark::State& state) {
  pliant::estimation::ComplianceFilter filter(pliant::models::testing::PaperParameters());
  TimeSteps(state, [&](FilterSample s) {
    s.tip_fixed = false;
    benchmark::DoNotOptimize(filter.Step(s));
  });
}

// With one deflection effect in the parameters (deflection_coupling: the
// encoder model's Jet through the catalogue code, and the other joint's load
// as a consider input). What the file's deflection effects cost on top of
// BM_FilterStep. (The log is the same: the cost, not the fit, is measured.)
// Arg 1: with the σ an identification writes, which the filter considers
// (ExtraEffects::ConsideredVariance: a Jet over the effect's parameters).
void BM_FilterStepDeflection(benchmark::State& state) {
  auto parameters = pliant::models::testing::PaperParameters();
  const double sd = state.range(0) ? 0.001 : 0.0;
  parameters.effects.push_back({"deflection_coupling", {"k12", "k21"}, {0.006, 0.004}, {sd, sd}});
  pliant::estimation::ComplianceFilter filter(parameters);
  TimeSteps(state, [&](const FilterSample& s) { benchmark::DoNotOptimize(filter.Step(s)); });
}

// With one internal-torque effect in the parameters (joint_friction, the
// real PSM2's friction fitted to the shared free-motion bag: docs/decisions/
// contact-rates.md): the catalogue code evaluated at each row's velocity and
// taken out of the effort. What the file's internal-torque effects cost on
// top of BM_FilterStep; Arg 1: with σ, as BM_FilterStepDeflection.
void BM_FilterStepFriction(benchmark::State& state) {
  auto parameters = pliant::models::testing::PaperParameters();
  const double sd = state.range(0) ? 0.01 : 0.0;
  parameters.effects.push_back({"joint_friction",
                                {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"},
                                {0.12, 0.33, 0.15, 0.14, 0.05},
                                {sd, sd, sd, sd, sd}});
  pliant::estimation::ComplianceFilter filter(parameters);
  TimeSteps(state, [&](const FilterSample& s) { benchmark::DoNotOptimize(filter.Step(s)); });
}

// Online (as BM_FilterStepContact) with the arm's dynamics identified on its
// free motion (the real PSM2 bag's joint_inertia and joint_friction,
// docs/decisions/arm-dynamics-from-free-motion.md): taken out of the effort,
// and, Arg 1, their σ the learned torque's prior with the considered share
// apart. What they cost on top of BM_FilterStepContact.
void BM_FilterStepArmDynamics(benchmark::State& state) {
  auto parameters = pliant::models::testing::PaperParameters();
  const bool sd = state.range(0) != 0;
  parameters.effects.push_back(
      {"joint_friction", {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"},
       {0.13, 0.41, 0.137, 0.124, 0.031},
       sd ? std::vector<double>{0.027, 0.16, 0.015, 0.025, 0.011} : std::vector<double>(5, 0.0)});
  parameters.effects.push_back({"joint_inertia", {"inertia1", "inertia2"}, {0.217, 0.165},
                                sd ? std::vector<double>{0.009, 0.021} : std::vector<double>{0, 0}});
  pliant::estimation::ComplianceFilter filter(parameters);
  TimeSteps(state, [&](FilterSample s) {
    s.tip_fixed = false;
    benchmark::DoNotOptimize(filter.Step(s));
  });
}

void BM_DenseFixedEkf(benchmark::State& state) {
  pliant::bench::DenseFixedEkf ekf(pliant::models::testing::PaperParameters(), {});
  TimeSteps(state, [&](const FilterSample& s) {
    ekf.Step(s);
    benchmark::DoNotOptimize(ekf.mean());
  });
}

void BM_DenseDynamicEkf(benchmark::State& state) {
  pliant::bench::DenseDynamicEkf ekf(pliant::models::testing::PaperParameters(), {});
  TimeSteps(state, [&](const FilterSample& s) {
    ekf.Step(s);
    benchmark::DoNotOptimize(ekf.mean());
  });
}

// 10 minutes at 1.5 kHz: filter forward, smooth backward, read every estimate.
void BM_Offline900k(benchmark::State& state) {
  const auto& samples = Samples();
  constexpr std::size_t kSamples = 900'000;
  for (auto _ : state) {
    pliant::estimation::FilterSmoother smoother(pliant::models::testing::PaperParameters());
    smoother.Reserve(kSamples);
    for (std::size_t k = 0; k < kSamples; ++k) {
      FilterSample s = samples[k % samples.size()];
      s.time_s = double(k) / 1500.0;
      smoother.Add(s);
    }
    smoother.Smooth();
    double sum = 0.0;
    for (std::size_t k = 0; k < kSamples; ++k) sum += smoother.Estimate(k).corrected_rad[0];
    benchmark::DoNotOptimize(sum);
  }
  state.counters["samples"] = double(kSamples);
}

BENCHMARK(BM_Equation2)->Iterations(2'000'000);
BENCHMARK(BM_FilterStep)->Iterations(2'000'000);
BENCHMARK(BM_FilterStepAligned)->Iterations(2'000'000);
BENCHMARK(BM_FilterStepColouredEffort)->Iterations(2'000'000);
BENCHMARK(BM_FilterStepContact)->Iterations(2'000'000);
BENCHMARK(BM_FilterStepFriction)->Iterations(2'000'000)->Arg(0)->Arg(1);
BENCHMARK(BM_FilterStepDeflection)->Iterations(2'000'000)->Arg(0)->Arg(1);
BENCHMARK(BM_FilterStepArmDynamics)->Iterations(2'000'000)->Arg(0)->Arg(1);
BENCHMARK(BM_DenseFixedEkf)->Iterations(2'000'000);
BENCHMARK(BM_DenseDynamicEkf)->Iterations(1'000'000);
BENCHMARK(BM_Offline900k)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
