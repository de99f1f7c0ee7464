#include "pliant/estimation/effort_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pliant::estimation {

double EffortNoiseFromSamples(const std::vector<double>& effort_nm) {
  std::vector<double> second;
  double quantum = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < effort_nm.size(); ++k) {
    const double step = std::abs(effort_nm[k] - effort_nm[k - 1]);
    if (step > 0.0 && std::isfinite(step)) quantum = std::min(quantum, step);
    if (k + 1 < effort_nm.size()) {
      const double d2 = effort_nm[k + 1] - 2.0 * effort_nm[k] + effort_nm[k - 1];
      if (std::isfinite(d2)) second.push_back(std::abs(d2));
    }
  }
  if (second.size() < std::size_t(kMinNoiseTriples)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const auto middle = second.begin() + std::ptrdiff_t(second.size() / 2);
  std::nth_element(second.begin(), middle, second.end());
  // 0.6745: the standard normal's median absolute value.
  const double from_median = *middle / (0.6744897501960817 * std::sqrt(6.0));
  const double from_quantum = std::isfinite(quantum) ? quantum / std::sqrt(12.0) : 0.0;
  return std::max(from_median, from_quantum);
}

}  // namespace pliant::estimation
