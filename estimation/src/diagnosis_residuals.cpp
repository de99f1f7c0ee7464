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

namespace {

// Per joint, over the residual's windows (DiagnoseOptions::rms_window_s,
// within a segment): the sum over windows of n·mean², the samples, the
// windows, and for neighbouring windows of a segment the squared change of
// their means and the sum of 1/n of both (mm at the tip).
struct WindowedSums {
  double mean_square_sum[2] = {0.0, 0.0}, samples[2] = {0.0, 0.0}, windows[2] = {0.0, 0.0};
  double change_square_sum[2] = {0.0, 0.0}, change_weight[2] = {0.0, 0.0};
};

WindowedSums SumWindows(const Problem& problem, const std::vector<Eigen::Vector2d>& residual,
                        const std::vector<bool>* keep_group) {
  WindowedSums w;
  for (int j = 0; j < 2; ++j) {
    double window_sum = 0.0, window_count = 0.0, window_start = 0.0;
    double last_mean = 0.0, last_count = 0.0;  // the segment's previous window, if any
    int window_group = -1;
    auto close = [&] {
      if (window_count <= 0.0) return;
      const double mean = window_sum / window_count;
      w.mean_square_sum[j] += window_sum * mean;
      w.windows[j] += 1.0;
      if (last_count > 0.0) {
        w.change_square_sum[j] += (mean - last_mean) * (mean - last_mean);
        w.change_weight[j] += 1.0 / window_count + 1.0 / last_count;
      }
      last_mean = mean, last_count = window_count;
      window_sum = window_count = 0.0;
    };
    for (std::size_t i = 0; i < residual.size(); ++i) {
      const Sample& s = problem.samples[i];
      if (keep_group && !(*keep_group)[s.group]) continue;
      if (!s.used[j]) continue;
      if (s.group != window_group || s.state.time_s - window_start >= problem.rms_window_s) {
        close();
        if (s.group != window_group) last_count = 0.0;  // a new segment
        window_group = s.group, window_start = s.state.time_s;
      }
      window_sum += residual[i][j] * s.mm_per_rad[j];
      window_count += 1.0;
      w.samples[j] += 1.0;
    }
    close();
  }
  return w;
}

}  // namespace

double TipRmsMm(const Problem& problem, const std::vector<Eigen::Vector2d>& residual,
                const std::vector<bool>* keep_group) {
  const WindowedSums w = SumWindows(problem, residual, keep_group);
  double mean_square = 0.0;
  for (int j = 0; j < 2; ++j)
    mean_square += w.samples[j] > 0.0 ? w.mean_square_sum[j] / w.samples[j] : 0.0;
  return std::sqrt(mean_square);
}

double NoiseFloorMm(const Problem& problem, const std::vector<Eigen::Vector2d>& residual) {
  // A window of n samples keeps v/n of the noise in its mean (v the noise's
  // variance per sample, with whatever correlation it has within a window);
  // over a joint's windows that is v·windows/samples of TipRmsMm's mean
  // square. Neighbouring windows' means differ by noise of variance
  // v·(1/n + 1/n') and by what the model's error changes in one window,
  // which is small: v is their ratio, and the floor is, if anything, high.
  const WindowedSums w = SumWindows(problem, residual, nullptr);
  double floor_square = 0.0;
  for (int j = 0; j < 2; ++j) {
    if (w.change_weight[j] <= 0.0 || w.samples[j] <= 0.0) continue;
    const double variance = w.change_square_sum[j] / w.change_weight[j];
    floor_square += variance * w.windows[j] / w.samples[j];
  }
  return std::sqrt(floor_square);
}

}  // namespace pliant::estimation::diagnosis
