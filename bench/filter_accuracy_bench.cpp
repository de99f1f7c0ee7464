// Accuracy of the online filter on a simulated log with known truth (issue 5),
// side by side with the memoryless corrections, in one run:
//
//   build/bench/filter_accuracy_bench --params P.json LOG.csv [--free] [--smooth]
//       [--slow-speed 0.02] [--per-segment] [--trace FROM TO] [--motor-inertia KG_M2]
//       [--shaft-damping NM_S_PER_RAD] [--accel-time S]
//       [--clearance-sd RAD] [--offset-sd NM] [--offset-rate NM_S]   (default: the parameters' covariance, else filter.h's defaults)
//
// prints, against q1_true/q2_true, the RMS and largest tip error (mm, through
// the PSM kinematics) of the uncorrected encoders, equation (2), the dead-zone
// correction, the filter and (with --smooth) the RTS smoother, and the "no
// jumps" figures: during the slow pushes (segments whose metadata says
// "speed S rad/s" with S the slow speed), between consecutive samples of one
// push, in encoder counts (7.7 µrad), the largest |Δq_corr| − |Δq_enc| (how
// much further the corrected angle moved than the encoder: issue 5's goal,
// ≤ 3 counts) and the largest |Δq_corr − Δq_enc| (the figure of sessions
// 1–5, which even the truth does not meet: a held tip does not move while
// the encoder steps by up to 4 counts — the "truth" row shows it).
// --output-limit COUNTS sets FilterOptions::output_step_limit_counts (inf: off).
// --free drops the tip_fixed column (the filter is not told the tip is held).
// --motor-inertia J: the filter subtracts J·θ̈ from the effort (the simulator's
// arm has 0.08 kg·m²; FilterOptions' default is 0). --shaft-damping c_s: and
// the shaft's damping with the tip held (the simulator's instruments: 0.02).
// Not a Google Benchmark: an accuracy study, run by hand (docs/validation.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/filter.h"
#include "pliant/estimation/filter_log.h"
#include "pliant/estimation/filter_smoother.h"
#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/parameters_json.h"

namespace {

using namespace pliant;
constexpr double kCount = 7.7e-6;

struct Jumps {
  double worst = 0.0;       // max |Δq_corr| − |Δq_enc|, rad
  std::size_t row = 0;
  int joint = 0;
  double difference = 0.0;  // max |Δq_corr − Δq_enc|, rad
  void Add(std::size_t r, int j, double d_corr, double d_enc) {
    const double d = std::abs(d_corr) - std::abs(d_enc);
    if (d > worst) {
      worst = d;
      row = r;
      joint = j;
    }
    difference = std::max(difference, std::abs(d_corr - d_enc));
  }
};

struct Method {
  std::string name;
  estimation::TipErrorStatistics error;
  Jumps jumps;
  std::vector<Eigen::Vector2d> corrected;
};

std::map<int, double> SegmentSpeeds(const io::LogHeader& header) {
  std::map<int, double> speeds;
  for (const auto& [key, value] : header.metadata) {
    if (key.rfind("segment ", 0) != 0) continue;
    const auto at = value.find("speed ");
    if (at == std::string::npos) continue;
    speeds[std::atoi(key.c_str() + 8)] = std::atof(value.c_str() + at + 6);
  }
  return speeds;
}

int Usage() {
  std::fprintf(stderr,
               "usage: filter_accuracy_bench --params P.json LOG.csv [--free] [--smooth] "
               "[--slow-speed RAD_S] [--per-segment] [--trace FROM TO] [--motor-inertia KG_M2] [--shaft-damping NM_S_PER_RAD] [--accel-time S] [--output-limit COUNTS] [--clearance-sd RAD] [--offset-sd NM] [--offset-rate NM_S]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string params_path, log_path;
  bool free_tip = false, smooth = false, per_segment = false;
  double slow_speed = 0.02;
  long trace_from = -1, trace_to = -1;
  estimation::FilterOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--params" && i + 1 < argc) {
      params_path = argv[++i];
    } else if (a == "--free") {
      free_tip = true;
    } else if (a == "--per-segment") {  // the filter's worst step in each slow push
      per_segment = true;
    } else if (a == "--smooth") {
      smooth = true;
    } else if (a == "--motor-inertia" && i + 1 < argc) {
      options.motor_inertia_kg_m2 = std::atof(argv[++i]);
    } else if (a == "--shaft-damping" && i + 1 < argc) {
      options.shaft_damping_nm_s_per_rad = std::atof(argv[++i]);
    } else if (a == "--clearance-sd" && i + 1 < argc) {
      options.backlash_sd_rad.setConstant(std::atof(argv[++i]));
    } else if (a == "--offset-sd" && i + 1 < argc) {
      options.effort_offset_sd_nm.setConstant(std::atof(argv[++i]));
    } else if (a == "--offset-rate" && i + 1 < argc) {
      options.effort_offset_rate_nm = std::atof(argv[++i]);
    } else if (a == "--output-limit" && i + 1 < argc) {
      options.output_step_limit_counts = std::atof(argv[++i]);
    } else if (a == "--no-align") {  // the inertial torque as the samples come (it lags)
      options.align_inertial_torque = false;
    } else if (a == "--accel-time" && i + 1 < argc) {
      options.acceleration_filter_time_s = std::atof(argv[++i]);
    } else if (a == "--slow-speed" && i + 1 < argc) {
      slow_speed = std::atof(argv[++i]);
    } else if (a == "--trace" && i + 2 < argc) {  // print rows FROM..TO (debugging)
      trace_from = std::atol(argv[++i]);
      trace_to = std::atol(argv[++i]);
    } else if (!a.empty() && a[0] != '-' && log_path.empty()) {
      log_path = a;
    } else {
      return Usage();
    }
  }
  if (params_path.empty() || log_path.empty()) return Usage();
  try {
    const auto parameters = io::ReadParameters(params_path);
    const io::Log log = io::ReadLog(log_path);
    const io::StandardColumns c(log.header);
    if (c.q1_true < 0 || c.q2_true < 0) {
      std::fprintf(stderr, "%s has no q1_true, q2_true\n", log_path.c_str());
      return 2;
    }
    // What the log lets the filter read, as `pliant filter` decides it.
    std::vector<std::string> notes;
    options = estimation::OptionsForLog(options, log.header,
                                        estimation::MedianRowSpacing(log.Column("t")), &notes);
    for (const auto& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    const auto speeds = SegmentSpeeds(log.header);
    const std::size_t rows = log.Rows(), cols = log.Columns();
    const estimation::ComplianceCorrector paper(parameters, estimation::CorrectionModel::kPaper);
    const estimation::ComplianceCorrector deadzone(parameters,
                                                   estimation::CorrectionModel::kDeadZone);
    estimation::FilterSmoother smoother(parameters, options);
    estimation::ComplianceFilter filter(parameters, options);
    if (smooth) smoother.Reserve(rows);
    std::vector<Method> m(smooth ? 5 : 4);
    const char* names[] = {"uncorrected", "equation (2)", "dead-zone", "filter", "smoother"};
    for (std::size_t i = 0; i < m.size(); ++i) {
      m[i].name = names[i];
      m[i].corrected.resize(rows);
    }
    std::size_t rejected = 0, reacquired = 0, mismatch = 0;
    for (std::size_t r = 0; r < rows; ++r) {
      const double* v = &log.values[r * cols];
      auto s = estimation::SampleFromRow(c, v, false);
      if (free_tip) s.tip_fixed = false;
      const Eigen::Vector3d q(v[c.q1], v[c.q2], v[c.q3]);
      const Eigen::Vector2d tau(v[c.tau1], v[c.tau2]);
      m[0].corrected[r] = q.head<2>();
      m[1].corrected[r] = paper.Correct(q, tau).corrected_rad;
      m[2].corrected[r] = deadzone.Correct(q, tau).corrected_rad;
      const auto e = smooth ? smoother.Add(s) : filter.Step(s);
      m[3].corrected[r] = e.corrected_rad;
      rejected += (e.flags & estimation::kFlagRejected) != 0;
      reacquired += (e.flags & estimation::kFlagReacquired) != 0;
      mismatch += (e.flags & estimation::kFlagModelMismatch) != 0;
      if (long(r) >= trace_from && long(r) <= trace_to) {
        std::printf("%zu t=%.4f seg=%g fix=%d q-qt=(%.2f,%.2f) tau=(%.4f,%.4f) corr-qt=(%.2f,%.2f) "
                    "eq2-qt=(%.2f,%.2f) sd=(%.2f,%.2f) b=(%.2f,%.2f) that=(%.4f,%.4f) s=(%.3f,%.3f) "
                    "fl=%u\n",
                    r, v[c.t], c.segment >= 0 ? v[c.segment] : -1.0, int(s.tip_fixed),
                    (v[c.q1] - v[c.q1_true]) / kCount, (v[c.q2] - v[c.q2_true]) / kCount,
                    v[c.tau1], v[c.tau2], (e.corrected_rad[0] - v[c.q1_true]) / kCount,
                    (e.corrected_rad[1] - v[c.q2_true]) / kCount,
                    (m[1].corrected[r][0] - v[c.q1_true]) / kCount,
                    (m[1].corrected[r][1] - v[c.q2_true]) / kCount,
                    std::sqrt(e.covariance_rad2(0, 0)) / kCount,
                    std::sqrt(e.covariance_rad2(1, 1)) / kCount, e.backlash_offset_rad[0] / kCount,
                    e.backlash_offset_rad[1] / kCount, e.external_torque_nm[0],
                    e.external_torque_nm[1], e.compliance_scale[0], e.compliance_scale[1],
                    e.flags);
      }
    }
    if (smooth) {
      smoother.Smooth();
      for (std::size_t r = 0; r < rows; ++r) m[4].corrected[r] = smoother.Estimate(r).corrected_rad;
    }
    std::size_t slow_pairs = 0;
    std::map<int, Jumps> filter_by_segment;
    Jumps truth_jumps;
    for (std::size_t r = 0; r < rows; ++r) {
      const double* v = &log.values[r * cols];
      const Eigen::Vector2d truth(v[c.q1_true], v[c.q2_true]);
      for (auto& method : m) {
        method.error.Add(Eigen::Vector3d(method.corrected[r][0], method.corrected[r][1], v[c.q3]),
                         truth);
      }
      if (r == 0 || c.segment < 0) continue;
      const double* u = &log.values[(r - 1) * cols];
      const int segment = int(v[c.segment]);
      if (segment == 0 || int(u[c.segment]) != segment) continue;
      const auto it = speeds.find(segment);
      if (it == speeds.end() || std::abs(it->second - slow_speed) > 1e-6) continue;
      ++slow_pairs;
      for (int j = 0; j < 2; ++j) {
        filter_by_segment[segment].Add(r, j, m[3].corrected[r][j] - m[3].corrected[r - 1][j],
                                       j == 0 ? v[c.q1] - u[c.q1] : v[c.q2] - u[c.q2]);
      }
      for (auto& method : m) {
        for (int j = 0; j < 2; ++j) {
          method.jumps.Add(r, j, method.corrected[r][j] - method.corrected[r - 1][j],
                           j == 0 ? v[c.q1] - u[c.q1] : v[c.q2] - u[c.q2]);
        }
      }
      truth_jumps.Add(r, 0, v[c.q1_true] - u[c.q1_true], v[c.q1] - u[c.q1]);
      truth_jumps.Add(r, 1, v[c.q2_true] - u[c.q2_true], v[c.q2] - u[c.q2]);
    }
    std::printf("%s: %zu rows%s; filter: rejected %zu rows, re-acquired %zu, mismatch %zu\n",
                log_path.c_str(), rows, free_tip ? " (tip_fixed ignored)" : "", rejected,
                reacquired, mismatch);
    std::printf("  %-13s %10s %10s   %s\n", "", "RMS mm", "max mm",
                "slow pushes, counts: max |dq_corr|-|dq_enc| at row, joint; max |dq_corr-dq_enc|");
    const auto print_jumps = [&](const Jumps& jumps) {
      if (slow_pairs > 0) {
        std::printf("%8.1f at row %zu, joint %d; %.1f\n", jumps.worst / kCount, jumps.row,
                    jumps.joint + 1, jumps.difference / kCount);
      } else {
        std::printf("(no slow push)\n");
      }
    };
    for (const auto& method : m) {
      std::printf("  %-13s %10.3f %10.3f   ", method.name.c_str(), method.error.RmsMm(),
                  method.error.MaxMm());
      print_jumps(method.jumps);
    }
    std::printf("  %-13s %10s %10s   ", "truth", "", "");
    print_jumps(truth_jumps);
    if (per_segment) {
      for (const auto& [segment, jumps] : filter_by_segment) {
        std::printf("  segment %3d: filter %7.1f counts at row %zu, joint %d; %.1f\n", segment,
                    jumps.worst / kCount, jumps.row, jumps.joint + 1, jumps.difference / kCount);
      }
    }
    std::printf("  filter / equation (2): %.0f %%\n",
                100.0 * m[3].error.RmsMm() / m[1].error.RmsMm());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
