// DIR/trials.csv: one row per finished trial, appended and flushed at once,
// so that a study killed at any moment resumes with every finished trial.
#include <charconv>
#include <cinttypes>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "pliant/experiments/montecarlo.h"
#include "pliant/io/atomic_file.h"
#include "pliant/io/input_error.h"

namespace pliant::experiments {
namespace {

constexpr int kDoubles = kSampledQuantities + kCorrectionMethods + 2 + 2 + 4;  // + nees, coverage, by joint
constexpr int kFields = 2 + kDoubles + 2 + 1;  // trial, seed, doubles, covered×2, held

std::string FirstLine(const Study& study) {
  char line[160];
  std::snprintf(line, sizeof line, "# pliant-montecarlo study %s fingerprint %016" PRIx64 " seed %" PRIu64 "\n",
                study.name.c_str(), study.fingerprint, study.seed);
  return line;
}

template <typename T>
bool Parse(std::string_view text, T& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

}  // namespace

std::string TrialCsvHeader() {
  std::string header = "trial,simulation_seed";
  for (int q = 0; q < kSampledQuantities; ++q) header += std::string(",") + SampledQuantityName(q);
  for (int m = 0; m < kCorrectionMethods; ++m) {
    header += std::string(",tip_error_") + CorrectionMethodName(m) + "_mm";
  }
  header += ",nees_filter,nees_smoother,coverage_filter,coverage_smoother";
  header += ",coverage_filter_j1,coverage_filter_j2,coverage_smoother_j1,coverage_smoother_j2";
  header += ",covered_filter,covered_smoother,held_samples\n";
  return header;
}

std::string FormatTrialRow(const TrialResult& r) {
  std::string row = std::to_string(r.trial) + "," + std::to_string(r.draw.simulation_seed);
  char number[32];
  const auto add = [&](double x) {
    std::snprintf(number, sizeof number, ",%.17g", x);
    row += number;
  };
  for (double x : r.draw.values) add(x);
  for (double x : r.tip_error_mm) add(x);
  for (double x : r.nees) add(x);
  for (double x : r.coverage_fraction) add(x);
  for (const auto& estimator : r.joint_coverage_fraction) {
    for (double x : estimator) add(x);
  }
  row += "," + std::to_string(r.covered[0]) + "," + std::to_string(r.covered[1]) + "," +
         std::to_string(r.held_samples) + "\n";
  return row;
}

std::optional<TrialResult> ParseTrialRow(std::string_view line) {
  if (line.empty() || line.back() != '\n') return std::nullopt;  // torn by a kill
  line.remove_suffix(1);
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (fields.size() != kFields) return std::nullopt;
  TrialResult r;
  double doubles[kDoubles];
  bool ok = Parse(fields[0], r.trial) && Parse(fields[1], r.draw.simulation_seed) && r.trial >= 0;
  for (int i = 0; i < kDoubles && ok; ++i) ok = Parse(fields[2 + i], doubles[i]);
  ok = ok && Parse(fields[2 + kDoubles], r.covered[0]) && Parse(fields[3 + kDoubles], r.covered[1]) &&
       Parse(fields[4 + kDoubles], r.held_samples);
  if (!ok) return std::nullopt;
  const double* d = doubles;
  for (double& x : r.draw.values) x = *d++;
  for (double& x : r.tip_error_mm) x = *d++;
  for (double& x : r.nees) x = *d++;
  for (double& x : r.coverage_fraction) x = *d++;
  for (auto& estimator : r.joint_coverage_fraction) {
    for (double& x : estimator) x = *d++;
  }
  return r;
}

TrialsFile::TrialsFile(const std::string& dir, const Study& study)
    : path_(dir + "/trials.csv"), first_line_(FirstLine(study)) {
  std::filesystem::create_directories(dir);
  std::ifstream in(path_, std::ios::binary);
  if (in) {
    std::string first, header, line;
    std::getline(in, first);
    if (first + "\n" != first_line_) {
      throw io::InputError(path_, 1, 0,
                           "this directory holds the trials of another study or seed ('" + first +
                               "'; this study: '" + first_line_.substr(0, first_line_.size() - 1) +
                               "')",
                           "give a new -o directory, or remove this one to start again");
    }
    std::getline(in, header);
    std::stringstream rest;
    rest << in.rdbuf();
    const std::string text = rest.str();
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t end = text.find('\n', start);
      const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
      // A torn or garbled row is dropped: that trial runs again.
      if (auto row = ParseTrialRow(std::string_view(text).substr(start, stop - start))) {
        finished_[row->trial] = *row;
      }
      start = stop;
    }
  }
  Sort();  // also rewrites a torn file without its torn line
  stream_ = std::fopen(path_.c_str(), "ab");
  if (!stream_) {
    throw std::system_error(errno, std::generic_category(), "cannot append to " + path_);
  }
}

TrialsFile::~TrialsFile() {
  if (stream_) std::fclose(stream_);
}

std::vector<int> TrialsFile::Pending(int trials) const {
  std::vector<int> pending;
  for (int k = 0; k < trials; ++k) {
    if (!finished_.count(k)) pending.push_back(k);
  }
  return pending;
}

void TrialsFile::Append(const TrialResult& result) {
  const std::string row = FormatTrialRow(result);
  if (std::fwrite(row.data(), 1, row.size(), stream_) != row.size() || std::fflush(stream_) != 0) {
    throw std::system_error(errno, std::generic_category(), "cannot write " + path_);
  }
  finished_[result.trial] = *ParseTrialRow(row);  // exactly what a resumed run will read
}

void TrialsFile::Sort() {
  std::string text = first_line_ + TrialCsvHeader();
  for (const auto& [k, row] : finished_) text += FormatTrialRow(row);
  if (stream_) std::fflush(stream_);
  io::WriteFileAtomically(path_, text);
  if (stream_) {  // keep appending to the new file, not the replaced one
    std::fclose(stream_);
    stream_ = std::fopen(path_.c_str(), "ab");
  }
}

}  // namespace pliant::experiments
