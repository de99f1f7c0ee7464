// The rates the diagnosis reads from a timed log: joint velocity and the
// measured effort's rate (docs/diagnose-method.md).
#include <cmath>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {

// Velocity from the log, or by central differences of the encoder.
std::vector<double> Velocity(const io::Log& log, const io::StandardColumns& c, int joint) {
  const int column = joint == 0 ? c.v1 : c.v2;
  if (column >= 0) return log.Column(log.header.columns[column]);
  const int q = joint == 0 ? c.q1 : c.q2;
  const std::size_t n = log.Rows();
  std::vector<double> v(n, 0.0);
  for (std::size_t r = 1; r + 1 < n; ++r) {
    const double dt = log.Value(r + 1, c.t) - log.Value(r - 1, c.t);
    if (dt > 0.0) v[r] = (log.Value(r + 1, q) - log.Value(r - 1, q)) / dt;
  }
  return v;
}

// Rate of the measured effort (N·m/s) by a least-squares line through the
// samples within ±window/2: a plain difference would turn the effort noise
// into a rate noise far larger than the rate.
std::vector<double> EffortRate(const io::Log& log, const io::StandardColumns& c, int joint,
                               double window_s) {
  const int tau = joint == 0 ? c.tau1 : c.tau2;
  const std::size_t n = log.Rows();
  std::vector<double> rate(n, 0.0);
  std::size_t lo = 0, hi = 0;
  for (std::size_t r = 0; r < n; ++r) {
    const double t = log.Value(r, c.t);
    while (log.Value(lo, c.t) < t - 0.5 * window_s) ++lo;
    while (hi + 1 < n && log.Value(hi + 1, c.t) <= t + 0.5 * window_s) ++hi;
    double st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0, m = 0.0;
    for (std::size_t k = lo; k <= hi; ++k) {
      const double dt = log.Value(k, c.t) - t, y = log.Value(k, tau);
      if (!std::isfinite(y)) continue;
      st += dt, sy += y, stt += dt * dt, sty += dt * y, m += 1.0;
    }
    const double denominator = m * stt - st * st;
    if (m >= 3.0 && denominator > 0.0) rate[r] = (m * sty - st * sy) / denominator;
  }
  return rate;
}

}  // namespace pliant::estimation::diagnosis
