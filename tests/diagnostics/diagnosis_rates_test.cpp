// The effort's rate the diagnosis fits on (CentredEffortRates): the stream's
// trailing line read half a window later, against the closed form of a
// quadratic effort, whose least-squares slope over evenly spaced rows is the
// derivative at their mean time.
#include <gtest/gtest.h>

#include "../../estimation/src/diagnosis_internal.h"
#include "pliant/estimation/effect_inputs.h"

namespace pliant::estimation::diagnosis {
namespace {

// τ1 = 0.3·t², τ2 = −t² + 0.1·t at 100 Hz over two stretches, 0–2 s and
// 3–4 s (a gap of 1 s between): rates 0.6·t and −2·t + 0.1 at the mean time
// of the rows each line reads.
io::Log QuadraticEfforts() {
  io::Log log;
  log.header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2"};
  for (int k = 0; k <= 400; ++k) {
    if (k > 200 && k < 300) continue;
    const double t = 0.01 * k;
    log.values.insert(log.values.end(), {t, 0.1, -0.2, 0.15, 0.3 * t * t, -t * t + 0.1 * t});
  }
  return log;
}

Eigen::Vector2d RateAt(double mean_time_s) {
  return Eigen::Vector2d(0.6 * mean_time_s, -2.0 * mean_time_s + 0.1);
}

TEST(CentredEffortRates, TheTrailingLineReadHalfAWindowLater) {
  const io::Log log = QuadraticEfforts();
  ASSERT_EQ(log.Rows(), 302u);
  const io::StandardColumns c(log.header);
  // 0.105 s: 11 rows (±5), with no row on the window's edge.
  const double window_s = 0.105;
  const auto centred = CentredEffortRates(log, c, window_s);
  EffectInputs stream(false, kTimeGapS, window_s);
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const double t = log.Value(r, c.t);
    const Eigen::Vector2d trailing =
        stream.Update(c, &log.values[r * log.Columns()]).effort_rate_nm_s;
    // Rows whose centred / trailing window lies whole inside their stretch.
    if ((t > 0.045 && t < 1.955) || (t > 3.045 && t < 3.955))
      EXPECT_NEAR((centred[r] - RateAt(t)).norm(), 0.0, 1e-9) << t;
    if (t > 0.095 && (t < 2.005 || t > 3.095))
      EXPECT_NEAR((trailing - RateAt(t - 0.05)).norm(), 0.0, 1e-9) << t;
  }
  // The rows beside the gap read their own stretch only: 2.0 s the line
  // through 1.90–2.00 s, 3.0 s the line through 3.00–3.05 s.
  EXPECT_NEAR((centred[200] - RateAt(1.95)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((centred[201] - RateAt(3.025)).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace pliant::estimation::diagnosis
