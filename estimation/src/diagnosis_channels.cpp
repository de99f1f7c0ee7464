// Where the model fails: the residual of each joint conditioned on every
// channel of the log (raw and derived) at lags over ±N samples. Score: the
// fraction of residual variance the channel's binned conditional mean
// explains (η²); significance: the one-way ANOVA F test on the effective
// sample size, Holm-adjusted over joints × channels × lags.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <set>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

constexpr int kBins = 10;

struct Channel {
  std::string name;
  std::string unit;
  std::vector<double> values;  // one per log row
  bool sign = false;           // two-valued: words say "> 0" / "< 0"
};

// Units of the canonical columns (docs/log-format.md); auxiliary ones have none known.
std::string UnitOf(const std::string& name) {
  if (name == "t") return "s";
  if (name == "q3" || name == "q3_cmd") return "m";
  if (name == "q1" || name == "q2" || name == "q1_cmd" || name == "q2_cmd") return "rad";
  if (name == "v1" || name == "v2") return "rad/s";
  if (name == "v3") return "m/s";
  if (name == "tau1" || name == "tau2") return "N·m";
  if (name == "tau3") return "N";
  return "";
}

std::vector<Channel> Channels(const io::Log& log) {
  static const std::set<std::string> kSkipped = {"q1_ref", "q2_ref", "q1_true", "q2_true",
                                                 "tip_fixed"};
  std::vector<Channel> channels;
  for (const std::string& name : log.header.columns) {
    if (kSkipped.count(name)) continue;
    channels.push_back({name, UnitOf(name), log.Column(name), false});
  }
  for (const char* j : {"1", "2"}) {
    const std::string tau = std::string("tau") + j, v = std::string("v") + j;
    if (log.header.Has(tau)) {
      Channel c{"|" + tau + "|", "N·m", log.Column(tau), false};
      for (double& x : c.values) x = std::abs(x);
      channels.push_back(std::move(c));
    }
    if (log.header.Has(v)) {
      const std::vector<double> velocity = log.Column(v);
      Channel s{"sign(" + v + ")", "", velocity, true};
      for (double& x : s.values) x = x > 0.0 ? 1.0 : -1.0;
      channels.push_back(std::move(s));
      // Time since the joint last reversed: backlash and friction transients.
      Channel r{"since_reversal" + std::string(j), "s", velocity, false};
      const std::vector<double> t = log.Column("t");
      double last = t.empty() ? 0.0 : t[0];
      for (std::size_t i = 0; i < velocity.size(); ++i) {
        if (i > 0 && velocity[i] * velocity[i - 1] < 0.0) last = t[i];
        r.values[i] = t[i] - last;
      }
      channels.push_back(std::move(r));
    }
  }
  return channels;
}

// 0 and ±lags spread geometrically up to ±max_lag (every lag up to ±8).
std::vector<int> Lags(int max_lag) {
  std::set<int> lags = {0};
  for (int k = 1; k <= max_lag; k = std::max(k + 1, int(std::lround(k * 1.3)))) {
    lags.insert(k), lags.insert(-k);
  }
  if (max_lag > 0) lags.insert(max_lag), lags.insert(-max_lag);
  return {lags.begin(), lags.end()};
}

struct Binned {
  double eta2 = 0.0;
  int bins = 0;
  std::vector<double> mean, lower, upper;
};

// η² of x against channel values c by quantile bins (or by value when c has
// few distinct values).
Binned BinnedVariance(const std::vector<double>& x, const std::vector<double>& c) {
  Binned out;
  const std::size_t n = x.size();
  if (n < 4 * kBins) return out;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return c[a] < c[b]; });
  std::vector<int> bin(n);
  int bins = 0;
  std::vector<double> levels;
  for (std::size_t k = 0; k < n && levels.size() <= std::size_t(kBins); ++k) {
    if (levels.empty() || c[order[k]] != levels.back()) levels.push_back(c[order[k]]);
  }
  if (levels.size() <= std::size_t(kBins)) {
    for (std::size_t i = 0; i < n; ++i)
      bin[i] = int(std::lower_bound(levels.begin(), levels.end(), c[i]) - levels.begin());
    bins = int(levels.size());
  } else {
    // Equal counts, but ties stay in one bin.
    int current = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (k > 0 && c[order[k]] != c[order[k - 1]] && int(k * kBins / n) > current) ++current;
      bin[order[k]] = current;
    }
    bins = current + 1;
  }
  if (bins < 2) return out;
  out.bins = bins;
  out.mean.assign(bins, 0.0);
  out.lower.assign(bins, INFINITY);
  out.upper.assign(bins, -INFINITY);
  std::vector<double> count(bins, 0.0);
  double total = 0.0, mean = 0.0;
  for (double v : x) mean += v / double(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.mean[bin[i]] += x[i];
    count[bin[i]] += 1.0;
    out.lower[bin[i]] = std::min(out.lower[bin[i]], c[i]);
    out.upper[bin[i]] = std::max(out.upper[bin[i]], c[i]);
    total += (x[i] - mean) * (x[i] - mean);
  }
  double between = 0.0;
  for (int b = 0; b < bins; ++b) {
    out.mean[b] /= std::max(1.0, count[b]);
    between += count[b] * (out.mean[b] - mean) * (out.mean[b] - mean);
  }
  out.eta2 = total > 0.0 ? between / total : 0.0;
  return out;
}

std::string Words(const Channel& c, int joint, int lag, const Binned& b, double sample_period_s) {
  int hi = 0, lo = 0;
  for (int k = 1; k < b.bins; ++k) {
    if (b.mean[k] > b.mean[hi]) hi = k;
    if (b.mean[k] < b.mean[lo]) lo = k;
  }
  auto level = [](double mean_rad) {
    char text[48];
    std::snprintf(text, sizeof text, "%.2f mrad %s", std::abs(mean_rad) * 1e3,
                  mean_rad >= 0.0 ? "high" : "low");
    return std::string(text);
  };
  auto where = [&](int k) {
    char text[96];
    if (c.sign) return c.name.substr(5, c.name.size() - 6) + (b.lower[k] > 0.0 ? " > 0" : " < 0");
    if (b.lower[k] == b.upper[k]) {
      std::snprintf(text, sizeof text, "%s = %.4g", c.name.c_str(), b.lower[k]);
    } else {
      std::snprintf(text, sizeof text, "%s is in [%.4g, %.4g]%s%s", c.name.c_str(), b.lower[k],
                    b.upper[k], c.unit.empty() ? "" : " ", c.unit.c_str());
    }
    return std::string(text);
  };
  std::string words = "joint " + std::to_string(joint) + " reads " + level(b.mean[hi]) +
                      " while " + where(hi) + " and " + level(b.mean[lo]) + " while " + where(lo);
  if (lag != 0) {
    char text[96];
    std::snprintf(text, sizeof text, " (the error %s the channel by %d samples, %.1f ms)",
                  lag > 0 ? "follows" : "leads", std::abs(lag),
                  std::abs(lag) * sample_period_s * 1e3);
    words += text;
  }
  return words;
}

}  // namespace

std::vector<ChannelFinding> RankChannels(const io::Log& log, const Problem& problem,
                                         const std::vector<Eigen::Vector2d>& residual,
                                         const DiagnoseOptions& options) {
  const std::vector<Channel> channels = Channels(log);
  const std::vector<double> t = log.Column("t");
  const double period = t.size() > 1 ? (t.back() - t.front()) / double(t.size() - 1) : 0.0;
  struct Best {
    ChannelFinding finding;
    double eta2 = -1.0;
    std::size_t test = 0;
  };
  std::vector<Best> best(channels.size());
  const std::vector<int> lags = Lags(std::max(0, options.max_lag_samples));
  std::vector<double> all_p;  // every test, for Holm's adjustment
  for (int j = 0; j < 2; ++j) {
    std::vector<std::size_t> rows;
    std::vector<double> x;
    std::vector<int> run;
    for (std::size_t i = 0; i < residual.size(); ++i) {
      if (!problem.samples[i].used[j]) continue;
      rows.push_back(problem.samples[i].row);
      x.push_back(residual[i][j]);
      run.push_back(problem.samples[i].group);
    }
    if (x.size() < 8 * kBins) continue;
    const double n_eff = double(x.size()) * EffectiveSizeFactor(x, run);
    for (std::size_t ci = 0; ci < channels.size(); ++ci) {
      const Channel& c = channels[ci];
      for (int lag : lags) {
        std::vector<double> xs, cs;
        for (std::size_t k = 0; k < rows.size(); ++k) {
          const long source = long(rows[k]) - lag;
          if (source < 0 || source >= long(c.values.size()) || !std::isfinite(c.values[source])) continue;
          xs.push_back(x[k]);
          cs.push_back(c.values[source]);
        }
        const Binned b = BinnedVariance(xs, cs);
        if (b.bins < 2) continue;
        const double d1 = b.bins - 1, d2 = std::max(1.0, n_eff * xs.size() / x.size() - b.bins);
        const double f = (b.eta2 / d1) / std::max(1e-12, (1.0 - b.eta2) / d2);
        const double p = FUpperTail(f, d1, d2);
        all_p.push_back(p);
        Best& current = best[ci];
        // Prefer the smallest |lag| among near-equal scores: a slow channel
        // explains almost as much at every lag.
        const bool better = b.eta2 > current.eta2 * 1.02 ||
                            (b.eta2 >= current.eta2 * 0.98 && std::abs(lag) < std::abs(current.finding.lag));
        if (current.eta2 < 0.0 || better) {
          current.eta2 = b.eta2;
          current.test = all_p.size() - 1;
          current.finding = {c.name, j + 1, lag, b.eta2, p, Words(c, j + 1, lag, b, period), ""};
        }
      }
    }
  }
  HolmAdjust(all_p);
  std::vector<ChannelFinding> findings;
  for (Best& b : best) {
    if (b.eta2 < 0.0) continue;
    b.finding.p_value = all_p[b.test];
    findings.push_back(b.finding);
  }
  std::sort(findings.begin(), findings.end(), [&](const ChannelFinding& a, const ChannelFinding& b) {
    const bool sa = a.p_value < options.family_significance, sb = b.p_value < options.family_significance;
    return sa != sb ? sa : a.score > b.score;
  });
  return findings;
}

}  // namespace pliant::estimation::diagnosis
