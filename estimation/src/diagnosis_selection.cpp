// Selection that separates candidates (docs/diagnose-method.md, "Which effect
// is missing"): held-out residuals by segment, the per-segment gains the
// block test reads, and the pairwise comparison that lets a candidate win
// only by what it explains that the others cannot.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

using Residual = std::vector<Eigen::Vector2d>;

std::vector<Term> FittedCopy(const std::vector<Term>& fitted, const FitResult& fit) {
  std::vector<Term> terms = fitted;
  for (std::size_t t = 0; t < terms.size(); ++t) terms[t].parameters = fit.parameters[t];
  return terms;
}

}  // namespace

std::vector<Term> WithRefit(const Problem& problem, const std::vector<Term>& terms) {
  std::vector<Term> all = problem.refit;
  all.insert(all.end(), terms.begin(), terms.end());
  return all;
}

std::vector<Term> WithAddedRefit(const Problem& problem, const std::vector<Term>& added) {
  std::vector<Term> all = problem.added_refit;
  all.insert(all.end(), added.begin(), added.end());
  return all;
}

void AssignFolds(int wanted_folds, Problem* problem) {
  // Dealt in turn, the groups of a log that visits depths in order put every
  // shallow push of a joint in one fold: its training groups then hold that
  // joint at the deep end only, and a refit depth tilt extrapolates from
  // there. Dealt stratified — a group by the scarcest joint it loads, then by
  // depth — consecutive depths of each scarce joint go to different folds, so
  // every fold's training groups hold it at (nearly) both ends of its depths.
  struct Key {
    int joints = 0;  ///< bit j: some sample loads joint j
    double depth_m = 0.0;
    int samples = 0;
  };
  std::vector<Key> key(std::size_t(problem->groups));
  for (const Sample& s : problem->samples) {
    Key& k = key[std::size_t(s.group)];
    k.joints |= (s.used[0] ? 1 : 0) | (s.used[1] ? 2 : 0);
    k.depth_m += s.state.insertion_depth_m, ++k.samples;
  }
  int loading[2] = {0, 0};  // groups that load each joint
  for (Key& k : key) {
    k.depth_m /= std::max(1, k.samples);
    for (int j = 0; j < 2; ++j) loading[j] += (k.joints >> j) & 1;
  }
  // The stratum: the joint with the fewest loading groups among those the
  // group loads, as (that count, joint); groups that load none come last.
  const auto stratum = [&](const Key& k) {
    std::pair<int, int> best{problem->groups + 1, 2};
    for (int j = 0; j < 2; ++j) {
      if ((k.joints >> j) & 1) best = std::min(best, std::pair<int, int>{loading[j], j});
    }
    return best;
  };
  std::vector<int> order(std::size_t(problem->groups));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const Key &ka = key[std::size_t(a)], &kb = key[std::size_t(b)];
    const auto sa = stratum(ka), sb = stratum(kb);
    return sa != sb ? sa < sb : ka.depth_m < kb.depth_m;
  });
  problem->folds = std::min(wanted_folds, problem->groups);
  problem->fold_of_group.assign(std::size_t(problem->groups), 0);
  for (std::size_t i = 0; i < order.size(); ++i)
    problem->fold_of_group[std::size_t(order[i])] = int(i) % std::max(1, problem->folds);
}

Residual CrossValidated(const Problem& problem, const BaseModel& model,
                        const std::vector<Term>& fixed, const std::vector<Term>& fitted) {
  Residual heldout(problem.samples.size(), Eigen::Vector2d::Zero());
  for (int fold = 0; fold < problem.folds; ++fold) {
    std::vector<bool> train(problem.groups), test(problem.groups);
    for (int g = 0; g < problem.groups; ++g) {
      train[g] = problem.fold_of_group[g] != fold;
      test[g] = !train[g];
    }
    std::vector<Term> terms = fixed;
    if (!fitted.empty()) {
      const auto fit = FitTerms(problem, model, fixed, fitted, train, false, 1.0);
      const auto refitted = FittedCopy(fitted, fit);
      terms.insert(terms.end(), refitted.begin(), refitted.end());
    }
    // The held-out tip angle is profiled on the held-out samples alone.
    const Residual r = Residuals(problem, model, terms, &test);
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (test[problem.samples[i].group]) heldout[i] = r[i];
    }
  }
  return heldout;
}

double RmsDifferenceMm(const Problem& problem, const Residual& a, const Residual& b) {
  double mean_square = 0.0;
  for (int j = 0; j < 2; ++j) {
    double sum = 0.0, count = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Sample& s = problem.samples[i];
      if (!s.used[j]) continue;
      sum += std::pow((a[i][j] - b[i][j]) * s.mm_per_rad[j], 2);
      count += 1.0;
    }
    mean_square += count > 0.0 ? sum / count : 0.0;
  }
  return std::sqrt(mean_square);
}

std::vector<double> GainPerGroup(const Problem& problem, const Residual& before,
                                 const Residual& after) {
  std::vector<double> ss_before(problem.groups, 0.0), ss_after(problem.groups, 0.0);
  for (std::size_t i = 0; i < before.size(); ++i) {
    const Sample& s = problem.samples[i];
    for (int j = 0; j < 2; ++j) {
      if (!s.used[j]) continue;
      const double k = s.mm_per_rad[j] * s.mm_per_rad[j];
      ss_before[s.group] += k * before[i][j] * before[i][j];
      ss_after[s.group] += k * after[i][j] * after[i][j];
    }
  }
  std::vector<double> out;
  for (int g = 0; g < problem.groups; ++g) {
    if (ss_before[g] > 0.0 && ss_after[g] > 0.0) out.push_back(std::log(ss_before[g] / ss_after[g]));
  }
  return out;
}

std::vector<std::string> RankBySeparation(const Problem& problem, const BaseModel& model,
                                          const std::vector<Term>& fixed,
                                          const DiagnoseOptions& options,
                                          std::vector<CandidateFit>& candidates) {
  std::stable_sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.finding.score > b.finding.score;
  });
  std::vector<std::size_t> material;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].finding.missing && int(material.size()) < options.max_compared_candidates)
      material.push_back(i);
  }
  for (auto& c : candidates) c.finding.unique_score = c.finding.score;
  // gain[a][b]: held-out reduction of the error left by b alone when a joins it.
  std::map<std::pair<std::size_t, std::size_t>, double> gain;
  for (std::size_t x = 0; x < material.size(); ++x) {
    for (std::size_t y = x + 1; y < material.size(); ++y) {
      const std::size_t a = material[x], b = material[y];
      const Term ta = candidates[a].term, tb = candidates[b].term;
      const double both =
          TipRmsMm(problem, CrossValidated(problem, model, fixed, WithRefit(problem, {ta, tb})));
      const double alone_a = candidates[a].finding.heldout_rms_after_mm;
      const double alone_b = candidates[b].finding.heldout_rms_after_mm;
      gain[{a, b}] = alone_b > 0.0 ? 1.0 - both / alone_b : 0.0;
      gain[{b, a}] = alone_a > 0.0 ? 1.0 - both / alone_a : 0.0;
    }
  }
  const double t = options.min_unique_reduction;
  std::vector<bool> dominated(candidates.size(), false);
  for (std::size_t a : material) {
    for (std::size_t b : material) {
      if (a == b) continue;
      EffectFinding& f = candidates[a].finding;
      f.unique_score = std::min(f.unique_score, gain[{a, b}]);
      if (gain[{a, b}] >= t) continue;
      // b explains what a does: a stand-in for b, or the two cannot be told apart.
      if (gain[{b, a}] >= t) {
        dominated[a] = true;
      } else {
        f.indistinguishable_from.push_back(candidates[b].finding.name);
      }
    }
  }
  for (std::size_t a : material) candidates[a].finding.missing = !dominated[a];
  // Best first: effects that add to every rival, by that gain; then the ones
  // tied with a rival or explained by one, by their own score; then the rest.
  auto rank = [t](const CandidateFit& c) {
    if (!c.finding.missing) return 2;
    return c.finding.unique_score >= t ? 0 : 1;
  };
  std::stable_sort(candidates.begin(), candidates.end(), [&](const auto& a, const auto& b) {
    if (rank(a) != rank(b)) return rank(a) < rank(b);
    if (rank(a) == 0) return a.finding.unique_score > b.finding.unique_score;
    return a.finding.score > b.finding.score;
  });
  std::vector<std::string> selected;
  for (auto& c : candidates) {
    if (!c.finding.missing) continue;
    if (c.finding.unique_score >= t || selected.empty()) selected.push_back(c.finding.name);
    for (const auto& other : c.finding.indistinguishable_from) {
      const auto it = std::find_if(candidates.begin(), candidates.end(),
                                   [&](const auto& o) { return o.finding.name == other; });
      if (c.finding.separating_experiment.empty() && it != candidates.end())
        c.finding.separating_experiment = SeparatingExperiment(problem, model, fixed, c.term, it->term);
    }
  }
  return selected;
}

}  // namespace pliant::estimation::diagnosis
