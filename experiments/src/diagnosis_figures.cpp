// The report's plots: the residual against time, against the channels that
// explain it best, against the effort (the paper's Fig. 5 shows effort
// against angle; a missing effect shows as structure here), and over the
// worst segment of each joint (Figs. 7-8: the tip did not move, so the
// corrected angle should be flat).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "pliant/experiments/diagnosis_report.h"
#include "pliant/experiments/plot.h"

namespace pliant::experiments {
namespace {

constexpr double kMrad = 1e3;
const char* kBefore = "points pt 7 ps 0.35 lc rgb '#d62728'";
const char* kAfter = "points pt 7 ps 0.35 lc rgb '#1f77b4'";

std::optional<std::vector<double>> ColumnIfAny(const io::Log& log, const std::string& name) {
  if (!log.header.Has(name)) return std::nullopt;
  return log.Column(name);
}

// A channel named by the diagnosis: a log column, |column| or sign(column).
std::optional<std::vector<double>> ChannelValues(const io::Log& log, const std::string& name) {
  auto inner = [&](const std::string& prefix, const std::string& suffix) -> std::string {
    if (name.size() > prefix.size() + suffix.size() && name.rfind(prefix, 0) == 0 &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    }
    return "";
  };
  if (auto values = ColumnIfAny(log, name)) return values;
  if (auto values = ColumnIfAny(log, inner("|", "|"))) {
    for (double& v : *values) v = std::abs(v);
    return values;
  }
  if (auto values = ColumnIfAny(log, inner("sign(", ")"))) {
    for (double& v : *values) v = (v > 0) - (v < 0);
    return values;
  }
  return std::nullopt;
}

PlotSeries Scatter(const std::string& title, const char* style) { return {title, {}, {}, style}; }

bool HasAfter(const estimation::ResidualSeries& s) {
  return s.residual_after_rad[0].size() == s.row.size() && !s.row.empty();
}

std::string AfterTitle(const estimation::Diagnosis& d) {
  if (!d.added_effects.empty()) {
    std::string names;
    for (const auto& n : d.added_effects) names += (names.empty() ? "" : " + ") + n;
    return "with " + names;
  }
  if (!d.effects.empty()) return "with " + d.effects.front().name;
  return "after";
}

// One panel per joint of residual (mrad) against x(row).
template <typename X>
std::vector<PlotPanel> PerJoint(const estimation::Diagnosis& d, const std::string& x_label,
                                X x_of) {
  const auto& s = d.series;
  std::vector<PlotPanel> panels;
  for (int j = 0; j < 2; ++j) {
    PlotPanel panel{"joint " + std::to_string(j + 1), x_label, "residual (mrad)", {}};
    PlotSeries before = Scatter("model as given", kBefore);
    PlotSeries after = Scatter(AfterTitle(d), kAfter);
    for (std::size_t i = 0; i < s.row.size() && i < s.residual_before_rad[j].size(); ++i) {
      const std::optional<double> x = x_of(j, s.row[i]);
      if (!x || !std::isfinite(*x) || !std::isfinite(s.residual_before_rad[j][i])) continue;
      before.x.push_back(*x);
      before.y.push_back(kMrad * s.residual_before_rad[j][i]);
      if (HasAfter(s)) {
        after.x.push_back(*x);
        after.y.push_back(kMrad * s.residual_after_rad[j][i]);
      }
    }
    panel.series.push_back(std::move(before));
    if (HasAfter(s)) panel.series.push_back(std::move(after));
    panels.push_back(std::move(panel));
  }
  return panels;
}

// The segment where the effect changes joint j's residual most (the largest
// drop of its mean square from before to after), when that drop is at least
// a tenth of the segment's mean square before: otherwise the two curves would
// lie on each other and the panel would show nothing.
std::optional<double> WorstSegment(const io::Log& log, const estimation::Diagnosis& d, int j) {
  const auto segments = ColumnIfAny(log, "segment");
  if (!segments || !HasAfter(d.series)) return std::nullopt;
  struct Sums { double before = 0.0, after = 0.0, count = 0.0; };
  std::map<double, Sums> sums;
  const auto& s = d.series;
  for (std::size_t i = 0; i < s.row.size() && i < s.residual_before_rad[j].size(); ++i) {
    const double b = s.residual_before_rad[j][i], a = s.residual_after_rad[j][i];
    if (!std::isfinite(b) || !std::isfinite(a)) continue;
    Sums& sum = sums[(*segments)[s.row[i]]];
    sum.before += b * b, sum.after += a * a, sum.count += 1.0;
  }
  std::optional<double> worst;
  double worst_drop = 0.0;
  for (const auto& [segment, sum] : sums) {
    const double drop = (sum.before - sum.after) / sum.count;
    if (drop > worst_drop && drop >= 0.1 * sum.before / sum.count) worst_drop = drop, worst = segment;
  }
  return worst;
}

// Panels with at least one point: gnuplot refuses a plot with none.
std::vector<PlotPanel> WithPoints(std::vector<PlotPanel> panels) {
  std::vector<PlotPanel> kept;
  for (auto& panel : panels) {
    bool any = false;
    for (const auto& series : panel.series) any = any || !series.x.empty();
    if (any) kept.push_back(std::move(panel));
  }
  return kept;
}

}  // namespace

std::vector<std::string> WriteDiagnosisFigures(const std::string& dir, const io::Log& log,
                                               const estimation::Diagnosis& d,
                                               std::vector<std::string>* missing) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  std::vector<std::string> paths;
  auto write = [&](Figure figure, const std::string& name) {
    figure.height_px = 420;
    figure.panels = WithPoints(std::move(figure.panels));
    const std::string path = (fs::path(dir) / name).string();
    try {
      if (figure.panels.empty()) throw std::runtime_error("no residual to plot in " + name);
      WriteFigure(figure, path);
      paths.push_back(path);
    } catch (const std::exception& e) {
      if (!missing) throw;
      missing->push_back(name + ": " + e.what());
    }
  };
  const std::vector<double> time = log.Column("t");

  write({"Residual of the model against time",
         PerJoint(d, "time (s)", [&](int, std::size_t row) { return std::optional(time[row]); })},
        "residual_time.png");

  // The channels that explain the residual best (one panel each, up to three).
  Figure channels{"Residual against the channels that explain it best", {}};
  std::set<std::pair<std::string, int>> shown;
  for (const auto& c : d.channels) {
    if (channels.panels.size() == 3 || !shown.insert({c.name, c.joint}).second) continue;
    const auto values = ChannelValues(log, c.name);
    if (!values) continue;
    const int j = c.joint == 2 ? 1 : 0;
    char title[160];
    std::snprintf(title, sizeof title, "joint %d vs %s, lag %d (explains %.0f %%)", j + 1,
                  c.name.c_str(), c.lag, 100.0 * c.score);
    PlotPanel panel{title, c.name, "residual (mrad)", {Scatter("model as given", kBefore)}};
    const auto& s = d.series;
    for (std::size_t i = 0; i < s.row.size() && i < s.residual_before_rad[j].size(); ++i) {
      const long source = static_cast<long>(s.row[i]) - c.lag;
      if (source < 0 || source >= static_cast<long>(values->size())) continue;
      panel.series[0].x.push_back((*values)[source]);
      panel.series[0].y.push_back(kMrad * s.residual_before_rad[j][i]);
    }
    channels.panels.push_back(std::move(panel));
  }
  if (!channels.panels.empty()) write(channels, "residual_channels.png");

  const std::vector<double> effort[2] = {log.Column("tau1"), log.Column("tau2")};
  write({"Residual against the measured effort (analogue of the paper's Fig. 5)",
         PerJoint(d, "measured effort (N·m)",
                  [&](int j, std::size_t row) { return std::optional(effort[j][row]); })},
        "fig5_residual_effort.png");

  // Figs. 7-8: of each joint, the segment the effect changes most, over time;
  // a joint where it changes no segment visibly has no panel.
  const std::optional<double> worst[2] = {WorstSegment(log, d, 0), WorstSegment(log, d, 1)};
  const auto segments = ColumnIfAny(log, "segment");
  auto in_worst = [&](int j, std::size_t row) -> std::optional<double> {
    if (!worst[j] || (*segments)[row] != *worst[j]) return std::nullopt;
    return time[row];
  };
  Figure segment_figure{
      "The segment the effect changes most, per joint: the tip stood still, so a right model "
      "gives a flat zero residual (analogue of the paper's Figs. 7, 8)",
      PerJoint(d, "time (s)", in_worst)};
  for (int j = 0; j < 2; ++j) {
    PlotPanel& panel = segment_figure.panels[j];
    if (worst[j]) panel.title += ", segment " + std::to_string(static_cast<long>(*worst[j]));
    panel.title += j == 0 ? " (Fig. 7)" : " (Fig. 8)";
  }
  if (worst[0] || worst[1]) write(segment_figure, "fig7_fig8_worst_segment.png");
  return paths;
}

}  // namespace pliant::experiments
