// Whole-log physics checks (log_plausibility.h).
#include "pliant/io/log_plausibility.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

const char kDegreesFix[] =
    "this looks like degrees; convert q1, q2 (and their _cmd, _ref and _true columns, and v1, v2) "
    "to radians (multiply by π/180)";

template <typename... Args>
std::string Format(const char* format, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

// Least-squares slope of y on x, from sums about the first point (exact
// enough for the ranges of a log, and constant memory).
struct Regression {
  double x0 = 0.0, y0 = 0.0;
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  double x_min = HUGE_VAL, x_max = -HUGE_VAL;

  void Add(double x, double y) {
    if (n == 0.0) x0 = x, y0 = y;
    const double dx = x - x0, dy = y - y0;
    n += 1.0, sx += dx, sy += dy, sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
    x_min = std::min(x_min, x), x_max = std::max(x_max, x);
  }
  double Sxx() const { return sxx - sx * sx / n; }
  double Syy() const { return syy - sy * sy / n; }
  double Sxy() const { return sxy - sx * sy / n; }
  double Slope() const { return Sxy() / Sxx(); }
  double Correlation() const { return Sxy() / std::sqrt(Sxx() * Syy()); }
};

class Checker {
 public:
  Checker(const LogReader& reader) : reader_(reader), header_(reader.header()) {
    const auto index = [&](const char* name) { return header_.Index(name); };
    q_ = {index("q1"), index("q2")};
    tau_ = {index("tau1"), index("tau2")};
    v_ = {index("v1"), index("v2")};
    t_ = index("t");
    tip_fixed_ = index("tip_fixed");
    segment_ = index("segment");
    quasi_static_ = header_.Metadata("timing") == "quasi-static";
  }

  void Add(const double* row) {
    CheckJointRange(row);
    AddHold(row);
    if (have_previous_) AddStep(row);
    previous_.assign(row, row + header_.columns.size());
    have_previous_ = true;
  }

  std::vector<std::string> Finish() {
    CloseHold();
    CheckHoldSlopes();
    CheckVelocities();
    return TimeWarnings();
  }

 private:
  [[noreturn]] void Fail(std::size_t line, std::size_t column, std::string problem,
                         std::string fix) const {
    throw InputError(reader_.path(), line, column, std::move(problem), std::move(fix));
  }

  void CheckJointRange(const double* row) {
    const double range[2] = {kYawRangeRad, kPitchRangeRad};
    const char* joint[2] = {"yaw", "pitch"};
    for (int j = 0; j < 2; ++j) {
      const double q = row[q_[j]];
      if (std::abs(q) > kJointRangeMargin * range[j]) {
        Fail(reader_.line(), static_cast<std::size_t>(q_[j]) + 1,
             Format("q%d = %g rad is beyond the PSM's ", j + 1, q) + joint[j] +
                 Format(" range ±%.3f rad (dVRK configuration files)", range[j]),
             kDegreesFix);
      }
    }
  }

  // A hold is a run of rows with tip_fixed = 1 in one segment.
  void AddHold(const double* row) {
    const bool held = tip_fixed_ >= 0 && row[tip_fixed_] == 1.0;
    const double segment = segment_ >= 0 ? row[segment_] : 0.0;
    if (holding_ && (!held || segment != hold_segment_)) CloseHold();
    if (!held) return;
    holding_ = true;
    hold_segment_ = segment;
    for (int j = 0; j < 2; ++j) {
      if (std::isfinite(row[q_[j]]) && std::isfinite(row[tau_[j]])) {
        hold_[j].Add(row[tau_[j]], row[q_[j]]);
      }
    }
  }

  // Only holds loaded over 0.2 N·m or more tell a slope from the encoder's noise.
  void CloseHold() {
    for (int j = 0; j < 2; ++j) {
      const Regression& r = hold_[j];
      if (r.n >= 5 && r.x_max - r.x_min >= 0.2) slopes_[j].push_back(r.Slope());
      hold_[j] = Regression{};
    }
    holding_ = false;
  }

  void CheckHoldSlopes() {
    for (int j = 0; j < 2; ++j) {
      auto& s = slopes_[j];
      if (s.empty()) continue;
      std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
      const double median = s[s.size() / 2];
      if (std::abs(median) > kLargestPlausibleComplianceRadPerNm) {
        Fail(0, 0,
             Format("joint %d: on the held-tip rows (tip_fixed = 1) q%d moves by %.3g per N·m of "
                    "effort (median of the holds)",
                    j + 1, j + 1, median) +
                 Format("; an instrument's compliance is 0.03–0.1 rad/(N·m), and in degrees it "
                        "reads ~57 times that (%.2g–%.2g)",
                        0.03 * 180.0 / M_PI, 0.1 * 180.0 / M_PI),
             kDegreesFix);
      }
    }
  }

  void AddStep(const double* row) {
    const double dt = row[t_] - previous_[t_];
    // The median step from a systematic sample of at most kStepSample steps
    // (every stride_-th; the stride doubles when the sample fills), so that
    // the check's memory stays bounded on a log of any length.
    if (step_count_++ % stride_ == 0) {
      steps_.push_back(dt);
      if (steps_.size() == kStepSample) {
        for (std::size_t i = 0; i < kStepSample / 2; ++i) steps_[i] = steps_[2 * i];
        steps_.resize(kStepSample / 2);
        stride_ *= 2;
      }
    }
    if (dt > largest_gap_) largest_gap_ = dt, gap_line_ = reader_.line();
    for (int j = 0; j < 2 && !quasi_static_; ++j) {
      if (v_[j] < 0) continue;
      const double rate = (row[q_[j]] - previous_[q_[j]]) / dt;
      const double v = 0.5 * (row[v_[j]] + previous_[v_[j]]);
      if (std::isfinite(rate) && std::isfinite(v)) velocity_[j].Add(v, rate);
    }
  }

  // Δq/Δt against the logged velocity, where they track each other.
  void CheckVelocities() {
    for (int j = 0; j < 2; ++j) {
      const Regression& r = velocity_[j];
      if (r.n < 20 || !(r.Correlation() > 0.9)) continue;
      const double ratio = r.Slope();
      if (ratio > 20.0 && ratio < 200.0) {
        Fail(0, 0,
             Format("q%d changes %.3g times as fast as v%d says (Δq/Δt against v%d over the log)",
                    j + 1, ratio, j + 1, j + 1) +
                 Format(" while both should be in rad and rad/s; π/180 = 1/%.1f", 180.0 / M_PI),
             kDegreesFix);
      }
      if (ratio > 1e-4 && ratio < 1e-2) {
        Fail(0, 0,
             Format("q%d changes only %.3g times as fast as v%d says (Δq/Δt against v%d over the "
                    "log): t looks like milliseconds",
                    j + 1, ratio, j + 1, j + 1),
             "give t in seconds (divide it by 1000)");
      }
    }
  }

  std::vector<std::string> TimeWarnings() {
    std::vector<std::string> warnings;
    if (steps_.empty() || quasi_static_) return warnings;
    std::nth_element(steps_.begin(), steps_.begin() + steps_.size() / 2, steps_.end());
    const double median = steps_[steps_.size() / 2];
    const std::string file = reader_.path();
    if (median > kSlowestPlausibleRowPeriodS) {
      warnings.push_back(file + Format(": rows come every %.3g s (median): if t is in "
                                       "milliseconds, divide it by 1000; if the rows are held "
                                       "poses without time, add the line '# timing: quasi-static'",
                                       median));
    }
    if (largest_gap_ > kLongestPlausibleGapS && largest_gap_ > 1000.0 * median) {
      warnings.push_back(file + ":" + std::to_string(gap_line_) +
                         Format(": t jumps by %.4g s (the median step is %.3g s): two recordings "
                                "joined? Split the log, or give each part its own segment",
                                largest_gap_, median));
    }
    return warnings;
  }

  const LogReader& reader_;
  const LogHeader& header_;
  std::array<int, 2> q_{}, tau_{}, v_{};
  int t_ = 0, tip_fixed_ = -1, segment_ = -1;
  bool quasi_static_ = false;
  std::vector<double> previous_;
  bool have_previous_ = false;
  std::array<Regression, 2> hold_{}, velocity_{};
  bool holding_ = false;
  double hold_segment_ = 0.0;
  std::array<std::vector<double>, 2> slopes_;
  std::vector<double> steps_;
  static constexpr std::size_t kStepSample = 1 << 16;
  std::size_t step_count_ = 0, stride_ = 1;
  double largest_gap_ = 0.0;
  std::size_t gap_line_ = 0;
};

}  // namespace

LogPlausibility CheckLogPlausibility(const std::string& path, const LogReaderOptions& options) {
  // Standard input can be read once only, and the command itself reads it:
  // its rows get the per-row checks alone, and its span is unknown (NaN).
  if (path == "-") {
    LogPlausibility unknown;
    unknown.first_t_s = unknown.last_t_s = std::numeric_limits<double>::quiet_NaN();
    return unknown;
  }
  LogReader reader(path, options);
  Checker checker(reader);
  LogPlausibility out;
  const int t = reader.header().Index("t");
  bool first = true;
  while (const double* row = reader.Next()) {
    if (first) out.first_t_s = row[t], first = false;
    out.last_t_s = row[t];
    checker.Add(row);
  }
  out.warnings = checker.Finish();
  return out;
}

LogPlausibility CheckLogPlausibilityAndWarn(const std::string& path,
                                            const LogReaderOptions& options) {
  LogPlausibility out = CheckLogPlausibility(path, options);
  for (const auto& warning : out.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  return out;
}

}  // namespace pliant::io
