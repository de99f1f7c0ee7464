#pragma once
// How far a long task is, on one line of standard error redrawn a few times a
// second: the task, the count done (of its total, with a bar and an ETA, when
// the total is known) and the time elapsed. The line is drawn when the task
// starts, while it runs and when it ends, then erased, so a command's own
// output starts on a clean line.
//
// Off by default: a library prints nothing. The command line turns it on for
// the process when standard error is a terminal and --quiet is not given
// (ShowProgressOn); piped or redirected, a command stays quiet. Progress
// objects nest: while an inner one lives (a log being read inside a command's
// task), it alone draws.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace pliant::io {

class Progress {
 public:
  /// Turns drawing on or off for the whole process.
  static void Enable(bool on);
  static bool Enabled();
  /// The command line's rule: on when `fd` (standard error) is a terminal and
  /// the user did not ask for quiet.
  static bool ShowProgressOn(int fd, bool quiet);

  /// `total` 0: not known (the count and the time are shown); `unit` names
  /// what is counted ("rows", "MB", "trials"; "" with a total of 0 shows the
  /// elapsed time only, for a task with no count such as a solver's run).
  Progress(std::string task, std::string unit = "", double total = 0.0);
  /// Draws the final state and erases the line.
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Cheap (one relaxed atomic store) and safe from any thread: a loop may
  /// call it every iteration.
  void Set(double done) { done_.store(done, std::memory_order_relaxed); }
  /// Adds to the count; safe from any thread.
  void Add(double amount = 1.0);

 private:
  void Draw();
  void Tick();

  std::string task_, unit_;
  double total_;
  double start_s_;
  std::atomic<double> done_{0.0};
  bool drawing_;
  int level_;  ///< nesting depth: only the innermost live Progress draws
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread ticker_;
};

}  // namespace pliant::io
