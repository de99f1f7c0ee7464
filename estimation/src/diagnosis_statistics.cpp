// Tests on residual series (Boost.Math distributions): whiteness (Ljung–Box),
// normality (Jarque–Bera), the F test of an extension, Holm's adjustment, and
// the effective sample size of an autocorrelated series.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "chi_squared.h"
#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

double Mean(const std::vector<double>& x) {
  return x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
}

double ChiSquaredUpperTail(double statistic, double dof) {
  if (!(statistic > 0.0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), statistic));
}

}  // namespace

double EffectiveSizeFactor(const std::vector<double>& x, const std::vector<int>& run) {
  const double mean = Mean(x);
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    c0 += (x[i] - mean) * (x[i] - mean);
    if (i > 0 && run[i] == run[i - 1]) c1 += (x[i] - mean) * (x[i - 1] - mean);
  }
  if (!(c0 > 0.0)) return 1.0;
  const double rho = std::clamp(c1 / c0, 0.0, 0.999);
  return std::max((1.0 - rho) / (1.0 + rho), 1.0 / double(x.size()));
}

TestResult LjungBox(const std::vector<double>& x, int lags) {
  const std::size_t n = x.size();
  if (n < std::size_t(lags) + 2) return {};
  const double mean = Mean(x);
  double c0 = 0.0;
  for (double v : x) c0 += (v - mean) * (v - mean);
  if (!(c0 > 0.0)) return {};
  double q = 0.0;
  for (int k = 1; k <= lags; ++k) {
    double ck = 0.0;
    for (std::size_t i = k; i < n; ++i) ck += (x[i] - mean) * (x[i - k] - mean);
    const double rho = ck / c0;
    q += rho * rho / double(n - k);
  }
  q *= double(n) * double(n + 2);
  return {q, ChiSquaredUpperTail(q, lags)};
}

TestResult JarqueBera(const std::vector<double>& x) {
  const double n = double(x.size());
  if (n < 8) return {};
  const double mean = Mean(x);
  double m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (double v : x) {
    const double d = v - mean;
    m2 += d * d, m3 += d * d * d, m4 += d * d * d * d;
  }
  m2 /= n, m3 /= n, m4 /= n;
  if (!(m2 > 0.0)) return {};
  const double skew = m3 / std::pow(m2, 1.5);
  const double excess = m4 / (m2 * m2) - 3.0;
  const double jb = n / 6.0 * (skew * skew + excess * excess / 4.0);
  return {jb, ChiSquaredUpperTail(jb, 2.0)};
}

double FUpperTail(double f, double d1, double d2) {
  if (!(f > 0.0) || d1 <= 0.0 || d2 <= 0.0) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f(d1, d2), f));
}

TestResult BlockImprovementTest(const std::vector<double>& gain_per_block) {
  const double g = double(gain_per_block.size());
  if (g < 2.0) return {};
  const double mean = Mean(gain_per_block);
  double square = 0.0;
  for (double d : gain_per_block) square += (d - mean) * (d - mean);
  const double se = std::sqrt(square / (g - 1.0) / g);
  if (!(se > 0.0)) return {0.0, mean > 0.0 ? 0.0 : 1.0};
  const double t = mean / se;
  const boost::math::students_t student(g - 1.0);
  return {t, boost::math::cdf(boost::math::complement(student, t))};
}

void HolmAdjust(std::vector<double>& p) {
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  double running = 0.0;
  const double m = double(p.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    running = std::max(running, std::min(1.0, (m - double(k)) * p[order[k]]));
    p[order[k]] = running;
  }
}

std::array<double, 2> ChiSquaredMeanBand(double dof) {
  if (!(dof > 0.0)) return {0.0, 0.0};
  return {internal::ChiSquaredQuantile(dof, 0.025) / dof,
          internal::ChiSquaredQuantile(dof, 0.975) / dof};
}

}  // namespace pliant::estimation::diagnosis
