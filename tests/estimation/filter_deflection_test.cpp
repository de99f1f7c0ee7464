// The filter applies the parameters file's deflection effects (filter.h,
// filter_deflection.cpp): logs drawn from the filter's own model with a
// catalogue deflection effect added to the encoders, filtered with the effect
// at its true value and without it. Known truth: the tip angle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "filter_synthetic.h"
#include "pliant/estimation/extra_effects.h"
#include "pliant/estimation/filter_smoother.h"

namespace pliant::estimation {
namespace {

using testing::MakeSyntheticRun;
using testing::ModelLogOptions;
using testing::SyntheticOptions;
using testing::SyntheticRun;

models::ModelParameters WithEffect(const std::string& name, const std::vector<std::string>& names,
                                   const std::vector<double>& values) {
  models::ModelParameters p = models::testing::PaperParameters();
  p.effects.push_back({name, names, values, std::vector<double>(values.size(), 0.0)});
  return p;
}

// The run with the effect's deflection at the true load in each encoder (and
// the bias torque, which the effort reads at the encoder angle, moved with it).
SyntheticRun DeflectedRun(const models::ModelParameters& truth, const SyntheticOptions& so) {
  SyntheticRun run = MakeSyntheticRun(truth, ModelLogOptions(), so);
  const ExtraEffects effects(truth.effects);
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    FilterSample& s = run.samples[k];
    models::JointState<double> state;
    state.encoder_angle_rad = s.encoder_rad;
    state.insertion_depth_m = s.insertion_depth_m;
    state.external_torque_nm = run.true_torque[k];
    for (int j = 0; j < 2; ++j)
      state.compliance_rad_per_nm[j] = models::ComplianceAt(truth.joints[j], s.insertion_depth_m);
    const Eigen::Vector2d deflection = effects.Deflection(state);
    for (int j = 0; j < 2; ++j) {
      const auto& jp = truth.joints[j];
      const double before = models::BiasTorqueAt(jp, s.encoder_rad[j], s.insertion_depth_m);
      s.encoder_rad[j] += deflection[j];
      s.effort_nm[j] += models::BiasTorqueAt(jp, s.encoder_rad[j], s.insertion_depth_m) - before;
    }
  }
  return run;
}

// Squared errors and 95 % interval hits of the corrected angle, per joint,
// summed over the rows (of any number of runs) a test scores.
struct Score {
  double sum_sq[2] = {0.0, 0.0};
  long rows[2] = {0, 0};
  long inside[2] = {0, 0};
  double Rms(int j) const { return std::sqrt(sum_sq[j] / double(rows[j])); }
  double Covered(int j) const { return double(inside[j]) / double(rows[j]); }
};

using Loaded = std::function<bool(const SyntheticRun&, std::size_t, int)>;

// The rows after the first second (the filter has met both walls) that
// `loaded` picks.
template <typename Estimates>
void AddRows(const SyntheticRun& run, const Estimates& estimate, const Loaded& loaded,
             Score* score) {
  for (int j = 0; j < 2; ++j) {
    for (std::size_t k = 1500; k < run.samples.size(); ++k) {
      if (!loaded(run, k, j)) continue;
      const FilterEstimate e = estimate(k);
      const double error = e.corrected_rad[j] - run.truth[k][j];
      score->sum_sq[j] += error * error;
      score->inside[j] += std::abs(error) <= 1.96 * std::sqrt(e.covariance_rad2(j, j));
      ++score->rows[j];
    }
  }
}

void AddFilterRows(const models::ModelParameters& p, const SyntheticRun& run,
                   const Loaded& loaded, Score* score) {
  ComplianceFilter filter(p, ModelLogOptions());
  std::vector<FilterEstimate> out;
  for (const auto& s : run.samples) out.push_back(filter.Step(s));
  AddRows(run, [&](std::size_t k) { return out[k]; }, loaded, score);
}

SyntheticOptions Pushes(unsigned seed) {
  SyntheticOptions so;
  so.duration_s = 8.0;
  so.seed = seed;
  so.load_noise_nm = 0.05;
  so.draw_shaft_start = true;
  return so;
}

// A held tip's error is nearly one number per run: coverage is counted over
// many runs. Scores, over kSeeds runs, the filter on the log without the
// effect (the reference: the filter on its own model), and on the log with
// it, filtered without and with the effect.
constexpr unsigned kSeeds = 12;
struct Comparison {
  Score clean, without, with;
};
Comparison Compare(const models::ModelParameters& truth, const Loaded& loaded) {
  Comparison c;
  const auto paper = models::testing::PaperParameters();
  for (unsigned seed = 1; seed <= kSeeds; ++seed) {
    AddFilterRows(paper, MakeSyntheticRun(truth, ModelLogOptions(), Pushes(seed)), loaded,
                  &c.clean);
    const SyntheticRun run = DeflectedRun(truth, Pushes(seed));
    AddFilterRows(paper, run, loaded, &c.without);
    AddFilterRows(truth, run, loaded, &c.with);
  }
  for (int j = 0; j < 2; ++j) {
    std::printf("%s joint %d: RMS %.4f mrad (no effect in the log), with the effect %.4f -> "
                "%.4f mrad; covered %.3f, %.3f -> %.3f\n",
                truth.effects[0].name.c_str(), j + 1, 1e3 * c.clean.Rms(j),
                1e3 * c.without.Rms(j), 1e3 * c.with.Rms(j), c.clean.Covered(j),
                c.without.Covered(j), c.with.Covered(j));
  }
  return c;
}

// With the effect at its true value the loaded rows are as close to the
// truth as on a log without the effect, and their 95 % intervals cover as
// often; without it the intervals miss.
void ExpectCorrectedAndHonest(const Comparison& c) {
  for (int j = 0; j < 2; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j + 1));
    EXPECT_LT(c.with.Rms(j), 0.05 * c.without.Rms(j));
    EXPECT_LT(c.with.Rms(j), 1.5 * c.clean.Rms(j));
    EXPECT_LT(c.without.Covered(j), 0.2);
    EXPECT_NEAR(c.with.Covered(j), c.clean.Covered(j), 0.05);
  }
}

// deflection_coupling (k12 = 6, k21 = 4 mrad per N·m, as data/divot_hidden_effect.csv):
// each joint's encoder carries the other joint's load. Rows where the other
// joint is loaded past 0.3 N·m, where the coupling moves the encoder ≥ 1.2 mrad.
TEST(FilterDeflection, TheCouplingAtItsTrueValueCorrectsTheLoadedRowsAndStaysHonest) {
  const auto truth = WithEffect("deflection_coupling", {"k12", "k21"}, {0.006, 0.004});
  const Comparison c = Compare(truth, [](const SyntheticRun& run, std::size_t k, int j) {
    return std::abs(run.true_torque[k][1 - j]) > 0.3;
  });
  ExpectCorrectedAndHonest(c);
}

// load_dependent_compliance (γ = 0.2 /(N·m)² and β = −0.1 /(N·m) on joint 1:
// 0.1·K(L), about 5 mrad, at 1 N·m; joint 2, stiffer and loaded less in these
// runs, 0.8 and −0.2; the incremental compliance K·(1 + 2β|τ| + 3γτ²)): the
// effect's own slope enters the encoder's row and the held load's increment.
// Rows loaded past 0.5 N·m.
TEST(FilterDeflection, ALoadDependentComplianceAtItsTrueValueCorrectsTheLoadedRows) {
  const auto truth = WithEffect("load_dependent_compliance", {"gamma1", "gamma2", "beta1", "beta2"},
                                {0.2, 0.8, -0.1, -0.2});
  const Comparison c = Compare(truth, [](const SyntheticRun& run, std::size_t k, int j) {
    return std::abs(run.true_torque[k][j]) > 0.5;
  });
  ExpectCorrectedAndHonest(c);
}

// The smoother runs on the forward filter's passes: with the effect on it is
// at least as close as the filter on the loaded rows, and as honest.
TEST(FilterDeflection, TheSmootherWithTheCouplingIsConsistentWithTheFilter) {
  const auto truth = WithEffect("deflection_coupling", {"k12", "k21"}, {0.006, 0.004});
  const Loaded other_loaded = [](const SyntheticRun& run, std::size_t k, int j) {
    return std::abs(run.true_torque[k][1 - j]) > 0.3;
  };
  Score filtered, smoothed;
  for (unsigned seed = 1; seed <= kSeeds; ++seed) {
    const SyntheticRun run = DeflectedRun(truth, Pushes(seed));
    FilterSmoother smoother(truth, ModelLogOptions());
    for (const auto& s : run.samples) smoother.Add(s);
    const auto estimate = [&](std::size_t k) { return smoother.Estimate(k); };
    AddRows(run, estimate, other_loaded, &filtered);
    smoother.Smooth();
    AddRows(run, estimate, other_loaded, &smoothed);
  }
  for (int j = 0; j < 2; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j + 1));
    std::printf("smoother joint %d: RMS %.4f -> %.4f mrad, covered %.3f -> %.3f\n", j + 1,
                1e3 * filtered.Rms(j), 1e3 * smoothed.Rms(j), filtered.Covered(j),
                smoothed.Covered(j));
    EXPECT_LE(smoothed.Rms(j), filtered.Rms(j));
    EXPECT_GT(smoothed.Covered(j), 0.90);
  }
}

// A coupling the file holds at 0 with the σ of an identification that did not
// see it (the truth 1σ away): the σ is the encoder's further noise
// (ExtraEffects::ConsideredVariance) where the other joint is loaded, so the
// effort carries those rows. Measured: RMS 2.81 -> 0.81 mrad (joint 1), 3.05
// -> 0.58 (joint 2); covered 0.9 -> 12 %, 4.5 -> 5.1 %. Taken row by row as
// independent, the doubt averages down over a held push where the
// parameter's error does not: the intervals cover more, not 95 %
// (docs/decisions/effect-parameters-considered.md).
TEST(FilterDeflection, ACouplingsStatedDoubtMovesTheLoadedRowsTowardTheTruth) {
  const auto truth = WithEffect("deflection_coupling", {"k12", "k21"}, {0.006, 0.004});
  auto known = WithEffect("deflection_coupling", {"k12", "k21"}, {0.0, 0.0});
  auto doubted = known;
  doubted.effects[0].sd = {0.006, 0.004};
  const Loaded other_loaded = [](const SyntheticRun& run, std::size_t k, int j) {
    return std::abs(run.true_torque[k][1 - j]) > 0.3;
  };
  Score fixed, considered;
  for (unsigned seed = 1; seed <= kSeeds; ++seed) {
    const SyntheticRun run = DeflectedRun(truth, Pushes(seed));
    AddFilterRows(known, run, other_loaded, &fixed);
    AddFilterRows(doubted, run, other_loaded, &considered);
  }
  for (int j = 0; j < 2; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j + 1));
    std::printf("coupling at 0, joint %d: σ 0: RMS %.4f mrad covered %.3f; σ stated: RMS %.4f "
                "mrad covered %.3f\n", j + 1, 1e3 * fixed.Rms(j), fixed.Covered(j),
                1e3 * considered.Rms(j), considered.Covered(j));
    EXPECT_LT(considered.Rms(j), 0.35 * fixed.Rms(j));
    EXPECT_GE(considered.Covered(j), fixed.Covered(j));
  }
}

// A deflection effect at zero changes no estimate to the last bit: the
// effect's path adds nothing else (and without effects it is not taken).
TEST(FilterDeflection, ACouplingOfZeroLeavesEveryEstimateUnchanged) {
  const SyntheticRun run = MakeSyntheticRun(models::testing::PaperParameters(), ModelLogOptions(),
                                            Pushes(5));
  ComplianceFilter plain(models::testing::PaperParameters(), ModelLogOptions());
  ComplianceFilter zero(WithEffect("deflection_coupling", {"k12", "k21"}, {0.0, 0.0}),
                        ModelLogOptions());
  for (const auto& s : run.samples) {
    const FilterEstimate a = plain.Step(s), b = zero.Step(s);
    ASSERT_EQ(a.corrected_rad, b.corrected_rad);
    ASSERT_EQ(a.covariance_rad2, b.covariance_rad2);
    ASSERT_EQ(a.external_torque_nm, b.external_torque_nm);
  }
}

}  // namespace
}  // namespace pliant::estimation
