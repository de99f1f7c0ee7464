#include "pliant/estimation/unloaded_rows.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace pliant::estimation {

UnloadedRun FindUnloadedRun(const std::vector<double>& load_nm, double band_nm,
                            std::size_t min_rows) {
  UnloadedRun best;
  std::multiset<double> window;
  std::size_t first = 0;
  for (std::size_t r = 0; r < load_nm.size(); ++r) {
    if (!std::isfinite(load_nm[r])) {  // a gap ends every run
      window.clear();
      first = r + 1;
      continue;
    }
    window.insert(load_nm[r]);
    while (*window.rbegin() - *window.begin() > 2.0 * band_nm) {
      window.erase(window.find(load_nm[first++]));
    }
    if (window.size() > best.rows) best = {first, window.size()};
  }
  if (best.rows < min_rows) best = {};
  return best;
}

namespace {

// Variance of one row's load as the mean sees it: the larger of the rows'
// own variance and the batch-means estimate, b·var(batch means) over ⌊n/b⌋
// batches of b = ⌈√n⌉ consecutive rows (consistent for a stationary series
// whose correlation dies out; Flegal & Jones 2010). Rows that hold a slow
// wobble (a sweep's pose-to-pose bias error, an arm settling) share their
// errors, and sd/√n would count each as independent information.
double MeanVarianceTimesRows(const std::vector<double>& values, double white_variance) {
  const std::size_t n = values.size();
  const auto b = static_cast<std::size_t>(std::ceil(std::sqrt(double(n))));
  const std::size_t batches = b > 0 ? n / b : 0;
  if (batches < 2) return white_variance;
  std::vector<double> means(batches, 0.0);
  for (std::size_t k = 0; k < batches; ++k) {
    for (std::size_t i = 0; i < b; ++i) means[k] += values[k * b + i];
    means[k] /= double(b);
  }
  double grand = 0.0;
  for (double m : means) grand += m;
  grand /= double(batches);
  double spread = 0.0;
  for (double m : means) spread += (m - grand) * (m - grand);
  return std::max(white_variance, double(b) * spread / double(batches - 1));
}

}  // namespace

TareOffset TareOn(const std::vector<double>& load_nm, UnloadedRun run, double bias_sd_nm) {
  TareOffset tare;
  std::vector<double> values;
  for (std::size_t r = run.first_row; r < run.first_row + run.rows && r < load_nm.size(); ++r) {
    if (std::isfinite(load_nm[r])) values.push_back(load_nm[r]);
  }
  tare.rows = values.size();
  if (tare.rows == 0) return tare;
  const double n = double(tare.rows);
  double sum = 0.0, sum2 = 0.0;
  for (double v : values) {
    sum += v;
    sum2 += v * v;
  }
  tare.offset_nm = sum / n;
  const double white =
      tare.rows > 1 ? std::max(0.0, (sum2 - n * tare.offset_nm * tare.offset_nm) / (n - 1.0)) : 0.0;
  tare.sd_nm = std::sqrt(MeanVarianceTimesRows(values, white) / n);
  tare.disagrees =
      std::abs(tare.offset_nm) > 2.0 * std::sqrt(tare.sd_nm * tare.sd_nm + bias_sd_nm * bias_sd_nm);
  return tare;
}

}  // namespace pliant::estimation
