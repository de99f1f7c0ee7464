#pragma once
// Whole-log checks that no single row can make: a log whose numbers are each
// in range but whose physics is not the PSM's. Angles logged in degrees that
// stay under 6° pass every per-row range, yet the instrument then seems 57
// times as compliant as it is; a time in milliseconds makes every velocity
// 1000 times too small. Every command that reads a log runs these checks
// before any work (docs/errors.md, "Implausible logs").
//
// The evidence, each from physics:
//  - the joint's range: the PSM's yaw moves within ±1.588 rad and its pitch
//    within ±0.925 rad (dVRK configuration files); an angle beyond it (10 %
//    margin) in a log whose angles are all under 2π is a degree.
//  - a held tip: on rows with tip_fixed = 1 the encoder moves with the effort
//    by the compliance, K = 0.03–0.1 rad/(N·m) on the dVRK PSM (the paper's
//    eqs. 3–4); the median slope dq/dτ of the holds beyond 0.6 rad/(N·m)
//    (6 times the most compliant instrument) reads ~57·K: degrees.
//  - the velocity columns: Δq/Δt between rows against the logged v1, v2
//    (when they track each other, correlation > 0.9): a ratio near 57 means
//    q in degrees, near 1/1000 means t in milliseconds.
//  - the time step: rows more than 0.5 s apart in a log that does not declare
//    '# timing: quasi-static' (warning), and a gap of over a minute and
//    1000 median steps (warning: two recordings joined?).

#include <string>
#include <vector>

#include "pliant/io/log.h"
#include "pliant/io/log_reader.h"

namespace pliant::io {

/// Thresholds of the checks above (exposed for tests).
inline constexpr double kYawRangeRad = 1.588;
inline constexpr double kPitchRangeRad = 0.925;
inline constexpr double kJointRangeMargin = 1.1;
inline constexpr double kLargestPlausibleComplianceRadPerNm = 0.6;
inline constexpr double kSlowestPlausibleRowPeriodS = 0.5;
inline constexpr double kLongestPlausibleGapS = 60.0;

/// What the checks found that may be right but usually is not, and the
/// log's time span (for options that must lie within it).
struct LogPlausibility {
  std::vector<std::string> warnings;  ///< without the "warning: " prefix
  double first_t_s = 0.0;
  double last_t_s = 0.0;
  double DurationS() const { return last_t_s - first_t_s; }
};

/// Streams the log at `path` once. Throws InputError (exit 2) when its
/// physics says degrees or milliseconds. Standard input ("-") is not read: it
/// can be read once only, so it gets the reader's per-row checks alone and its
/// span is NaN.
LogPlausibility CheckLogPlausibility(const std::string& path,
                                     const LogReaderOptions& options = {});

/// CheckLogPlausibility with its warnings printed on stderr as "warning: …".
LogPlausibility CheckLogPlausibilityAndWarn(const std::string& path,
                                            const LogReaderOptions& options = {});

}  // namespace pliant::io
