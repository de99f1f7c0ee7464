#pragma once
// Monte Carlo accuracy studies (`pliant montecarlo`, docs/montecarlo.md): the
// trials of a study run on a pool of threads (and, through the CLI, on MPI
// ranks); each finished trial is appended to DIR/trials.csv at once, so a
// killed study resumes where it stopped; the summary is computed from the
// rows in trial order, so it is bit-identical for any number of threads or
// ranks.
//
//   const auto study = ReadStudy("experiments/studies/divot_study.json");
//   MontecarloOptions options;
//   options.output_dir = "/tmp/mc";
//   RunMontecarlo(study, options);   // writes trials.csv, summary.json, timing.json, *.png

#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "pliant/experiments/montecarlo_trial.h"

namespace pliant::experiments {

/// One CSV line (with its newline) per trial; doubles in %.17g, so a row read
/// back is the same bits.
std::string TrialCsvHeader();
std::string FormatTrialRow(const TrialResult& result);
/// nullopt for a line that is not a whole row (e.g. torn by a kill).
std::optional<TrialResult> ParseTrialRow(std::string_view line);

/// DIR/trials.csv of one study. Its first line names the study's fingerprint
/// and seed; the rows follow in the order trials finished.
class TrialsFile {
 public:
  /// Creates DIR if needed. Keeps the whole rows of an earlier run of the same
  /// study (a torn last line is dropped); throws io::InputError when DIR holds
  /// another study's trials.
  TrialsFile(const std::string& dir, const Study& study);
  ~TrialsFile();
  TrialsFile(const TrialsFile&) = delete;
  TrialsFile& operator=(const TrialsFile&) = delete;

  /// Trials already done, by index.
  const std::map<int, TrialResult>& finished() const { return finished_; }
  /// Indices in [0, trials) not yet done, ascending.
  std::vector<int> Pending(int trials) const;
  /// Appends a row and flushes it to the kernel. Not thread-safe.
  void Append(const TrialResult& result);
  /// Rewrites the file with the rows in trial order (atomically).
  void Sort();

 private:
  std::string path_;
  std::string first_line_;
  std::map<int, TrialResult> finished_;
  std::FILE* stream_ = nullptr;
};

/// The summary of rows 0..n−1 (all of them, in trial order): tip-error
/// percentiles per method, NEES against its χ² band, 95 % coverage and the
/// sensitivity breakdown. Holds no timing.
nlohmann::json SummariseStudy(const Study& study, const std::vector<TrialResult>& rows);

/// Error distribution per method, and error against depth and peak torque
/// (DIR/error_distribution.png, DIR/error_vs_contact.png). Needs gnuplot.
void PlotStudy(const std::vector<TrialResult>& rows, const std::string& dir);

/// Runs `trials` on `threads` threads (0: all cores); `done` is called for each
/// finished trial, one call at a time. The first exception of a trial stops
/// the others and is rethrown.
void RunTrials(const Study& study, const std::vector<int>& trials, int threads,
               const std::function<void(const TrialResult&)>& done);

/// Monotonic wall-clock seconds (for timing.json, never for summary.json).
double Now();

/// timing.json: workers, wall time and seconds per trial of this run.
nlohmann::json TimingJson(int threads, int ranks, int trials, std::size_t trials_run, double wall_s);

/// After every trial is in `file`: sorts it and writes summary.json and
/// timing.json (`timing`) atomically, then the plots (skipped, with a
/// warning on stderr, when gnuplot fails). Returns the summary.
nlohmann::json FinishStudy(const Study& study, int trials, TrialsFile& file,
                           const std::string& dir, const nlohmann::json& timing, bool plots);

struct MontecarloOptions {
  std::string output_dir;
  int threads = 0;  ///< 0: every core
  int trials = 0;   ///< 0: the study's count
  bool plots = true;
};

/// The single-machine run: resume from DIR, run the rest on threads, finish.
nlohmann::json RunMontecarlo(const Study& study, const MontecarloOptions& options);

}  // namespace pliant::experiments
