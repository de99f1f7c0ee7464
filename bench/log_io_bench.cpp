// Log I/O throughput: LogReader streaming parse and LogWriter, each against
// the cost of just reading the file's bytes, so a slowdown shows whether it is
// the parser or the disk. The log (10^6 rows x 10 columns of full-precision
// doubles, about 180 MB) is written once to the temporary directory.
//
//   ./log_io_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"

namespace {

constexpr std::size_t kRows = 1'000'000;
using Clock = std::chrono::steady_clock;

pliant::io::LogHeader BenchHeader() {
  pliant::io::LogHeader header;
  header.metadata = {{"source", "log_io_bench"}};
  header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "q1_cmd", "q2_cmd"};
  return header;
}

// A 1.5 kHz PSM log: smooth motions, efforts with noise-like digits.
void FillRow(std::size_t i, double* row) {
  const double t = static_cast<double>(i) / 1500.0;
  row[0] = t;
  row[1] = 0.8 * std::sin(0.7 * t);
  row[2] = 0.5 * std::cos(0.45 * t);
  row[3] = 0.15 + 0.05 * std::sin(0.2 * t);
  row[4] = 0.3 * std::sin(3.1 * t + 0.2);
  row[5] = -0.2 * std::cos(2.3 * t);
  row[6] = 0.56 * std::cos(0.7 * t);
  row[7] = -0.225 * std::sin(0.45 * t);
  row[8] = row[1] + 1e-4 * std::sin(40.0 * t);
  row[9] = row[2] - 1e-4 * std::cos(40.0 * t);
}

std::string TempPath(const char* name) {
  return (std::filesystem::temp_directory_path() /
          ("pliant_log_io_bench_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// Written on first use and removed at exit.
struct BenchLog {
  std::string path = TempPath("input.csv");
  BenchLog() {
    pliant::io::LogWriter writer(path, BenchHeader());
    double row[10];
    for (std::size_t i = 0; i < kRows; ++i) {
      FillRow(i, row);
      writer.Write(row);
    }
    writer.Commit();
  }
  ~BenchLog() { std::filesystem::remove(path); }
};

const std::string& LogPath() {
  static const BenchLog log;
  return log.path;
}

// The floor any parser stands on: read 1 MiB chunks and count newlines.
std::size_t CountLines(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  std::vector<char> buffer(std::size_t{1} << 20);
  std::size_t lines = 0;
  ssize_t got;
  while ((got = ::read(fd, buffer.data(), buffer.size())) > 0) {
    const char* p = buffer.data();
    const char* const end = p + got;
    while (
        (p = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p))))) {
      ++lines;
      ++p;
    }
  }
  ::close(fd);
  return lines;
}

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Raw-read seconds per pass, measured right after a benchmark's timed loop
// (outside it) on the same warm page cache.
double RawReadSeconds(const std::string& path) {
  double best = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = Clock::now();
    benchmark::DoNotOptimize(CountLines(path));
    best = std::min(best, SecondsSince(start));
  }
  return best;
}

void SetCounters(benchmark::State& state, double seconds, double raw_seconds) {
  const auto passes = static_cast<double>(state.iterations());
  state.counters["rows/s"] =
      benchmark::Counter(static_cast<double>(kRows) * passes, benchmark::Counter::kIsRate);
  state.counters["raw_rows/s"] = static_cast<double>(kRows) / raw_seconds;
  state.counters["x_raw_read"] = seconds / passes / raw_seconds;
  state.SetBytesProcessed(static_cast<std::int64_t>(std::filesystem::file_size(LogPath())) *
                          state.iterations());
}

void BM_RawRead(benchmark::State& state) {
  const std::string& path = LogPath();
  const auto start = Clock::now();
  for (auto _ : state) benchmark::DoNotOptimize(CountLines(path));
  SetCounters(state, SecondsSince(start),
              SecondsSince(start) / static_cast<double>(state.iterations()));
}

void BM_LogReaderParse(benchmark::State& state) {
  const std::string& path = LogPath();
  const auto start = Clock::now();
  for (auto _ : state) {
    pliant::io::LogReader reader(path);
    double sum = 0.0;
    while (const double* row = reader.Next()) sum += row[4];
    benchmark::DoNotOptimize(sum);
  }
  const double seconds = SecondsSince(start);
  SetCounters(state, seconds, RawReadSeconds(path));
}

void BM_LogWriter(benchmark::State& state) {
  const std::string input = LogPath();
  const std::string path = TempPath("output.csv");
  const pliant::io::LogHeader header = BenchHeader();
  std::vector<double> rows(kRows * 10);  // generated up front: only writing is timed
  for (std::size_t i = 0; i < kRows; ++i) FillRow(i, &rows[i * 10]);
  const auto start = Clock::now();
  for (auto _ : state) {
    pliant::io::LogWriter writer(path, header);
    for (std::size_t i = 0; i < kRows; ++i) writer.Write(&rows[i * 10]);
    writer.Commit();  // includes fsync: what a user's command pays
  }
  const double seconds = SecondsSince(start);
  SetCounters(state, seconds, RawReadSeconds(input));
  std::filesystem::remove(path);
}

BENCHMARK(BM_RawRead)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LogReaderParse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LogWriter)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
