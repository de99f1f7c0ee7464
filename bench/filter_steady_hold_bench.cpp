// The compliance scale's drift through a long steady hold (docs/filter.md,
// "Known limitation"; docs/decisions/0004-filter-held-load-rate.md): joint 1 ramped in 0.5 s to
// a steady load of m·w, its tip held for 19 s, the truth's s = 1. Printed with
// the filter's own effort noise and without any: the drift is the EKF's
// errors-in-variables bias on s·K·tau, so it goes with the noise.
// Run: build/bench/filter_steady_hold_bench   (0.2 s)
#include <cstdio>

#include "../tests/support/steady_hold.h"

int main() {
  using pliant::estimation::FilterOptions;
  using pliant::estimation::testing::TraceScaleOverHold;
  const double hold_s = 19.0;
  const FilterOptions bounded;  // the defaults
  FilterOptions free_load;
  free_load.bound_held_load_rate = false;
  std::printf("joint 1 held %.0f s at a steady load of m*w (w = the filter's dead-zone width), "
              "truth s = 1\n",
              hold_s);
  std::printf("  %5s   %-34s   %-26s   %s\n", "m", "defaults (held load's rate bounded)",
              "bound off (sigma_tau_dot)", "defaults, no effort noise");
  std::printf("  %5s   %8s %8s %16s   %8s %16s   %8s\n", "", "s", "sd(s)", "tip err, counts",
              "s", "tip err, counts", "s");
  for (double m : {1.0, 1.5, 2.0, 3.0, 5.0}) {
    const auto noisy = TraceScaleOverHold(bounded, m, hold_s, 1.0);
    const auto unbounded = TraceScaleOverHold(free_load, m, hold_s, 1.0);
    const auto quiet = TraceScaleOverHold(bounded, m, hold_s, 0.0);
    std::printf("  %5.1f   %8.4f %8.4f %16.0f   %8.4f %16.0f   %8.4f\n", m, noisy.at_end,
                noisy.sd_at_end, noisy.tip_error_counts, unbounded.at_end,
                unbounded.tip_error_counts, quiet.at_end);
  }
  return 0;
}
