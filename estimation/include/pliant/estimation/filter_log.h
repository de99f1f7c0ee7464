#pragma once
// Runs the online filter over a log and writes it back with the filter's
// columns added (docs/filter.md):
//   q1_corr, q2_corr (rad)   corrected joint angles
//   q1_sd, q2_sd (rad)       their standard deviations
//   q12_cov (rad²)           their covariance
//   tip_corr_mm, tip_corr_sd_mm   tip correction through the kinematics, and its σ
//   nis                      normalised innovation squared of the step
//   flags                    FilterFlag bits (filter.h)
// Without smoothing it streams: constant memory, one row in, one row out.
// With smoothing the whole log is held and the RTS smoother's estimates are
// written (NIS and flags stay the filter's). Output is atomic.

#include <cstddef>
#include <string>
#include <vector>

#include "pliant/estimation/filter.h"
#include "pliant/estimation/tip_error_statistics.h"
#include "pliant/io/log.h"
#include "pliant/io/log_reader.h"

namespace pliant::estimation {

struct LogFilterSummary {
  std::size_t rows = 0;
  std::size_t skipped_rows = 0;        ///< bad rows dropped (skip_bad_rows)
  std::size_t rejected_rows = 0;       ///< rows with a measurement rejected by the gate
  std::size_t missing_rows = 0;        ///< rows with a NaN measurement skipped
  std::size_t depth_out_of_range_rows = 0;
  std::size_t saturated_rows = 0;
  std::size_t mismatch_rows = 0;       ///< rows with the model-mismatch flag
  bool smoothed = false;
  std::string reference;               ///< "q*_true", "q*_ref", or ""
  TipErrorStatistics uncorrected;      ///< tip error against the reference, mm
  TipErrorStatistics filtered;
  TipErrorStatistics smoothed_error;   ///< when smoothed
  double mean_nis_per_dof = 0.0;       ///< ≈ 1 when the noise model is right
  /// What the log's header changed (a quasi-static log, an unrecorded joint),
  /// one sentence each; also in the output's "filter" metadata.
  std::vector<std::string> notes;
  /// What the log suggests that the filter did not take (EffortNoiseForLog):
  /// printed, not written into the output.
  std::vector<std::string> advice;
};

/// The sample the filter sees in one row of a log with these columns; the
/// q*_ref columns become its reference only with fuse_reference
/// (FilterOptions::fuse_log_reference).
FilterSample SampleFromRow(const io::StandardColumns& columns, const double* row,
                           bool fuse_reference);

/// The median step of t between consecutive rows over the first 21 times
/// given (NaN with fewer than 3 finite steps).
double MedianRowSpacing(const std::vector<double>& times_s);

/// What a log lets the filter read: which joints it records (its header), and
/// whether its rows are poses rather than samples in time — marked so
/// ("# timing: quasi-static") or lying a median of more than
/// FilterOptions::time_gap_s apart. Adds one sentence per change to `notes`.
FilterOptions OptionsForLog(FilterOptions options, const io::LogHeader& header,
                            double median_row_spacing_s, std::vector<std::string>* notes);

/// On a log of samples in time (not quasi-static: a pose's effort is no
/// sample of a steady rate), the larger recorded joint's EffortNoiseFromSamples
/// over the log's first rows (effort_nm: joint 1's, joint 2's). Where it is
/// above effort_noise_nm, with FilterOptions::effort_noise_from_log
/// effort_noise_nm becomes it (never lowered: the option also stands for what
/// the effort holds besides white noise) and one sentence in `notes` says so;
/// without, the sentence goes to `advice`.
FilterOptions EffortNoiseForLog(FilterOptions options, const std::vector<double> effort_nm[2],
                                std::vector<std::string>* notes, std::vector<std::string>* advice);

/// On a log of samples in time: each recorded joint's EffortNoiseColourFromStill
/// over the log's StillStretches (times_s, encoders and efforts of the log's
/// first rows). Where the effort's noise is correlated over more than a
/// sample and β is otherwise off (σ_β 0, no tare, no fused reference),
/// with FilterOptions::effort_colour_from_log β carries it (σ_β, τβ of that
/// joint) and one sentence in `notes` says so; else the sentence goes to
/// `advice`. docs/decisions/coloured-effort-noise.md.
FilterOptions EffortColourForLog(FilterOptions options, const std::vector<double>& times_s,
                                 const std::vector<double> encoder_rad[2],
                                 const std::vector<double> effort_nm[2],
                                 std::vector<std::string>* notes, std::vector<std::string>* advice);

/// Online — the log has no tip_fixed column, its rows are samples in time and
/// contact is inferred — with neither joint_inertia nor joint_friction in the
/// parameters: the sentence that says the filter learns the arm's torque from
/// its generic priors, which take up a push's first load, and how to identify
/// the arm's own (docs/decisions/arm-dynamics-from-free-motion.md); "" else.
std::string ArmDynamicsAdvice(const models::ModelParameters& parameters,
                              const FilterOptions& used, const io::LogHeader& header);

/// Throws io::InputError for a bad log and std::system_error when the output
/// cannot be written; no output file is left behind then.
LogFilterSummary FilterLog(const std::string& input_path, const std::string& output_path,
                           const models::ModelParameters& parameters,
                           const FilterOptions& options, bool smooth,
                           const std::string& metadata_note, io::LogReaderOptions read_options = {});

}  // namespace pliant::estimation
