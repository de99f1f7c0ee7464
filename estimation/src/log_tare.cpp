#include "pliant/estimation/log_tare.h"

#include <cstdio>
#include <vector>

#include "pliant/estimation/bias_tare.h"
#include "pliant/estimation/compliance_correction.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/models/travel_since_reversal.h"

namespace pliant::estimation {
namespace {

constexpr double kSteadyBandNm = 0.03;  // ± load of a steady, untouched joint
constexpr std::size_t kMinRows = 10;

struct TareSpec {
  bool automatic = true;
  double t0_s = 0.0, t1_s = 0.0;
};

TareSpec ParseSpec(const std::string& spec) {
  TareSpec out;
  if (spec == "auto") return out;
  out.automatic = false;
  int used = 0;
  if (std::sscanf(spec.c_str(), "%lf:%lf%n", &out.t0_s, &out.t1_s, &used) != 2 ||
      used != int(spec.size())) {
    throw io::InputError("--tare", 0, 0, "'" + spec + "' is neither auto nor T0:T1",
                         "write --tare auto, or --tare 0:2.5 for the rows with t from 0 to 2.5 s");
  }
  return out;
}

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// The loads the parameters' model reads, per joint, and each row's t.
struct Loads {
  std::vector<double> load_nm[2];
  std::vector<double> t_s;
};

Loads LoadsOf(const io::Log& log, const models::ModelParameters& parameters) {
  const ComplianceCorrector corrector(parameters, CorrectionModel::kPaper);
  const io::StandardColumns c(log.header);
  models::TravelSinceReversal travel;
  Loads out;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    const Eigen::Vector3d q(log.Value(r, c.q1), log.Value(r, c.q2), log.Value(r, c.q3));
    const auto result = corrector.Correct(
        q, {log.Value(r, c.tau1), log.Value(r, c.tau2)}, travel.Update(q.head<2>()));
    for (int j = 0; j < 2; ++j) out.load_nm[j].push_back(result.external_torque_nm[j]);
    out.t_s.push_back(log.Value(r, c.t));
  }
  return out;
}

UnloadedRun NamedRows(const std::vector<double>& t_s, const TareSpec& spec) {
  UnloadedRun run;
  for (std::size_t r = 0; r < t_s.size(); ++r) {
    if (!(t_s[r] >= spec.t0_s && t_s[r] <= spec.t1_s)) continue;
    if (run.rows == 0) run.first_row = r;
    run.rows = r + 1 - run.first_row;
  }
  return run;
}

TareRows RowsOf(const io::Log& log, int joint, UnloadedRun run) {
  const io::StandardColumns c(log.header);
  TareRows rows;
  for (std::size_t r = run.first_row; r < run.first_row + run.rows; ++r) {
    rows.angle_rad.push_back(log.Value(r, joint == 0 ? c.q1 : c.q2));
    rows.depth_m.push_back(log.Value(r, c.q3));
  }
  return rows;
}

}  // namespace

LogTare TareOnLog(const std::string& log_path, const std::string& spec,
                  models::ModelParameters* parameters) {
  const TareSpec rows_wanted = ParseSpec(spec);
  if (log_path == "-") {
    throw io::InputError("--tare", 0, 0,
                         "the tare reads the log before the command does, and standard input can "
                         "be read only once",
                         "give the log as a file, or leave out --tare");
  }
  const io::Log log = io::ReadLog(log_path);
  const Loads loads = LoadsOf(log, *parameters);
  const UnloadedRun named =
      rows_wanted.automatic ? UnloadedRun{} : NamedRows(loads.t_s, rows_wanted);
  if (!rows_wanted.automatic && named.rows == 0) {
    const double first = loads.t_s.empty() ? 0.0 : loads.t_s.front();
    const double last = loads.t_s.empty() ? 0.0 : loads.t_s.back();
    throw io::InputError(log_path, 0, 0,
                         "--tare " + spec + " names no row" +
                             Format(": its t runs from %g to %g s", first, last),
                         "name a time range inside it, or write --tare auto");
  }
  LogTare out;
  for (int j = 0; j < 2; ++j) {
    JointTare& joint = out.joints[j];
    joint.recorded = log.header.JointRecorded(j + 1);
    if (!joint.recorded) continue;
    joint.run = rows_wanted.automatic
                    ? FindUnloadedRun(loads.load_nm[j], kSteadyBandNm, kMinRows)
                    : named;
    if (joint.run.rows == 0) continue;
    const TareRows rows = RowsOf(log, j, joint.run);
    joint.bias_sd_nm = BiasSdOver(*parameters, j, rows);
    joint.tare = TareOn(loads.load_nm[j], joint.run, joint.bias_sd_nm);
    joint.first_t_s = loads.t_s[joint.run.first_row];
    joint.last_t_s = loads.t_s[joint.run.first_row + joint.run.rows - 1];
    TareBiasTorque(j, joint.tare.offset_nm, joint.tare.sd_nm, rows,
                   "tared on " + log_path +
                       Format(": %+.4f ± %.4f N·m", joint.tare.offset_nm, joint.tare.sd_nm) +
                       Format(" from %.0f unloaded rows (t %g to %g)", double(joint.tare.rows),
                              joint.first_t_s, joint.last_t_s),
                   parameters);
  }
  return out;
}

std::string LogTare::Words() const {
  std::string words;
  for (int j = 0; j < 2; ++j) {
    const JointTare& joint = joints[j];
    if (!joint.recorded) continue;
    const std::string name = "  tare joint " + std::to_string(j + 1);
    if (joint.run.rows == 0) {
      words += name + ": no run of " + std::to_string(kMinRows) +
               " rows with a steady load: the parameters' bias is used\n";
      continue;
    }
    words += name +
             Format(": %.0f unloaded rows (t %g to %g)", double(joint.tare.rows), joint.first_t_s,
                    joint.last_t_s) +
             Format(": bias offset %+.4f ± %.4f N·m", joint.tare.offset_nm, joint.tare.sd_nm) +
             (joint.bias_sd_nm > 0.0
                  ? Format(" (the parameters' bias σ there: %.4f N·m)", joint.bias_sd_nm)
                  : "") +
             (joint.tare.disagrees ? " — the log's unloaded rows disagree with the parameters' "
                                     "bias beyond its σ\n"
                                   : "\n");
  }
  return words;
}

std::string LogTare::Note() const {
  std::string note;
  for (int j = 0; j < 2; ++j) {
    if (joints[j].run.rows == 0) continue;
    note += (note.empty() ? "bias tared on the log: " : ", ") + std::string("joint ") +
            std::to_string(j + 1) +
            Format(" %+.4f ± %.4f N·m", joints[j].tare.offset_nm, joints[j].tare.sd_nm);
  }
  return note;
}

}  // namespace pliant::estimation
