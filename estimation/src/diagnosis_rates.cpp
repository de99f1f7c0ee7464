// The effort's rate the diagnosis and identify --effect fit on: the line the
// stream reads (EffectInputs), centred on its row (docs/diagnose-method.md).
#include <algorithm>

#include "diagnosis_internal.h"
#include "pliant/estimation/effect_inputs.h"

namespace pliant::estimation::diagnosis {

// The stream's trailing line (EffectInputs) read half a window later, at the
// last row of the same stretch (no gap) no later than t + w/2: the fit has the
// whole log, and the centred line finds an effort delay's physical value where
// the trailing one, w/2 late, finds less (decision record effect-inputs.md).
std::vector<Eigen::Vector2d> CentredEffortRates(const io::Log& log, const io::StandardColumns& c,
                                                double window_s) {
  const std::size_t n = log.Rows();
  std::vector<Eigen::Vector2d> trailing(n), centred(n);
  std::vector<bool> starts(n, true);  // the first row of a stretch
  EffectInputs tracker(false, kTimeGapS, window_s);
  for (std::size_t r = 0; r < n; ++r) {
    trailing[r] = tracker.Update(c, &log.values[r * log.Columns()]).effort_rate_nm_s;
    const double dt = r > 0 ? log.Value(r, c.t) - log.Value(r - 1, c.t) : -1.0;
    starts[r] = !(dt >= 0.0 && dt <= kTimeGapS);
  }
  std::size_t k = 0;
  for (std::size_t r = 0; r < n; ++r) {
    k = std::max(k, r);
    const double until = log.Value(r, c.t) + 0.5 * window_s;
    while (k + 1 < n && !starts[k + 1] && log.Value(k + 1, c.t) <= until) ++k;
    centred[r] = trailing[k];
  }
  return centred;
}

}  // namespace pliant::estimation::diagnosis
