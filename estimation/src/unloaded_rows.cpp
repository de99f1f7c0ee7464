#include "pliant/estimation/unloaded_rows.h"

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

TareOffset TareOn(const std::vector<double>& load_nm, UnloadedRun run, double bias_sd_nm) {
  TareOffset tare;
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t r = run.first_row; r < run.first_row + run.rows && r < load_nm.size(); ++r) {
    if (!std::isfinite(load_nm[r])) continue;
    sum += load_nm[r];
    sum2 += load_nm[r] * load_nm[r];
    ++tare.rows;
  }
  if (tare.rows == 0) return tare;
  const double n = double(tare.rows);
  tare.offset_nm = sum / n;
  const double variance = tare.rows > 1 ? std::max(0.0, (sum2 - n * tare.offset_nm * tare.offset_nm) / (n - 1.0)) : 0.0;
  tare.sd_nm = std::sqrt(variance / n);
  tare.disagrees =
      std::abs(tare.offset_nm) > 2.0 * std::sqrt(tare.sd_nm * tare.sd_nm + bias_sd_nm * bias_sd_nm);
  return tare;
}

}  // namespace pliant::estimation
