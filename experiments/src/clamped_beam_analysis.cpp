#include "pliant/experiments/clamped_beam_analysis.h"

#include <cmath>

namespace pliant::experiments {

LineFit FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit fit;
  fit.points = static_cast<int>(x.size());
  if (x.size() < 2) return fit;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= x.size();
  my /= y.size();
  double sxx = 0, sxy = 0;  // centred sums: no cancellation at large angles
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  return fit;
}

std::vector<ClampedBeamFit> FitClampedBeam(const SimulationResult& result, double min_load_nm) {
  std::vector<ClampedBeamFit> fits;
  int previous_segment = -1;
  for (const HoldRecord& hold : result.holds) {
    if (hold.segment <= 0 || !hold.tip_fixed) continue;
    const SegmentInfo& segment = result.segments.at(hold.segment - 1);
    const int j = segment.joint - 1;
    const bool new_run =
        fits.empty() || fits.back().joint != segment.joint ||
        fits.back().depth_m != segment.depth_m ||
        (hold.segment != previous_segment && segment.label.find("leg 1") != std::string::npos);
    if (new_run) {
      fits.push_back({});
      fits.back().joint = segment.joint;
      fits.back().depth_m = segment.depth_m;
      fits.back().unloaded_effort_nm = hold.effort_nm[j];
    }
    previous_segment = hold.segment;
    ClampedBeamFit& fit = fits.back();
    fit.angle_rad.push_back(hold.encoder_rad[j]);
    fit.effort_nm.push_back(hold.effort_nm[j]);
    fit.direction.push_back(segment.direction);
  }
  for (ClampedBeamFit& fit : fits) {
    std::vector<double> upper_q, upper_tau, lower_q, lower_tau;
    for (std::size_t i = 0; i < fit.angle_rad.size(); ++i) {
      const double load = fit.effort_nm[i] - fit.unloaded_effort_nm;
      if (load > min_load_nm)
        upper_q.push_back(fit.angle_rad[i]), upper_tau.push_back(fit.effort_nm[i]);
      if (load < -min_load_nm)
        lower_q.push_back(fit.angle_rad[i]), lower_tau.push_back(fit.effort_nm[i]);
    }
    fit.upper_wall = FitLine(upper_q, upper_tau);
    fit.lower_wall = FitLine(lower_q, lower_tau);
    fit.gap_rad = fit.upper_wall.AngleAt(fit.unloaded_effort_nm) -
                  fit.lower_wall.AngleAt(fit.unloaded_effort_nm);
  }
  return fits;
}

}  // namespace pliant::experiments
