// What a control loop relies on: Step() never touches the heap, and keeps the
// covariance finite, symmetric and positive definite whatever it is fed.
#include <cstdlib>
#include <new>
#include <random>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "filter_synthetic.h"
#include "pliant/estimation/filter.h"

// Every heap allocation of this test program goes through malloc (operator new
// does, and so does Eigen's aligned allocator): count them while `counting`.
// AddressSanitizer owns malloc itself, so under it the count is not taken.
#if defined(__SANITIZE_ADDRESS__)
#define PLIANT_COUNTS_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PLIANT_COUNTS_ALLOCATIONS 0
#endif
#endif
#ifndef PLIANT_COUNTS_ALLOCATIONS
#define PLIANT_COUNTS_ALLOCATIONS 1
#endif

namespace {
volatile bool counting = false;
volatile long allocations = 0;
}  // namespace
#if PLIANT_COUNTS_ALLOCATIONS
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void* malloc(std::size_t size) {
  if (counting) allocations = allocations + 1;
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t n, std::size_t size) {
  if (counting) allocations = allocations + 1;
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t size) {
  if (counting) allocations = allocations + 1;
  return __libc_realloc(p, size);
}
#endif

namespace pliant::estimation {
namespace {

bool IsHealthy(const pliant::estimation::FilterStateMatrix& p) {
  if (!p.allFinite() || p != p.transpose()) return false;
  return Eigen::LLT<pliant::estimation::FilterStateMatrix>(p).info() == Eigen::Success;
}

TEST(FilterRealTime, StepNeverAllocates) {
  if (!PLIANT_COUNTS_ALLOCATIONS) GTEST_SKIP() << "AddressSanitizer replaces malloc";
  const auto p = models::testing::PaperParameters();
  FilterOptions o;
  testing::SyntheticOptions so;
  so.duration_s = 4.0;
  auto run = testing::MakeSyntheticRun(p, o, so);
  // Every path: references, NaNs, saturation, outliers (gate, re-acquire).
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    auto& s = run.samples[k];
    if (k % 7 == 0) s.reference_rad = s.encoder_rad;
    if (k % 101 == 0) s.encoder_rad[0] = FilterSample::kMissing;
    if (k % 97 == 0) s.effort_nm[1] = 5.0;
    if (k >= 3000 && k < 3100) s.encoder_rad[1] += 0.1;
  }
  // With motor inertia too: the alignment's held samples live in a ring
  // sized at construction.
  ComplianceFilter filter(p, o);
  // With a file's effects and their σ (ConsideredVariance's Jets).
  auto with_effects = p;
  with_effects.effects = {
      {"joint_friction",
       {"viscous1", "viscous2", "coulomb1", "coulomb2", "velocity_scale"},
       {0.1, 0.1, 0.05, 0.05, 0.005},
       {0.01, 0.01, 0.01, 0.01, 0.001}},
      {"deflection_coupling", {"k12", "k21"}, {0.006, 0.004}, {0.001, 0.001}}};
  ComplianceFilter effects(with_effects, o);
  o.motor_inertia_kg_m2 = 0.08;
  ComplianceFilter aligned(p, o);
  ASSERT_GT(aligned.alignment_steps(), 0);
  // The test's own first malloc (gtest, locale) happens outside the window.
  const long before = allocations;
  counting = true;
  std::uint32_t seen = 0;
  for (const auto& s : run.samples) seen |= filter.Step(s).flags;
  for (const auto& s : run.samples) aligned.Step(s);
  for (const auto& s : run.samples) effects.Step(s);
  while (aligned.StepHeldSample()) {
  }
  counting = false;
  EXPECT_EQ(allocations - before, 0);
  EXPECT_TRUE(seen & kFlagRejected);
  EXPECT_TRUE(seen & kFlagReacquired);
  EXPECT_TRUE(seen & kFlagMissing);
  EXPECT_TRUE(seen & kFlagEffortSaturated);
}

TEST(FilterRealTime, CountsAllocationsWhenThereAreSome) {  // the counter works
  if (!PLIANT_COUNTS_ALLOCATIONS) GTEST_SKIP() << "AddressSanitizer replaces malloc";
  const long before = allocations;
  counting = true;
  void* volatile p = std::malloc(64);
  counting = false;
  std::free(p);
  EXPECT_EQ(allocations - before, 1);
}

// 10⁷ steps (about 2 s) of a model log with random outliers, NaNs, effort
// saturation and depth jumps: the covariance stays finite, symmetric and
// positive definite at every step, and the estimate is back on the truth
// within 100 steps after the last outlier burst.
TEST(FilterRealTime, TenMillionHostileStepsKeepTheCovarianceHealthy) {
  const auto p = models::testing::PaperParameters();
  const FilterOptions o;
  testing::SyntheticOptions so;
  so.duration_s = 40.0;
  so.load_noise_nm = 0.1;
  const auto run = testing::MakeSyntheticRun(p, o, so);
  ComplianceFilter filter(p, o);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  constexpr long kSteps = 10'000'000;
  const long quiet_from = kSteps - 200;
  long unhealthy = 0;
  FilterEstimate e;
  for (long k = 0; k < kSteps; ++k) {
    FilterSample s = run.samples[std::size_t(k) % run.samples.size()];
    s.time_s = double(k) / 1500.0;
    if (k < quiet_from) {
      const double u = uniform(rng);
      if (u < 1e-3) s.encoder_rad[0] += 0.2 * (uniform(rng) - 0.5);
      else if (u < 2e-3) s.effort_nm[1] += 4.0 * (uniform(rng) - 0.5);
      else if (u < 3e-3) s.encoder_rad[1] = FilterSample::kMissing;
      else if (u < 4e-3) s.effort_nm[0] = FilterSample::kMissing;
      else if (u < 5e-3) s.insertion_depth_m = uniform(rng) * 0.3;
      else if (u < 5.5e-3) s.insertion_depth_m = FilterSample::kMissing;
      else if (u < 6e-3) s.effort_nm[0] = 3.4;
      if (k % 1'000'000 < 60) s.encoder_rad += Eigen::Vector2d(0.05, -0.05);  // a burst
    }
    e = filter.Step(s);
    if ((k & 63) == 0 || k >= quiet_from) {
      unhealthy += !IsHealthy(filter.joint_state(0).covariance);
      unhealthy += !IsHealthy(filter.joint_state(1).covariance);
    }
    if (k == quiet_from + 100) {
      const Eigen::Vector2d truth = run.truth[std::size_t(k) % run.samples.size()];
      for (int j = 0; j < 2; ++j) {
        const double sd = std::sqrt(e.covariance_rad2(j, j));
        EXPECT_LT(std::abs(e.corrected_rad[j] - truth[j]), std::max(4.0 * sd, 5e-5)) << j;
      }
    }
  }
  EXPECT_EQ(unhealthy, 0);
}

}  // namespace
}  // namespace pliant::estimation
