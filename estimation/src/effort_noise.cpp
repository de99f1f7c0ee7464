#include "pliant/estimation/effort_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Core>

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

namespace {

constexpr double kLongestLagS = 0.15;  // the variogram's reach
constexpr int kMinStretches = 20;
constexpr std::size_t kMinPairs = 2000;

// The smallest non-zero step of an encoder that repeats its value on at least
// a tenth of its steps (quantised); 0 for one that does not.
double EncoderCount(const std::vector<double>& q) {
  double count = std::numeric_limits<double>::infinity();
  std::size_t repeats = 0, steps = 0;
  for (std::size_t i = 1; i < q.size(); ++i) {
    const double step = std::abs(q[i] - q[i - 1]);
    if (!std::isfinite(step)) continue;
    ++steps;
    if (step == 0.0) ++repeats;
    else count = std::min(count, step);
  }
  return steps > 0 && repeats * 10 >= steps && std::isfinite(count) ? count : 0.0;
}

// γ(k) for k = 1..lags (index k − 1) pooled over the stretches, with the
// number of pairs behind each.
void Semivariogram(const std::vector<double>& x,
                   const std::vector<std::pair<std::size_t, std::size_t>>& still, int lags,
                   Eigen::VectorXd* gamma, Eigen::VectorXd* pairs) {
  gamma->setZero(lags);
  pairs->setZero(lags);
  for (const auto& [begin, end] : still) {
    for (int k = 1; k <= lags && begin + std::size_t(k) < end; ++k) {
      for (std::size_t i = begin; i + std::size_t(k) < end; ++i) {
        const double d = x[i + std::size_t(k)] - x[i];
        if (!std::isfinite(d)) continue;
        (*gamma)[k - 1] += 0.5 * d * d;
        (*pairs)[k - 1] += 1.0;
      }
    }
  }
  *gamma = gamma->cwiseQuotient(pairs->cwiseMax(1.0));
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> StillStretches(
    const std::vector<double>& times_s, const std::vector<double> encoder_rad[2],
    double min_duration_s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  double count[2];
  bool any = false;
  for (int j = 0; j < 2; ++j) {
    count[j] = EncoderCount(encoder_rad[j]);
    const bool recorded = std::any_of(encoder_rad[j].begin(), encoder_rad[j].end(),
                                      [](double q) { return std::isfinite(q); });
    if (recorded && count[j] == 0.0) return out;  // not quantised: stillness unseen
    any = any || recorded;
  }
  if (!any) return out;
  const std::size_t n = times_s.size();
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= n; ++i) {
    bool moved = i == n;
    for (int j = 0; j < 2 && !moved; ++j) {
      const double step = std::abs(encoder_rad[j][i] - encoder_rad[j][begin]);
      moved = count[j] > 0.0 && !(step <= 1.5 * count[j]);
    }
    if (!moved) continue;
    if (times_s[i - 1] - times_s[begin] >= min_duration_s) out.emplace_back(begin, i);
    begin = i;
  }
  return out;
}

EffortNoiseColour EffortNoiseColourFromStill(
    const std::vector<double>& effort_nm,
    const std::vector<std::pair<std::size_t, std::size_t>>& still, double sample_period_s) {
  EffortNoiseColour out;
  out.stretches = int(still.size());
  const int lags = int(kLongestLagS / sample_period_s);
  if (!(sample_period_s > 0.0) || lags < 6 || out.stretches < kMinStretches) return out;
  Eigen::VectorXd gamma, pairs;
  Semivariogram(effort_nm, still, lags, &gamma, &pairs);
  out.pairs = std::size_t(pairs[0]);
  if (out.pairs < kMinPairs) return out;
  const Eigen::VectorXd lag = Eigen::VectorXd::LinSpaced(lags, 1.0, lags) * sample_period_s;
  const Eigen::VectorXd w = pairs;  // each lag weighted by its pairs
  double best = std::numeric_limits<double>::infinity();
  const double shortest_s = 0.5 * sample_period_s, longest_s = 0.5;
  for (int g = 0; g < 200; ++g) {  // τc over a geometric grid
    const double tc = shortest_s * std::pow(longest_s / shortest_s, g / 199.0);
    Eigen::MatrixX2d a(lags, 2);
    a.col(0).setOnes();
    a.col(1) = (1.0 - (-lag.array() / tc).exp()).matrix();
    const Eigen::Matrix2d normal = a.transpose() * w.asDiagonal() * a;
    const Eigen::Vector2d c = normal.ldlt().solve(a.transpose() * w.asDiagonal() * gamma);
    if (!(c.minCoeff() >= 0.0)) continue;  // both variances non-negative
    const double cost = (a * c - gamma).cwiseAbs2().dot(w);
    if (cost < best) {
      best = cost;
      out.white_sd_nm = std::sqrt(c[0]);
      out.coloured_sd_nm = std::sqrt(c[1]);
      out.correlation_s = tc;
    }
  }
  out.found = std::isfinite(best) && out.coloured_sd_nm > 0.0 &&
              out.correlation_s >= sample_period_s && out.correlation_s <= kLongestLagS / 3.0;
  return out;
}

}  // namespace pliant::estimation
