#pragma once
// pliant correct --tare: the bias offset from the log's own unloaded rows.
#include <string>

#include "pliant/estimation/compliance_correction.h"

namespace pliant::cli {

/// `spec` is "auto" (the longest run of rows with a steady load) or "T0:T1"
/// (rows with t in [T0, T1], s). Sets the corrector's bias offset for each
/// recorded joint and returns what it found, in words, one line per joint.
/// Throws io::InputError for a bad spec or a range with no rows.
std::string TareFromLog(const std::string& log_path, const std::string& spec,
                        estimation::ComplianceCorrector* corrector);

}  // namespace pliant::cli
