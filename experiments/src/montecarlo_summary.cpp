// The summary of a study (summary.json) and its plots. Everything here is a
// function of the rows in trial order, never of timing or of the split.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/statistics/bivariate_statistics.hpp>

#include "pliant/estimation/consistency.h"
#include "pliant/experiments/montecarlo.h"
#include "pliant/experiments/plot.h"

namespace pliant::experiments {
namespace {

using nlohmann::json;

// Empirical quantile of sorted data, linear between order statistics
// (Hyndman & Fan type 7, the default of R and NumPy).
double Percentile(const std::vector<double>& sorted, double p) {
  const double h = (sorted.size() - 1) * p;
  const std::size_t i = static_cast<std::size_t>(std::floor(h));
  if (i + 1 >= sorted.size()) return sorted.back();
  return sorted[i] + (h - i) * (sorted[i + 1] - sorted[i]);
}

// Ranks from 1, ties share their mean rank (for Spearman's ρ).
std::vector<double> Ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return x[a] < x[b]; });
  std::vector<double> rank(x.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return rank;
}

double Spearman(const std::vector<double>& x, const std::vector<double>& y) {
  const double rho = boost::math::statistics::correlation_coefficient(Ranks(x), Ranks(y));
  return std::isfinite(rho) ? rho : 0.0;
}

json Percentiles(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  return {{"mean", mean},
          {"p05", Percentile(values, 0.05)},
          {"p50", Percentile(values, 0.50)},
          {"p95", Percentile(values, 0.95)},
          {"max", values.back()}};
}

std::vector<double> Column(const std::vector<TrialResult>& rows, double (*get)(const TrialResult&, int),
                           int index) {
  std::vector<double> out;
  for (const auto& r : rows) out.push_back(get(r, index));
  return out;
}

double Error(const TrialResult& r, int m) { return r.tip_error_mm[m]; }
double Drawn(const TrialResult& r, int q) { return r.draw.values[q]; }

// Linear regression of the error on the standardised drawn quantities: with
// independent draws, β_i² / Var(error) is the share of the error's variance
// that quantity i's spread explains (the shares sum to R²).
json VarianceShares(const std::vector<std::vector<double>>& inputs, const std::vector<std::string>& names,
                    const std::vector<double>& error) {
  const Eigen::Index n = static_cast<Eigen::Index>(error.size()), p = static_cast<Eigen::Index>(inputs.size());
  json out = json::object();
  if (n < p + 2) return out;
  Eigen::MatrixXd x(n, p + 1);
  x.col(p).setOnes();
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Map<const Eigen::VectorXd> v(inputs[i].data(), n);
    const double mean = v.mean(), sd = std::sqrt((v.array() - mean).square().sum() / (n - 1));
    // A quantity that happens not to vary in these rows explains nothing.
    x.col(i) = sd > 0.0 ? Eigen::VectorXd((v.array() - mean) / sd) : Eigen::VectorXd::Zero(n);
  }
  const Eigen::Map<const Eigen::VectorXd> y(error.data(), n);
  const double variance = (y.array() - y.mean()).square().sum() / (n - 1);
  const Eigen::VectorXd beta = x.colPivHouseholderQr().solve(y);
  json shares = json::object();
  double explained = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    const double share = x.col(i).isZero() ? 0.0 : beta[i] * beta[i] / variance;
    shares[names[i]] = share;
    explained += share;
  }
  out["variance_share"] = shares;
  out["variance_share_sum"] = explained;
  out["r2_linear"] = 1.0 - (x * beta - y).squaredNorm() / ((n - 1) * variance);
  return out;
}

}  // namespace

json SummariseStudy(const Study& study, const std::vector<TrialResult>& rows) {
  const double n = static_cast<double>(rows.size());
  json summary = {{"study", study.name},
                  {"fingerprint", json(study.fingerprint)},
                  {"seed", study.seed},
                  {"trials", rows.size()},
                  {"identify", study.identify}};
  json methods = json::object();
  for (int m = 0; m < kCorrectionMethods; ++m) {
    const auto errors = Column(rows, Error, m);
    json method = {{"tip_error_mm", Percentiles(errors)}};
    // Which drawn quantity's spread moves this method's error most: Spearman's
    // rank correlation over the trials (quantities held constant are left out).
    json sensitivity = json::object();
    std::vector<std::vector<double>> inputs;
    std::vector<std::string> names;
    for (int q = 0; q < kSampledQuantities; ++q) {
      if (!study.quantities[q].Varies()) continue;
      inputs.push_back(Column(rows, Drawn, q));
      names.push_back(SampledQuantityName(q));
      const double rho = Spearman(inputs.back(), errors);
      sensitivity[names.back()] = rho;
    }
    method["rank_correlation"] = sensitivity;
    method["regression"] = VarianceShares(inputs, names, errors);
    // The quantity whose spread explains most of the error's variance.
    std::string dominant;  // "" when there are too few trials for the regression
    double largest = 0.0;
    for (const auto& name : names) {
      const double share = method["regression"].value("variance_share", json::object()).value(name, 0.0);
      if (share > largest) largest = share, dominant = name;
    }
    method["dominant"] = dominant;
    methods[CorrectionMethodName(m)] = method;
  }
  summary["methods"] = methods;

  // One NEES per trial: independent χ²(2) values when the covariance is right.
  const auto band = estimation::MeanNeesBand95(static_cast<long>(rows.size()));
  const double nees95 = boost::math::quantile(boost::math::chi_squared(2.0), 0.95);
  json honesty = json::object();
  for (int e = 0; e < 2; ++e) {
    double sum = 0.0, covered = 0.0, fraction = 0.0, inside = 0.0, by_joint[2] = {0.0, 0.0};
    for (const auto& r : rows) {
      sum += r.nees[e];
      inside += r.nees[e] <= nees95;
      covered += r.covered[e];
      fraction += r.coverage_fraction[e];
      for (int j = 0; j < 2; ++j) by_joint[j] += r.joint_coverage_fraction[e][j];
    }
    const double mean = sum / n;
    honesty[e == 0 ? "filter" : "smoother"] = {
        {"nees_mean", mean},
        {"nees_band_95", {band.lower, band.upper}},
        {"nees_in_band", band.Contains(mean)},
        {"nees_within_chi2_95", inside / n},
        {"coverage_95_picked_sample", covered / (2.0 * n)},
        {"coverage_95_held_samples", fraction / n},
        {"coverage_95_held_samples_by_joint", {by_joint[0] / n, by_joint[1] / n}}};
  }
  summary["honesty"] = honesty;
  return summary;
}

void PlotStudy(const std::vector<TrialResult>& rows, const std::string& dir) {
  static const char* const kStyles[kCorrectionMethods] = {
      "lines lw 2 lc rgb 'gray50'", "lines lw 2 lc rgb 'red'", "lines lw 2 lc rgb 'orange'",
      "lines lw 2 lc rgb 'blue'", "lines lw 2 lc rgb 'dark-green'"};
  Figure distribution;
  distribution.title = "tip error per method (" + std::to_string(rows.size()) + " trials)";
  PlotPanel cdf{"cumulative distribution", "RMS tip error over the push (mm)",
                "fraction of trials", {}, "bottom right"};
  for (int m = 0; m < kCorrectionMethods; ++m) {
    auto errors = Column(rows, Error, m);
    std::sort(errors.begin(), errors.end());
    PlotSeries s{CorrectionMethodName(m), errors, {}, kStyles[m]};
    for (std::size_t i = 0; i < errors.size(); ++i) s.y.push_back((i + 1.0) / errors.size());
    cdf.series.push_back(s);
  }
  distribution.panels.push_back(cdf);
  distribution.width_px = 800;
  WriteFigure(distribution, dir + "/error_distribution.png");

  Figure contact;
  contact.title = "tip error against the contact";
  for (int q : {kDepthM, kPeakTorqueNm}) {
    PlotPanel panel{q == kDepthM ? "against depth" : "against peak torque",
                    q == kDepthM ? "insertion depth (m)" : "peak torque (N·m)", "tip error (mm)", {}};
    for (int m = 0; m < kCorrectionMethods; ++m) {
      std::string style = kStyles[m];
      style.replace(0, style.find(" lc"), "points pt 7 ps 0.4");
      panel.series.push_back({CorrectionMethodName(m), Column(rows, Drawn, q), Column(rows, Error, m), style});
    }
    contact.panels.push_back(panel);
  }
  WriteFigure(contact, dir + "/error_vs_contact.png");
}

}  // namespace pliant::experiments
