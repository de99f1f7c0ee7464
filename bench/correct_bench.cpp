// Throughput of `pliant correct` on a 10^6-row log, side by side in one run with
//   raw_read     — the file's bytes read and their newlines counted (the floor),
//   copy_log     — the same log parsed and written back, no correction,
// so the correction is reported as a ratio to plain I/O. Run:
//   build/bench/correct_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "pliant/estimation/log_correction.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#include "pliant/io/parameters_json.h"

namespace {

namespace fs = std::filesystem;
constexpr std::size_t kRows = 1'000'000;

const fs::path& Directory() {
  static const fs::path dir = [] {
    auto d = fs::temp_directory_path() / "pliant_correct_bench";
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// A 1.5 kHz divot-push-like log with every standard column and one auxiliary.
const std::string& InputLog() {
  static const std::string path = [] {
    const std::string p = (Directory() / "in.csv").string();
    pliant::io::LogHeader header;
    header.metadata = {{"generator", "correct_bench"}};
    header.columns = {"t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "tip_fixed",
                      "motor_temperature_c"};
    pliant::io::LogWriter writer(p, header);
    for (std::size_t i = 0; i < kRows; ++i) {
      const double t = double(i) / 1500.0;
      const double load = std::sin(0.5 * t);
      const double row[] = {t, 0.1 + 7.7e-6 * std::round(load * 1000.0), -0.2, 0.15,
                            0.199 + load, -0.003 - 0.5 * load, 0.0, 0.0, 1.0, 35.0 + 1e-4 * t};
      writer.Write(row);
    }
    writer.Commit();
    return p;
  }();
  return path;
}

pliant::models::ModelParameters PaperParameters() {
  return pliant::io::ReadParameters(std::string(PLIANT_SOURCE_DIR) + "/data/paper.json");
}

void SetRows(benchmark::State& state) {
  state.counters["rows_per_s"] =
      benchmark::Counter(double(kRows) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RawRead(benchmark::State& state) {
  const std::string& path = InputLog();
  std::vector<char> buffer(1 << 20);
  for (auto _ : state) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    std::size_t lines = 0, n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0) {
      for (const char* p = buffer.data(); (p = static_cast<const char*>(
                                               std::memchr(p, '\n', buffer.data() + n - p)));
           ++p) {
        ++lines;
      }
    }
    std::fclose(f);
    benchmark::DoNotOptimize(lines);
  }
  SetRows(state);
}

void BM_CopyLog(benchmark::State& state) {
  const std::string& path = InputLog();
  const std::string out = (Directory() / "copy.csv").string();
  for (auto _ : state) {
    pliant::io::LogReader reader(path);
    pliant::io::LogWriter writer(out, reader.header());
    while (const double* row = reader.Next()) writer.Write(row);
    writer.Commit();
  }
  SetRows(state);
}

void BM_CorrectLog(benchmark::State& state) {
  const std::string& path = InputLog();
  const std::string out = (Directory() / "corrected.csv").string();
  const auto model = state.range(0) == 0 ? pliant::estimation::CorrectionModel::kPaper
                                         : pliant::estimation::CorrectionModel::kDeadZone;
  const pliant::estimation::ComplianceCorrector corrector(PaperParameters(), model);
  for (auto _ : state) {
    benchmark::DoNotOptimize(pliant::estimation::CorrectLog(path, out, corrector, "bench"));
  }
  state.SetLabel(state.range(0) == 0 ? "paper" : "deadzone");
  SetRows(state);
}

BENCHMARK(BM_RawRead)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CopyLog)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CorrectLog)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
