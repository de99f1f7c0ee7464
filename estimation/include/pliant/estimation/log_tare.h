#pragma once
// --tare auto|T0:T1 of pliant correct and pliant filter: one pre-pass over the
// log that finds its unloaded rows (unloaded_rows.h) on the loads the
// parameters' model reads (tau − tau0 − internal effects, as
// ComplianceCorrector computes them), measures the bias error there and
// writes it into the parameters' bias torque (bias_tare.h). Both commands
// then run on the tared parameters: one model, tared once.

#include <array>
#include <string>

#include "pliant/estimation/unloaded_rows.h"
#include "pliant/models/parameters.h"

namespace pliant::estimation {

struct JointTare {
  bool recorded = false;    ///< the log records this joint (LogHeader::JointRecorded)
  UnloadedRun run;          ///< rows 0: no unloaded run found, the bias is left as it was
  TareOffset tare;          ///< offset, its σ, and whether it disagrees with the bias
  double bias_sd_nm = 0.0;  ///< the parameters' σ of tau0 over those rows (0: none given)
  double first_t_s = 0.0, last_t_s = 0.0;  ///< t of the run's first and last row
};

struct LogTare {
  std::array<JointTare, 2> joints;
  /// One line per recorded joint ("  tare joint 1: 848 unloaded rows (t 22.93
  /// to 31.4): bias offset +0.0799 ± 0.0003 N·m[ — … disagree …]").
  std::string Words() const;
  /// One line for the output log's metadata ("bias tared on the log: joint 1
  /// +0.0799 ± 0.0003 N·m, …"); empty when nothing was tared.
  std::string Note() const;
};

/// Reads the log at `log_path`, finds the tare rows of each recorded joint
/// (`spec` "auto": the longest run of at least 10 rows whose load stays within
/// ±0.03 N·m; "T0:T1": the rows with t in [T0, T1], s) and tares `parameters`
/// with what they show. Throws io::InputError for a spec that is neither, for
/// standard input ("-": the log is read twice), and for a range with no rows.
LogTare TareOnLog(const std::string& log_path, const std::string& spec,
                  models::ModelParameters* parameters);

}  // namespace pliant::estimation
