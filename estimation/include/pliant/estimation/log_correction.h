#pragma once
// Streams a log through a ComplianceCorrector: reads a row, corrects joints 1
// and 2, writes the row with q1_corr and q2_corr added. Memory is constant in
// the log's length; the output appears atomically, and only when every row
// was read and corrected.

#include <cstddef>
#include <string>

#include "pliant/estimation/compliance_correction.h"
#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/io/log_reader.h"

namespace pliant::estimation {

struct LogCorrectionSummary {
  std::size_t rows = 0;
  std::size_t skipped_rows = 0;         ///< bad rows dropped (skip_bad_rows)
  std::size_t depth_clamped_rows = 0;   ///< rows whose depth was outside the valid range
  std::string reference;                ///< "q*_true", "q*_ref", or "" when the log has none
  TipErrorStatistics uncorrected;       ///< tip error against the reference, mm
  TipErrorStatistics corrected;
};

/// Throws io::InputError for a bad log and std::system_error when the output
/// cannot be written; in both cases no output file is left behind.
LogCorrectionSummary CorrectLog(const std::string& input_path, const std::string& output_path,
                                const ComplianceCorrector& corrector,
                                const std::string& metadata_note,
                                io::LogReaderOptions options = {});

}  // namespace pliant::estimation
