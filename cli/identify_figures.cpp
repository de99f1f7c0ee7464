#include "identify_figures.h"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>

#include "pliant/experiments/plot.h"

namespace pliant::cli {
namespace {

std::string Sibling(const std::string& path, const std::string& suffix) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return path + suffix;
  return path.substr(0, dot) + suffix + path.substr(dot);
}

bool Has(const estimation::IdentificationSample& s, int j) {
  return std::isfinite(s.angle_rad[j]) && std::isfinite(s.effort_nm[j]);
}

// Fig. 4: free-tip effort against angle, one series per depth (5 mm bins).
experiments::PlotPanel BiasPanel(const estimation::IdentificationData& data, int j) {
  experiments::PlotPanel panel{"joint " + std::to_string(j + 1) + ", tip free",
                               "joint angle (rad)", "measured effort (N·m)", {}, "top right"};
  std::map<long, experiments::PlotSeries> by_depth;
  for (const auto& s : data.samples) {
    if (s.tip_fixed || !Has(s, j)) continue;
    auto& series = by_depth[std::lround(s.insertion_depth_m / 0.005)];
    series.x.push_back(s.angle_rad[j]);
    series.y.push_back(s.effort_nm[j]);
  }
  for (auto& [bin, series] : by_depth) {
    char title[32];
    std::snprintf(title, sizeof title, "L = %.3f m", bin * 0.005);
    series.title = title;
    series.style = "linespoints pt 7 ps 0.4";
    panel.series.push_back(series);
  }
  return panel;
}

// Fig. 5: effort against angle on the joint's middle clamp, by direction of motion.
experiments::PlotPanel LoopPanel(const estimation::IdentificationData& data, int j) {
  std::map<int, int> rows;
  for (const auto& s : data.samples)
    if (s.tip_fixed && Has(s, j)) ++rows[s.segment];
  experiments::PlotPanel panel{"joint " + std::to_string(j + 1) + ", tip clamped",
                               "joint angle (rad)", "measured effort (N·m)", {}, "top left"};
  if (rows.empty()) return panel;
  auto middle = rows.begin();
  std::advance(middle, rows.size() / 2);
  experiments::PlotSeries up{"moving toward +q", {}, {}, "points pt 7 ps 0.6"};
  experiments::PlotSeries down{"moving toward -q", {}, {}, "points pt 6 ps 0.6"};
  double depth = 0.0;
  for (const auto& s : data.samples) {
    if (!s.tip_fixed || s.segment != middle->first || !Has(s, j)) continue;
    auto& series = s.travel_since_reversal_rad[j] >= 0.0 ? up : down;
    series.x.push_back(s.angle_rad[j]);
    series.y.push_back(s.effort_nm[j]);
    depth = s.insertion_depth_m;
  }
  char title[64];
  std::snprintf(title, sizeof title, "joint %d, tip clamped at L = %.3f m", j + 1, depth);
  panel.title = title;
  panel.series = {up, down};
  return panel;
}

void Draw(const experiments::Figure& figure, const std::string& path) {
  try {
    experiments::WriteFigure(figure, path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: no picture %s: %s\n", path.c_str(), e.what());
  }
}

}  // namespace

void DrawDataFigures(const estimation::IdentificationData& data, const std::string& figure_path) {
  experiments::Figure fig4{"bias torque: effort with the tip free, per depth (paper Fig. 4)", {}};
  experiments::Figure fig5{"clamped beam: effort against angle (paper Fig. 5)", {}};
  for (int j = 0; j < 2; ++j) {
    fig4.panels.push_back(BiasPanel(data, j));
    fig5.panels.push_back(LoopPanel(data, j));
  }
  Draw(fig4, Sibling(figure_path, "_fig4"));
  Draw(fig5, Sibling(figure_path, "_fig5"));
}

}  // namespace pliant::cli
