// Running a study on one machine: a pool of threads over trial indices, a
// progress bar (io::Progress), and the outputs written when every trial is in.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "pliant/experiments/montecarlo.h"
#include "pliant/io/atomic_file.h"
#include "pliant/io/progress.h"

namespace pliant::experiments {

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

nlohmann::json TimingJson(int threads, int ranks, int trials, std::size_t trials_run, double wall_s) {
  return {{"threads", threads},
          {"ranks", ranks},
          {"trials", trials},
          {"trials_run", trials_run},
          {"wall_s", wall_s},
          {"seconds_per_trial", trials_run ? wall_s / trials_run : 0.0}};
}

void RunTrials(const Study& study, const std::vector<int>& trials, int threads,
               const std::function<void(const TrialResult&)>& done) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min<int>(threads, static_cast<int>(trials.size())));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex mutex;
  auto work = [&] {
    for (std::size_t i; !failed && (i = next++) < trials.size();) {
      try {
        const TrialResult result = RunTrial(study, trials[i]);
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failed) done(result);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failed) failure = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

nlohmann::json FinishStudy(const Study& study, int trials, TrialsFile& file,
                           const std::string& dir, const nlohmann::json& timing, bool plots) {
  file.Sort();
  std::vector<TrialResult> rows;
  for (const auto& [k, row] : file.finished()) {
    if (k < trials) rows.push_back(row);
  }
  const auto summary = SummariseStudy(study, rows);
  io::WriteFileAtomically(dir + "/summary.json", summary.dump(2) + "\n");
  io::WriteFileAtomically(dir + "/timing.json", timing.dump(2) + "\n");
  if (plots) {
    try {
      PlotStudy(rows, dir);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "warning: no plots: %s\n", e.what());
    }
  }
  return summary;
}

nlohmann::json RunMontecarlo(const Study& study, const MontecarloOptions& options) {
  const int trials = options.trials > 0 ? options.trials : study.trials;
  TrialsFile file(options.output_dir, study);
  const auto pending = file.Pending(trials);
  const int threads = options.threads > 0
                          ? options.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const double start = Now();
  {
    io::Progress progress("pliant montecarlo", "trials", trials);
    progress.Set(trials - static_cast<double>(pending.size()));
    RunTrials(study, pending, threads, [&](const TrialResult& r) {
      file.Append(r);
      progress.Add();
    });
  }
  const auto timing = TimingJson(threads, 1, trials, pending.size(), Now() - start);
  return FinishStudy(study, trials, file, options.output_dir, timing, options.plots);
}

}  // namespace pliant::experiments
