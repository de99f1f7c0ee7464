#include "correct_tare.h"

#include <cstdio>

#include "pliant/estimation/unloaded_rows.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/models/travel_since_reversal.h"

namespace pliant::cli {
namespace {

constexpr double kSteadyBandNm = 0.03;  // ± load of a steady, untouched joint
constexpr std::size_t kMinRows = 10;

std::string Line(const char* format, double a, double b, double c, double d) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, format, a, b, c, d);
  return buffer;
}

}  // namespace

std::string TareFromLog(const std::string& log_path, const std::string& spec,
                        estimation::ComplianceCorrector* corrector) {
  double t0 = 0.0, t1 = 0.0;
  const bool automatic = spec == "auto";
  if (!automatic && std::sscanf(spec.c_str(), "%lf:%lf", &t0, &t1) != 2) {
    throw io::InputError("--tare", 0, 0, "'" + spec + "' is neither auto nor T0:T1",
                         "write --tare auto, or --tare 0:2.5 for the rows with t from 0 to 2.5 s");
  }
  if (log_path == "-") {
    throw io::InputError("--tare", 0, 0,
                         "the tare reads the log before the correction does, and standard input "
                         "can be read once only",
                         "give the log as a file, or leave out --tare");
  }
  const io::Log log = io::ReadLog(log_path);
  const io::StandardColumns c(log.header);
  std::vector<double> load[2];
  std::vector<double> time;
  models::TravelSinceReversal travel;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const Eigen::Vector3d q(log.Value(r, c.q1), log.Value(r, c.q2), log.Value(r, c.q3));
    const auto result = corrector->Correct(
        q, {log.Value(r, c.tau1), log.Value(r, c.tau2)}, travel.Update(q.head<2>()));
    for (int j = 0; j < 2; ++j) load[j].push_back(result.external_torque_nm[j]);
    time.push_back(log.Value(r, c.t));
  }
  std::string words;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  for (int j = 0; j < 2; ++j) {
    if (!log.header.JointRecorded(j + 1)) continue;
    estimation::UnloadedRun run;
    if (automatic) {
      run = estimation::FindUnloadedRun(load[j], kSteadyBandNm, kMinRows);
    } else {
      for (std::size_t r = 0; r < time.size(); ++r) {
        if (time[r] < t0 || time[r] > t1) continue;
        if (run.rows == 0) run.first_row = r;
        run.rows = r + 1 - run.first_row;
      }
      if (run.rows == 0)
        throw io::InputError(log_path, 0, 0, "no row has t in " + spec,
                             "name a time range the log covers (its t column)");
    }
    const std::string joint = "joint " + std::to_string(j + 1);
    if (run.rows == 0) {
      words += "  tare " + joint + ": no run of " + std::to_string(kMinRows) +
               " rows with a steady load: the parameters' bias is used\n";
      continue;
    }
    const auto tare = estimation::TareOn(load[j], run, 0.0);
    offset[j] = tare.offset_nm;
    words += "  tare " + joint + Line(": %.0f unloaded rows (t %g to %g): bias offset %+.4f",
                                      double(tare.rows), time[run.first_row],
                                      time[run.first_row + run.rows - 1], tare.offset_nm) +
             Line(" ± %.4f N·m", tare.sd_nm, 0, 0, 0) +
             (tare.disagrees ? " — the log's unloaded rows disagree with the parameters' bias "
                               "beyond its σ\n"
                             : "\n");
  }
  corrector->SetBiasOffset(offset);
  return words;
}

}  // namespace pliant::cli
