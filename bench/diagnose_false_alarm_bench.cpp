// How often does `pliant diagnose` call an effect missing when none is?
// (issue 6, "on data with no hidden effect, no candidate is declared missing
// in at least 95 % of seeds"). Simulates the short divot log of the
// diagnosis tests (tests/diagnostics/diagnosis_support.h) with no hidden
// effect for N seeds, diagnoses each with the truth's model, and counts the
// seeds with a missing effect; with --hidden NAME='{json}' it measures the
// detection rate of that effect instead.
//
//   build/bench/diagnose_false_alarm_bench [--seeds 40] [--hidden 'NAME={"p":v}'] [--tip-fixed]
//       [--check PARAMETER=TRUE_VALUE] [--redraw-design] [--set KEY=JSON ...]
//       [--write DIR]
//
// --check: coverage of the fitted parameter's sd — how often the truth lies
// within 1.96 sd of the hidden effect's fitted value (95 % if the sd is honest).
// --tip-fixed: no tracker in the log; the reference is the held tip.
// --redraw-design: each seed draws its own design and instrument (two depths
// in 0.09–0.22 m, six push directions, a peak load of 0.7–1.3 N·m, K ×0.7–1.3
// and a clearance of 3–12 mrad per joint), so that the segments' misfit
// against the model is redrawn with the noise: the spread a sandwich over
// segments claims.
// --set: a scenario override applied to every seed after the design's (as
// `pliant simulate --set`), e.g. --set truth.tip.shaft_damping_nm_s_per_rad=0 to
// see what one physical detail of the simulator adds to the misfit.
// --write: each seed's log and the model it is diagnosed with, as
// DIR/seed_N.csv and DIR/seed_N.json, so that a case can be re-run with
// `pliant diagnose --params DIR/seed_N.json DIR/seed_N.csv`.
//
// Not a Google Benchmark: a statistical study, run by hand (docs/diagnose-method.md).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <boost/math/distributions/beta.hpp>

#include "../tests/diagnostics/diagnosis_support.h"
#include "pliant/estimation/diagnosis.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"

namespace {

// One drawn design and instrument (--redraw-design): the experiment's
// overrides, then K and the clearance of the truth the log and the model share.
pliant::experiments::Scenario DrawnScenario(const std::string& hidden, int seed, bool tip_fixed,
                                            const std::vector<std::string>& sets,
                                            std::string* summary) {
  std::mt19937_64 rng(std::uint64_t(seed) * 7919u + 17u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto draw = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  std::string directions = "[";
  for (int k = 0; k < 6; ++k) directions += (k ? "," : "") + std::to_string(draw(0.0, 360.0));
  const double shallow = draw(0.09, 0.15), deep = draw(0.16, 0.22), peak = draw(0.7, 1.3);
  std::vector<std::string> overrides = {
      "experiment.depths_m=[" + std::to_string(shallow) + "," + std::to_string(deep) + "]",
      "experiment.directions_deg=" + directions + "]",
      "experiment.peak_torques_nm=[" + std::to_string(peak) + "]",
      tip_fixed ? "sensors.tracker=false" : "sensors.tracker=true"};
  overrides.insert(overrides.end(), sets.begin(), sets.end());
  auto scenario = pliant::testing::ShortDivot(hidden, overrides);
  char text[160];
  int length = std::snprintf(text, sizeof text, "depths %.3f/%.3f m, peak %.2f N·m", shallow, deep, peak);
  for (std::size_t j = 0; j < 2; ++j) {
    const double scale = draw(0.7, 1.3), clearance = draw(0.003, 0.012);
    pliant::models::ScaleCompliance(scenario.truth.joints[j].compliance, scale);
    scenario.truth.joints[j].backlash_rad = clearance;
    length += std::snprintf(text + length, sizeof text - std::size_t(length), ", joint %zu K x%.2f δ %.1f mrad",
                            j + 1, scale, 1e3 * clearance);
  }
  *summary = text;
  return scenario;
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 40;
  std::string hidden = "{}", expected;
  bool tip_fixed = false;
  std::string checked, write_dir;
  double true_value = 0.0;
  bool redraw = false;
  std::vector<std::string> sets;
  for (int i = 1; i < argc; ++i) tip_fixed |= !std::strcmp(argv[i], "--tip-fixed");
  for (int i = 1; i < argc; ++i) redraw |= !std::strcmp(argv[i], "--redraw-design");
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--seeds")) seeds = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--set")) sets.push_back(argv[i + 1]);
    if (!std::strcmp(argv[i], "--write")) write_dir = argv[i + 1];
    if (!std::strcmp(argv[i], "--check")) {
      const std::string arg = argv[i + 1];
      checked = arg.substr(0, arg.find('='));
      true_value = std::atof(arg.substr(arg.find('=') + 1).c_str());
    }
    if (!std::strcmp(argv[i], "--hidden")) {
      const std::string arg = argv[i + 1];
      const auto eq = arg.find('=');
      expected = arg.substr(0, eq);
      hidden = "{\"" + expected + "\":" + arg.substr(eq + 1) + "}";
    }
  }
  std::vector<std::string> fixed_overrides = {tip_fixed ? "sensors.tracker=false"
                                                         : "sensors.tracker=true"};
  fixed_overrides.insert(fixed_overrides.end(), sets.begin(), sets.end());
  const auto fixed_scenario = pliant::testing::ShortDivot(hidden, fixed_overrides);
  int called = 0, right = 0, covered = 0, checks = 0;
  double sum_z2 = 0.0;
  std::map<std::string, int> best_counts;
  double worst_score = -1.0;
  for (int run = 0; run < seeds; ++run) {
    std::string design;
    const auto scenario =
        redraw ? DrawnScenario(hidden, 1000 + run, tip_fixed, sets, &design) : fixed_scenario;
    if (redraw) std::printf("seed %4d  %s\n", 1000 + run, design.c_str());
    const auto model = pliant::testing::ModelOf(scenario);
    const auto log = pliant::experiments::Simulate(scenario, 1000 + run).log;
    if (!write_dir.empty()) {
      const std::string stem = write_dir + "/seed_" + std::to_string(1000 + run);
      pliant::io::WriteLog(stem + ".csv", log);
      pliant::io::WriteParameters(stem + ".json", model);
    }
    const auto d = pliant::estimation::Diagnose(log, "divot.csv", model, {});
    const auto& best = d.effects.front();
    for (const auto& f : d.effects) {
      for (std::size_t k = 0; f.name == expected && k < f.parameter_names.size(); ++k) {
        if (f.parameter_names[k] != checked) continue;
        const double z = (f.parameters[k] - true_value) / f.parameter_sd[k];
        ++checks, covered += std::abs(z) <= 1.96, sum_z2 += z * z;
        std::printf("           %s = %.5g ± %.2g (z %+.2f)\n", checked.c_str(), f.parameters[k],
                    f.parameter_sd[k], z);
      }
    }
    ++best_counts[best.name];
    worst_score = std::max(worst_score, best.score);
    called += d.missing_effect.has_value();
    right += d.missing_effect && *d.missing_effect == expected;
    std::printf("seed %4d  best %-26s held-out reduction %+.3f  p %.2g  rms %.4f -> %.4f mm  missing %s\n",
                1000 + run, best.name.c_str(), best.score, best.p_value, d.rms_before_mm,
                best.heldout_rms_after_mm, d.missing_effect ? d.missing_effect->c_str() : "none");
  }
  // Clopper–Pearson 95 % interval of the rate.
  using boost::math::beta_distribution;
  const double n = seeds, k = expected.empty() ? called : right;
  const double lower = k > 0 ? boost::math::quantile(beta_distribution<>(k, n - k + 1), 0.025) : 0.0;
  const double upper = k < n ? boost::math::quantile(beta_distribution<>(k + 1, n - k), 0.975) : 1.0;
  std::printf("\n%s: %d of %d seeds (%.1f %%, 95 %% interval %.1f-%.1f %%)\n",
              expected.empty() ? "false alarms (an effect called missing, none hidden)"
                               : ("detections of " + expected).c_str(),
              int(k), seeds, 100.0 * k / n, 100.0 * lower, 100.0 * upper);
  std::printf("largest held-out reduction of the best candidate: %.3f\n", worst_score);
  if (checks > 0) {
    std::printf("coverage of %s ± 1.96 sd: %d of %d (%.1f %%), mean z² %.2f (1 if honest)\n",
                checked.c_str(), covered, checks, 100.0 * covered / checks, sum_z2 / checks);
  }
  for (const auto& [name, count] : best_counts) std::printf("  best %-26s %d seeds\n", name.c_str(), count);
  return 0;
}
