#include "pliant/estimation/log_correction.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "pliant/estimation/effect_inputs.h"
#include "pliant/io/log_writer.h"

namespace pliant::estimation {

LogCorrectionSummary CorrectLog(const std::string& input_path, const std::string& output_path,
                                const ComplianceCorrector& corrector,
                                const std::string& metadata_note, io::LogReaderOptions options) {
  io::LogReader reader(input_path, options);
  io::LogHeader header = reader.header();
  const io::StandardColumns in(header);
  const std::size_t input_columns = header.columns.size();
  const int q1_corr = header.AddColumn("q1_corr");
  const int q2_corr = header.AddColumn("q2_corr");
  if (!metadata_note.empty()) header.metadata.emplace_back("correction", metadata_note);
  io::LogWriter writer(output_path, header);

  LogCorrectionSummary summary;
  const io::TipReference reference = io::FindTipReference(in);
  summary.reference = reference.name;
  std::vector<double> row(header.columns.size());
  // What the file's effects read of each row, as the identification fitted them.
  EffectInputs inputs(header.QuasiStatic());
  while (const double* values = reader.Next()) {
    std::copy(values, values + input_columns, row.begin());
    const Eigen::Vector3d q(values[in.q1], values[in.q2], values[in.q3]);
    const Eigen::Vector2d effort(values[in.tau1], values[in.tau2]);
    const auto result = corrector.Correct(inputs.Update(in, values), effort);
    row[q1_corr] = result.corrected_rad[0];
    row[q2_corr] = result.corrected_rad[1];
    writer.Write(row.data());
    ++summary.rows;
    summary.depth_clamped_rows += result.depth_clamped;
    if (!reference.name.empty()) {
      const Eigen::Vector2d truth(values[reference.q1], values[reference.q2]);
      summary.uncorrected.Add(q, truth);
      summary.corrected.Add(Eigen::Vector3d(row[q1_corr], row[q2_corr], q[2]), truth);
    }
  }
  writer.Commit();
  summary.skipped_rows = reader.skipped_rows();
  return summary;
}

}  // namespace pliant::estimation
