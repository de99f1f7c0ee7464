// The base model's residual on the compared rows, with the tip's unknown
// position profiled out per held group, and its RMS at the tip
// (docs/diagnose-method.md).
#include <cmath>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {

void ProfileGroups(const Problem& problem, std::vector<Eigen::Vector2d>& residual,
                   const std::vector<bool>* only) {
  if (!problem.profile_tip) return;
  std::vector<Eigen::Vector2d> sum(problem.tip_groups, Eigen::Vector2d::Zero());
  std::vector<Eigen::Vector2d> count(problem.tip_groups, Eigen::Vector2d::Zero());
  for (std::size_t i = 0; i < residual.size(); ++i) {
    const Sample& s = problem.samples[i];
    if (only && !(*only)[s.group]) continue;
    for (int j = 0; j < 2; ++j) {
      if (!s.used[j]) continue;
      sum[s.tip_group][j] += residual[i][j];
      count[s.tip_group][j] += 1.0;
    }
  }
  for (std::size_t i = 0; i < residual.size(); ++i) {
    const Sample& s = problem.samples[i];
    if (only && !(*only)[s.group]) continue;
    for (int j = 0; j < 2; ++j) {
      if (s.used[j]) residual[i][j] -= sum[s.tip_group][j] / count[s.tip_group][j];
    }
  }
}

std::vector<Eigen::Vector2d> Residuals(const Problem& problem, const BaseModel& model,
                                       const std::vector<Term>& terms,
                                       const std::vector<bool>* only) {
  std::vector<const double*> values;
  for (const Term& term : terms) values.push_back(term.parameters.data());
  std::vector<Eigen::Vector2d> residual;
  residual.reserve(problem.samples.size());
  for (const Sample& s : problem.samples) {
    Eigen::Vector2d r = ModelResidual<double>(s, model, terms, values);
    for (int j = 0; j < 2; ++j) r[j] = s.used[j] ? r[j] : 0.0;
    residual.push_back(r);
  }
  ProfileGroups(problem, residual, only);
  return residual;
}

double TipRmsMm(const Problem& problem, const std::vector<Eigen::Vector2d>& residual,
                const std::vector<bool>* keep_group) {
  double sum[2] = {0.0, 0.0}, count[2] = {0.0, 0.0};
  for (int j = 0; j < 2; ++j) {
    double window_sum = 0.0, window_count = 0.0, window_start = 0.0;
    int window_group = -1;
    auto close = [&] {
      if (window_count > 0.0) sum[j] += window_sum * window_sum / window_count;
      window_sum = window_count = 0.0;
    };
    for (std::size_t i = 0; i < residual.size(); ++i) {
      const Sample& s = problem.samples[i];
      if (keep_group && !(*keep_group)[s.group]) continue;
      if (!s.used[j]) continue;
      if (s.group != window_group || s.state.time_s - window_start >= problem.rms_window_s) {
        close();
        window_group = s.group, window_start = s.state.time_s;
      }
      window_sum += residual[i][j] * s.mm_per_rad[j];
      window_count += 1.0;
      count[j] += 1.0;
    }
    close();
  }
  double mean_square = 0.0;
  for (int j = 0; j < 2; ++j) mean_square += count[j] > 0.0 ? sum[j] / count[j] : 0.0;
  return std::sqrt(mean_square);
}

}  // namespace pliant::estimation::diagnosis
