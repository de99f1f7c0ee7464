#include "pliant/experiments/paper_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "pliant/experiments/clamped_beam_analysis.h"
#include "pliant/experiments/plot.h"

namespace pliant::experiments {
namespace {

std::string Depth(double depth_m) {
  char text[32];
  std::snprintf(text, sizeof text, "L = %.3f m", depth_m);
  return text;
}

}  // namespace

void PlotBiasSweep(const SimulationResult& result, const std::string& path) {
  Figure figure{"Bias torque against joint angle at several depths (paper Fig. 4, simulated)", {}};
  for (int joint = 1; joint <= 2; ++joint) {
    PlotPanel panel{
        "joint " + std::to_string(joint), "joint angle (rad)", "measured effort (N·m)", {}};
    std::map<int, std::size_t> series_of_segment;
    for (const HoldRecord& hold : result.holds) {
      if (hold.segment <= 0) continue;
      const SegmentInfo& segment = result.segments.at(hold.segment - 1);
      if (segment.joint != joint) continue;
      auto found = series_of_segment.find(segment.id);
      if (found == series_of_segment.end()) {
        panel.series.push_back({Depth(segment.depth_m), {}, {}, "linespoints pt 7 ps 0.5"});
        found = series_of_segment.emplace(segment.id, panel.series.size() - 1).first;
      }
      panel.series[found->second].x.push_back(hold.encoder_rad[joint - 1]);
      panel.series[found->second].y.push_back(hold.effort_nm[joint - 1]);
    }
    figure.panels.push_back(std::move(panel));
  }
  WriteFigure(figure, path);
}

void PlotClampedBeam(const SimulationResult& result, const std::string& path, double depth_m) {
  const auto fits = FitClampedBeam(result);
  Figure figure{"Effort against encoder angle, tip clamped (paper Fig. 5, simulated)", {}};
  for (int joint = 1; joint <= 2; ++joint) {
    const ClampedBeamFit* best = nullptr;
    for (const auto& fit : fits) {
      if (fit.joint == joint &&
          (!best || std::abs(fit.depth_m - depth_m) < std::abs(best->depth_m - depth_m))) {
        best = &fit;
      }
    }
    PlotPanel panel{
        "joint " + std::to_string(joint), "encoder angle (rad)", "measured effort (N·m)", {}};
    if (best) {
      panel.title += ", " + Depth(best->depth_m);
      PlotSeries up{"moving +", {}, {}, "points pt 7 ps 0.6"};
      PlotSeries down{"moving -", {}, {}, "points pt 6 ps 0.8"};
      for (std::size_t i = 0; i < best->angle_rad.size(); ++i) {
        PlotSeries& s = best->direction[i] > 0 ? up : down;
        s.x.push_back(best->angle_rad[i]);
        s.y.push_back(best->effort_nm[i]);
      }
      panel.series = {up, down};
      // Each wall's line over its own points, drawn on to the unloaded effort
      // so that the gap between the lines (2·delta) shows.
      for (const auto* line : {&best->upper_wall, &best->lower_wall}) {
        if (line->points < 2) continue;
        const bool upper = line == &best->upper_wall;
        double far = line->AngleAt(best->unloaded_effort_nm);
        for (std::size_t i = 0; i < best->angle_rad.size(); ++i) {
          const double load = best->effort_nm[i] - best->unloaded_effort_nm;
          if (upper ? load > 0.1 : load < -0.1) {
            far = upper ? std::max(far, best->angle_rad[i]) : std::min(far, best->angle_rad[i]);
          }
        }
        const double near = line->AngleAt(best->unloaded_effort_nm);
        char title[96];
        std::snprintf(title, sizeof title, "fit, %s wall: 1/K = %.2f N·m/rad",
                      upper ? "upper" : "lower", line->slope);
        panel.series.push_back(
            {title,
             {near, far},
             {line->slope * near + line->intercept, line->slope * far + line->intercept},
             "lines lw 2"});
      }
    }
    figure.panels.push_back(std::move(panel));
  }
  WriteFigure(figure, path);
}

void PlotDeflection(const SimulationResult& result, const std::string& path) {
  const io::Log& log = result.log;
  const io::StandardColumns c(log.header);
  Figure figure{"Encoder minus true joint angle (deflection and backlash)", {}};
  for (int joint = 1; joint <= 2; ++joint) {
    PlotSeries series{
        "q" + std::to_string(joint) + " - q" + std::to_string(joint) + "_true", {}, {}, "lines"};
    const int q = joint == 1 ? c.q1 : c.q2, truth = joint == 1 ? c.q1_true : c.q2_true;
    for (std::size_t row = 0; row < log.Rows(); ++row) {
      series.x.push_back(log.Value(row, c.t));
      series.y.push_back(log.Value(row, q) - log.Value(row, truth));
    }
    figure.panels.push_back({"joint " + std::to_string(joint), "t (s)", "rad", {series}});
  }
  WriteFigure(figure, path);
}

void PlotExperiment(const Scenario& scenario, const SimulationResult& result,
                    const std::string& path) {
  switch (scenario.type) {
    case ExperimentType::kBiasSweep:
      return PlotBiasSweep(result, path);
    case ExperimentType::kClampedBeam:
      return PlotClampedBeam(result, path);
    default:
      return PlotDeflection(result, path);
  }
}

}  // namespace pliant::experiments
