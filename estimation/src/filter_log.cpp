#include "pliant/estimation/filter_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "pliant/estimation/effort_noise.h"
#include "pliant/estimation/filter_smoother.h"
#include "pliant/io/file_checksum.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "scratch_file.h"
#include "smoothed_pass.h"

namespace pliant::estimation {
namespace {

constexpr std::size_t kSpacingRows = 21;  // the rows whose spacing decides

double Optional(const double* row, int column) {
  return column >= 0 ? row[column] : std::numeric_limits<double>::quiet_NaN();
}

struct OutputColumns {
  explicit OutputColumns(io::LogHeader& header)
      : q1(header.AddColumn("q1_corr")),
        q2(header.AddColumn("q2_corr")),
        sd1(header.AddColumn("q1_sd")),
        sd2(header.AddColumn("q2_sd")),
        cov(header.AddColumn("q12_cov")),
        tip(header.AddColumn("tip_corr_mm")),
        tip_sd(header.AddColumn("tip_corr_sd_mm")),
        nis(header.AddColumn("nis")),
        flags(header.AddColumn("flags")),
        contact(header.AddColumn("contact_probability")) {}

  void Fill(const FilterEstimate& e, double* row) const {
    constexpr double kEmpty = std::numeric_limits<double>::quiet_NaN();
    row[q1] = recorded[0] ? e.corrected_rad[0] : kEmpty;
    row[q2] = recorded[1] ? e.corrected_rad[1] : kEmpty;
    row[sd1] = recorded[0] ? std::sqrt(e.covariance_rad2(0, 0)) : kEmpty;
    row[sd2] = recorded[1] ? std::sqrt(e.covariance_rad2(1, 1)) : kEmpty;
    row[cov] = recorded[0] && recorded[1] ? e.covariance_rad2(0, 1) : kEmpty;
    row[tip] = e.tip_correction_mm;
    row[tip_sd] = e.tip_correction_sd_mm;
    row[nis] = e.nis;
    row[flags] = double(e.flags);
    // One contact for the tip: both joints share its posterior.
    row[contact] = e.contact_probability[recorded[0] ? 0 : 1];
  }

  int q1, q2, sd1, sd2, cov, tip, tip_sd, nis, flags, contact;
  bool recorded[2] = {true, true};  // an unrecorded joint's columns are empty
};

// A log file's first rows: their times (the spacing, MedianRowSpacing),
// encoders and efforts (the noise: EffortNoiseFromSamples over the first
// kNoiseRows, its colour over the still stretches of all). Empty for standard
// input, which cannot be read twice.
struct LogPrefix {
  std::vector<double> times_s, encoder_rad[2], effort_nm[2];
};
constexpr std::size_t kNoiseRows = 4096;    // the rows whose efforts give the white noise
constexpr std::size_t kColourRows = 65536;  // the rows whose still stretches give its colour

LogPrefix ReadPrefix(const std::string& path, const io::LogReaderOptions& read_options) {
  LogPrefix prefix;
  if (path == "-") return prefix;
  io::LogReader reader(path, read_options);
  const io::StandardColumns in(reader.header());
  while (prefix.times_s.size() < kColourRows) {
    const double* row = reader.Next();
    if (row == nullptr) break;
    prefix.times_s.push_back(row[in.t]);
    prefix.encoder_rad[0].push_back(Optional(row, in.q1));
    prefix.encoder_rad[1].push_back(Optional(row, in.q2));
    prefix.effort_nm[0].push_back(row[in.tau1]);
    prefix.effort_nm[1].push_back(row[in.tau2]);
  }
  return prefix;
}

// What the filter runs with on this log: OptionsForLog, then EffortNoiseForLog.
FilterOptions UsedOptions(const models::ModelParameters& parameters, const FilterOptions& options,
                          const io::LogHeader& header, const std::string& path,
                          const io::LogReaderOptions& read_options, LogFilterSummary* summary) {
  const LogPrefix prefix = ReadPrefix(path, read_options);
  FilterOptions used =
      OptionsForLog(options, header, MedianRowSpacing(prefix.times_s), &summary->notes);
  if (path == "-" && used.effort_noise_from_log && !used.quasi_static) {
    summary->notes.push_back("standard input is read once: the effort noise is not estimated");
  }
  const std::string arm = ArmDynamicsAdvice(parameters, used, header);
  if (!arm.empty()) summary->advice.push_back(arm);
  if (const auto fitted = io::FittedOn(parameters.identified_from, path)) {  // (identify's record)
    summary->notes.push_back("the parameters were fitted on this log (" + fitted->file +
                             "): what it says of their errors is in-sample");
  }
  std::vector<double> first[2];
  for (int j = 0; j < 2; ++j) {
    const auto& e = prefix.effort_nm[j];
    first[j].assign(e.begin(), e.begin() + std::ptrdiff_t(std::min(e.size(), kNoiseRows)));
  }
  used = EffortNoiseForLog(used, first, &summary->notes, &summary->advice);
  return EffortColourForLog(used, prefix.times_s, prefix.encoder_rad, prefix.effort_nm,
                            &summary->notes, &summary->advice);
}

std::string Note(const std::string& metadata_note, const LogFilterSummary& summary) {
  std::string note = metadata_note;
  for (const auto& n : summary.notes) note += "; " + n;
  return note;
}

class Tally {
 public:
  Tally(LogFilterSummary* summary, const io::StandardColumns& in)
      : summary_(summary), in_(in), reference_(io::FindTipReference(in)) {
    summary_->reference = reference_.name;
  }

  void Count(const FilterEstimate& e) {
    ++summary_->rows;
    summary_->rejected_rows += (e.flags & kFlagRejected) != 0;
    summary_->missing_rows += (e.flags & kFlagMissing) != 0;
    summary_->depth_out_of_range_rows += (e.flags & kFlagDepthOutOfRange) != 0;
    summary_->saturated_rows += (e.flags & kFlagEffortSaturated) != 0;
    summary_->mismatch_rows += (e.flags & kFlagModelMismatch) != 0;
    nis_ += e.nis;
    dof_ += e.nis_dof;
    clearance_error_rad_ = e.clearance_error_rad;  // the instrument's states, as they end
    compliance_scale_ = e.compliance_scale;
  }

  void Accuracy(const double* row, const FilterEstimate& e, TipErrorStatistics* stats,
                bool also_uncorrected) {
    if (reference_.name.empty()) return;
    const Eigen::Vector2d truth(row[reference_.q1], row[reference_.q2]);
    const double depth = row[in_.q3];
    if (also_uncorrected) {
      summary_->uncorrected.Add(Eigen::Vector3d(row[in_.q1], row[in_.q2], depth), truth);
    }
    stats->Add(Eigen::Vector3d(e.corrected_rad[0], e.corrected_rad[1], depth), truth);
  }

  void Finish() { summary_->mean_nis_per_dof = dof_ > 0 ? nis_ / double(dof_) : 0.0; }

  // The instrument's states are constants the file states with a σ: where
  // one ends more than kDrift of them away, the log does not fit the file
  // (another instrument, or an effect the model lacks) and the summary says so.
  // A clearance is not told from one an encoder count away, whatever σ the
  // identification gave it: the count is added to its σ in quadrature.
  void InstrumentAdvice(const ComplianceFilter& filter, const FilterOptions& used) {
    constexpr double kDrift = 3.0;
    const double count_rad = std::sqrt(12.0) * used.encoder_noise_rad;
    for (int j = 0; j < 2; ++j) {
      if (!used.joint_recorded[j] || summary_->rows == 0) continue;
      Eigen::Vector2d sd = filter.instrument_prior_sd(j);
      sd[0] = std::hypot(sd[0], count_rad);
      const double e = clearance_error_rad_[j], s = compliance_scale_[j] - 1.0;
      char text[400];
      if (sd[0] > 0.0 && std::abs(e) > kDrift * sd[0]) {
        std::snprintf(text, sizeof text,
                      "joint %d's clearance ended %+.2f mrad from the file's δ (%.0f σ of its "
                      "%.2f mrad): this log does not fit the file — identify on this instrument, "
                      "or look for an effect the model lacks (pliant diagnose)",
                      j + 1, 1e3 * e, std::abs(e) / sd[0], 1e3 * sd[0]);
        summary_->advice.emplace_back(text);
      }
      if (sd[1] > 0.0 && std::abs(s) > kDrift * sd[1]) {
        std::snprintf(text, sizeof text,
                      "joint %d's compliance scale ended at %.3f (%.0f σ of its %.2f from 1): "
                      "the file's K is off on this log — identify on this instrument, or look "
                      "for an effect the model lacks (pliant diagnose)",
                      j + 1, 1.0 + s, std::abs(s) / sd[1], sd[1]);
        summary_->advice.emplace_back(text);
      }
    }
  }

 private:
  LogFilterSummary* summary_;
  const io::StandardColumns& in_;
  io::TipReference reference_;
  double nis_ = 0.0;
  double dof_ = 0.0;
  Eigen::Vector2d clearance_error_rad_{0.0, 0.0}, compliance_scale_{1.0, 1.0};
};

}  // namespace

FilterSample SampleFromRow(const io::StandardColumns& c, const double* row, bool fuse_reference) {
  FilterSample s;
  s.time_s = row[c.t];
  s.encoder_rad << row[c.q1], row[c.q2];
  s.insertion_depth_m = row[c.q3];
  s.effort_nm << row[c.tau1], row[c.tau2];
  if (fuse_reference) s.reference_rad << Optional(row, c.q1_ref), Optional(row, c.q2_ref);
  s.tip_fixed = Optional(row, c.tip_fixed) >= 0.5;  // NaN compares false: not fixed
  s.velocity_rad_s << Optional(row, c.v1), Optional(row, c.v2);
  return s;
}

namespace {

// Each row's smoothed values as the scratch file holds them: the output
// columns, then the corrected angles (the accuracy needs them, also where an
// unrecorded joint's column is empty).
constexpr std::size_t kSmoothedValues = 11;
constexpr std::size_t kChunkRows = 4096;  // rows read back from scratch at a time

// The smoothed pass in bounded memory (smoothed_pass.h): the input rows are
// spooled to a scratch file as they stream in (they are read again backward,
// block by block, and once more for the output), the smoothed values go to a
// second one at each row's place, and the output is written in order last.
LogFilterSummary SmoothLog(const std::string& input_path, const std::string& output_path,
                           const models::ModelParameters& parameters, const FilterOptions& options,
                           const std::string& metadata_note, io::LogReaderOptions read_options,
                           LogFilterSummary* summary) {
  io::LogReader reader(input_path, read_options);
  io::LogHeader header = reader.header();
  const io::StandardColumns in(header);
  const std::size_t input_columns = header.columns.size();
  const FilterOptions used = UsedOptions(parameters, options, header, input_path, read_options, summary);
  OutputColumns out(header);
  out.recorded[0] = used.joint_recorded[0];
  out.recorded[1] = used.joint_recorded[1];
  if (!metadata_note.empty()) {
    header.metadata.emplace_back("filter", Note(metadata_note, *summary) + ", RTS smoothed");
  }
  CheckpointedSmoother smoother(parameters, used);
  ScratchFile input_rows("the input rows"), smoothed("the smoothed values");
  Tally tally(summary, in);
  std::size_t rows = 0;
  while (const double* values = reader.Next()) {
    input_rows.Append(values, input_columns);
    const FilterEstimate e = smoother.Add(SampleFromRow(in, values, used.fuse_log_reference));
    tally.Count(e);
    tally.Accuracy(values, e, &summary->filtered, true);
    ++rows;
  }
  summary->skipped_rows = reader.skipped_rows();

  std::vector<double> block_rows, row(header.columns.size()), block_values;
  const auto read = [&](std::size_t first, std::size_t count, std::vector<FilterSample>* samples) {
    block_rows.resize(count * input_columns);
    input_rows.Read(first * input_columns, block_rows.size(), block_rows.data());
    samples->clear();
    for (std::size_t r = 0; r < count; ++r) {
      samples->push_back(SampleFromRow(in, &block_rows[r * input_columns], used.fuse_log_reference));
    }
  };
  const auto take = [&](std::size_t first, const std::vector<FilterEstimate>& estimates) {
    block_values.resize(estimates.size() * kSmoothedValues);
    for (std::size_t k = 0; k < estimates.size(); ++k) {
      double* values = &block_values[k * kSmoothedValues];
      std::fill(row.begin(), row.end(), 0.0);
      out.Fill(estimates[k], row.data());
      std::copy(row.begin() + std::ptrdiff_t(input_columns), row.end(), values);
      values[9] = estimates[k].corrected_rad[0];
      values[10] = estimates[k].corrected_rad[1];
    }
    smoothed.Write(first * kSmoothedValues, block_values.data(), block_values.size());
  };
  smoother.Smooth(read, take);

  io::LogWriter writer(output_path, header);
  for (std::size_t first = 0; first < rows; first += kChunkRows) {
    const std::size_t count = std::min(kChunkRows, rows - first);
    block_rows.resize(count * input_columns);
    input_rows.Read(first * input_columns, block_rows.size(), block_rows.data());
    block_values.resize(count * kSmoothedValues);
    smoothed.Read(first * kSmoothedValues, block_values.size(), block_values.data());
    for (std::size_t r = 0; r < count; ++r) {
      const double* values = &block_rows[r * input_columns];
      const double* smoothed_values = &block_values[r * kSmoothedValues];
      std::copy(values, values + input_columns, row.begin());
      std::copy(smoothed_values, smoothed_values + 9, row.begin() + std::ptrdiff_t(input_columns));
      writer.Write(row.data());
      FilterEstimate e;
      e.corrected_rad << smoothed_values[9], smoothed_values[10];
      tally.Accuracy(values, e, &summary->smoothed_error, false);
    }
  }
  writer.Commit();
  tally.Finish();
  tally.InstrumentAdvice(ComplianceFilter(parameters, used), used);
  return *summary;
}

}  // namespace

double MedianRowSpacing(const std::vector<double>& times_s) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < std::min(times_s.size(), kSpacingRows); ++i) {
    const double step = times_s[i] - times_s[i - 1];
    if (std::isfinite(step)) steps.push_back(step);
  }
  if (steps.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

// A log marked quasi-static has rows that are poses; so has one whose rows
// lie further apart than a time gap (a calibration's settled poses, hold
// means, a pose index for t): read as a continuous log, each of its rows
// would be a gap that starts the tip and the load again, and a clamp's load
// would be judged by its size alone.
FilterOptions OptionsForLog(FilterOptions options, const io::LogHeader& header,
                            double median_row_spacing_s, std::vector<std::string>* notes) {
  const bool spaced = !options.quasi_static && !header.QuasiStatic() &&
                      median_row_spacing_s >= options.time_gap_s;
  options.quasi_static = options.quasi_static || header.QuasiStatic() || spaced;
  if (options.quasi_static) {
    std::ostringstream why;
    if (spaced) {
      why << std::setprecision(3) << " (its rows lie a median " << median_row_spacing_s
          << " s apart, beyond the time gap of " << options.time_gap_s
          << " s: read as one row per pose)";
    }
    notes->push_back(
        "quasi-static log" + why.str() +
        ": each row filtered as a static measurement (t read as a pose index only; a contact "
        "may go on from pose to pose)");
  }
  for (int j = 0; j < 2; ++j) {
    options.joint_recorded[j] = header.JointRecorded(j + 1);
    if (!options.joint_recorded[j]) {
      const std::string n = std::to_string(j + 1);
      notes->push_back("joint " + n + " not recorded: kept at its prior, q" + n + "_corr and q" +
                       n + "_sd left empty");
    }
  }
  return options;
}

LogFilterSummary FilterLog(const std::string& input_path, const std::string& output_path,
                           const models::ModelParameters& parameters,
                           const FilterOptions& options, bool smooth,
                           const std::string& metadata_note, io::LogReaderOptions read_options) {
  LogFilterSummary summary;
  summary.smoothed = smooth;
  if (!smooth) {
    io::LogReader reader(input_path, read_options);
    io::LogHeader header = reader.header();
    const FilterOptions used =
        UsedOptions(parameters, options, header, input_path, read_options, &summary);
    ComplianceFilter filter(parameters, used);
    const io::StandardColumns in(header);
    const std::size_t input_columns = header.columns.size();
    OutputColumns out(header);
    out.recorded[0] = used.joint_recorded[0];
    out.recorded[1] = used.joint_recorded[1];
    if (!metadata_note.empty()) header.metadata.emplace_back("filter", Note(metadata_note, summary));
    io::LogWriter writer(output_path, header);
    Tally tally(&summary, in);
    std::vector<double> row(header.columns.size());
    while (const double* values = reader.Next()) {
      std::copy(values, values + input_columns, row.begin());
      const FilterEstimate e = filter.Step(SampleFromRow(in, values, used.fuse_log_reference));
      out.Fill(e, row.data());
      writer.Write(row.data());
      tally.Count(e);
      tally.Accuracy(values, e, &summary.filtered, true);
    }
    writer.Commit();
    summary.skipped_rows = reader.skipped_rows();
    tally.Finish();
    tally.InstrumentAdvice(filter, used);
    return summary;
  }

  return SmoothLog(input_path, output_path, parameters, options, metadata_note, read_options,
                   &summary);
}

}  // namespace pliant::estimation
