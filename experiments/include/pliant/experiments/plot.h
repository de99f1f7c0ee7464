#pragma once
// Pictures through gnuplot (Debian: gnuplot-nox), for the simulator's figures
// and the reports of later tools. A figure is panels side by side, each with
// series of (x, y) points or lines; WriteFigure writes the data and a gnuplot
// script and runs gnuplot, which draws PNG (pngcairo) or SVG by the path's
// extension.
//
//   pliant::experiments::Figure figure;
//   figure.panels.push_back({"joint 1", "angle (rad)", "effort (N·m)", {}});
//   figure.panels[0].series.push_back({"0.09 m", xs, ys, "linespoints"});
//   pliant::experiments::WriteFigure(figure, "fig4.png");

#include <string>
#include <vector>

namespace pliant::experiments {

struct PlotSeries {
  std::string title;
  std::vector<double> x;
  std::vector<double> y;
  /// A gnuplot "with" clause: "points pt 7 ps 0.5", "lines lw 2", "linespoints".
  std::string style = "points pt 7 ps 0.5";
};

struct PlotPanel {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  /// gnuplot's `set key` argument: where the legend covers the fewest points.
  std::string legend = "top left";
};

struct Figure {
  std::string title;
  std::vector<PlotPanel> panels;
  int width_px = 1200;
  int height_px = 500;
};

/// The gnuplot program: $PLIANT_GNUPLOT if set, else `gnuplot` on the PATH;
/// "" when there is none.
std::string FindGnuplot();

/// Draws `figure` into `path` (.png or .svg). With keep_sources the script and
/// data stay beside the picture (path + ".gp", path + ".dat"), otherwise they
/// go to a temporary directory that is removed. Throws std::runtime_error
/// when gnuplot is missing (saying how to install it) or fails.
void WriteFigure(const Figure& figure, const std::string& path, bool keep_sources = false);

}  // namespace pliant::experiments
