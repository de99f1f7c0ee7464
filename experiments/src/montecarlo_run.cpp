// Running a study on one machine: a pool of threads over trial indices, a
// progress bar, and the outputs written when every trial is in.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "pliant/experiments/montecarlo.h"
#include "pliant/io/atomic_file.h"

namespace pliant::experiments {
namespace {

std::string Clock(double seconds) {
  const long s = std::lround(seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

}  // namespace

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

Progress::Progress(int total, int already_done)
    : total_(total), done_(already_done), started_with_(already_done), start_s_(Now()),
      terminal_(isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
  if (terminal_ && last_draw_s_ >= 0.0) std::fputc('\n', stderr);
}

void Progress::Tick() {
  ++done_;
  if (!terminal_) return;
  const double now = Now();
  if (done_ < total_ && now - last_draw_s_ < 0.2) return;  // redraw at most 5 times a second
  last_draw_s_ = now;
  const double elapsed = now - start_s_;
  const int run = done_ - started_with_;
  const double eta = run > 0 ? elapsed / run * (total_ - done_) : 0.0;
  constexpr int kWidth = 30;
  const int filled = total_ ? kWidth * done_ / total_ : kWidth;
  std::fprintf(stderr, "\r[%s%s] %d/%d trials  %s elapsed  ETA %s ",
               std::string(filled, '#').c_str(), std::string(kWidth - filled, ' ').c_str(), done_,
               total_, Clock(elapsed).c_str(), Clock(eta).c_str());
  std::fflush(stderr);
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
    Progress progress(trials, trials - static_cast<int>(pending.size()));
    RunTrials(study, pending, threads, [&](const TrialResult& r) {
      file.Append(r);
      progress.Tick();
    });
  }
  const auto timing = TimingJson(threads, 1, trials, pending.size(), Now() - start);
  return FinishStudy(study, trials, file, options.output_dir, timing, options.plots);
}

}  // namespace pliant::experiments
