// Identification on the simulator's logs of the paper's protocol: speed, and
// the honesty of the reported uncertainty over many seeds (a study, not a
// unit test: minutes of CPU). First make the logs (about 25 s per seed):
//
//   bench/make_identify_logs.sh /tmp/pliant_identify 1 50
//   PLIANT_IDENTIFY_LOGS=/tmp/pliant_identify build/bench/identify_bench \
//       --benchmark_counters_tabular=true
//
// Results are recorded in docs/validation.md (section 2) and, the speed, in
// docs/validation-studies.md (section 9).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <Eigen/Cholesky>
#include <boost/math/distributions/chi_squared.hpp>

#include "pliant/estimation/identification.h"
#include "pliant/estimation/joint_smoother.h"
#include "pliant/estimation/parameter_query.h"
#include "pliant/io/log_reader.h"

namespace {

using namespace pliant;

std::string LogDirectory() {
  const char* dir = std::getenv("PLIANT_IDENTIFY_LOGS");
  return dir ? dir : "/tmp/pliant_identify";
}

bool HaveSeed(int seed) {
  const std::string d = LogDirectory();
  return std::filesystem::exists(d + "/beam_" + std::to_string(seed) + ".csv") &&
         std::filesystem::exists(d + "/sweep_" + std::to_string(seed) + ".csv");
}

// The bias sweep and the 14-depth clamped beam of one seed, `copies` times
// (a longer log of the same protocol, for the time-against-length study).
estimation::IdentificationData Load(int first_seed, int copies = 1) {
  estimation::IdentificationData data;
  for (int c = 0; c < copies; ++c) {
    for (const char* kind : {"sweep_", "beam_"}) {
      const std::string path = LogDirectory() + "/" + kind + std::to_string(first_seed + c) + ".csv";
      estimation::AppendSamples(io::ReadLog(path), path, {}, &data);
    }
  }
  return data;
}

estimation::IdentificationResult Identify(const estimation::IdentificationData& data, bool smoother) {
  return smoother ? estimation::RunJointSmoother(data, estimation::PaperPrior())
                  : estimation::RunPaperProcedure(data, estimation::PaperPrior());
}

// Whole protocol (read + identify), one core.
void BM_IdentifyPaperProtocol(benchmark::State& state) {
  if (!HaveSeed(1)) return state.SkipWithError("no logs: run bench/make_identify_logs.sh first");
  const bool smoother = state.range(0) == 1;
  for (auto _ : state) {
    const auto data = Load(1, int(state.range(1)));
    benchmark::DoNotOptimize(Identify(data, smoother));
    state.counters["rows"] = double(data.log_rows);
    state.counters["samples"] = double(data.samples.size());
  }
}
BENCHMARK(BM_IdentifyPaperProtocol)
    ->ArgNames({"smoother", "copies"})
    ->ArgsProduct({{0, 1}, {1, 2, 4}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Worst |K/K_true − 1| over 0.09–0.22 m and |δ/δ_true − 1| of one joint. The
// law is evaluated without the file's clamp: when the simulator's sweep at an
// end depth lacks a leg (see docs/validation.md), the range shrinks.
std::pair<double, double> Errors(const models::ModelParameters& found, int joint) {
  const auto truth = estimation::PaperPrior();
  const auto& law = found.joints[joint].compliance;
  double worst = 0.0;
  for (double depth = 0.09; depth <= 0.2201; depth += 0.005) {
    const double k = models::EvaluateCompliance(law.form, law.cubic.coefficients.data(), depth);
    worst = std::max(worst, std::abs(k / models::ComplianceAt(truth.joints[joint], depth) - 1.0));
  }
  return {worst, std::abs(found.joints[joint].backlash_rad / truth.joints[joint].backlash_rad - 1.0)};
}

// Squared Mahalanobis distance of the truth (the paper's cubics and the dVRK
// file's δ) from the estimate, over the 10 numbers law1, law2, δ1, δ2.
double TruthDistance(const models::ModelParameters& found) {
  const auto truth = estimation::PaperPrior();
  const auto& c = *found.covariance;
  std::vector<long> index;
  Eigen::VectorXd error(10);
  int k = 0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 4; ++i, ++k) {
      const std::string name = "joint" + std::to_string(j + 1) + ".compliance.c" + std::to_string(3 - i);
      index.push_back(long(std::find(c.names.begin(), c.names.end(), name) - c.names.begin()));
      error[k] = found.joints[j].compliance.cubic.coefficients[i] - truth.joints[j].compliance.cubic.coefficients[i];
    }
  }
  for (int j = 0; j < 2; ++j, ++k) {
    const std::string name = "joint" + std::to_string(j + 1) + ".backlash_rad";
    index.push_back(long(std::find(c.names.begin(), c.names.end(), name) - c.names.begin()));
    error[k] = found.joints[j].backlash_rad - truth.joints[j].backlash_rad;
  }
  Eigen::MatrixXd sigma(10, 10);
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) sigma(a, b) = c.matrix(index[a], index[b]);
  return error.dot(sigma.ldlt().solve(error));
}

// Coverage: how often the truth lies inside the reported 95 % region.
void BM_Coverage(benchmark::State& state) {
  const bool smoother = state.range(0) == 1;
  const double limit = boost::math::quantile(boost::math::chi_squared(10.0), 0.95);
  for (auto _ : state) {
    int sets = 0, covered = 0, delta_covered = 0;
    double worst_k = 0.0, worst_delta = 0.0;
    for (int seed = 1; seed <= 200 && HaveSeed(seed); ++seed) {
      const auto r = Identify(Load(seed), smoother);
      ++sets;
      covered += TruthDistance(r.parameters) <= limit;
      const auto& c = *r.parameters.covariance;
      for (int j = 0; j < 2; ++j) {
        const auto [k_error, delta_error] = Errors(r.parameters, j);
        worst_k = std::max(worst_k, k_error);
        worst_delta = std::max(worst_delta, delta_error);
        const std::string name = "joint" + std::to_string(j + 1) + ".backlash_rad";
        const long i = long(std::find(c.names.begin(), c.names.end(), name) - c.names.begin());
        const double z = (r.parameters.joints[j].backlash_rad -
                          estimation::PaperPrior().joints[j].backlash_rad) / std::sqrt(c.matrix(i, i));
        delta_covered += std::abs(z) <= 1.959964;
      }
    }
    if (sets == 0) return state.SkipWithError("no logs: run bench/make_identify_logs.sh first");
    state.counters["data_sets"] = sets;
    state.counters["coverage_10d"] = double(covered) / sets;
    state.counters["coverage_delta"] = double(delta_covered) / (2.0 * sets);  // each δ alone
    state.counters["worst_K_err"] = worst_k;
    state.counters["worst_delta_err"] = worst_delta;
  }
}
BENCHMARK(BM_Coverage)->ArgName("smoother")->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
