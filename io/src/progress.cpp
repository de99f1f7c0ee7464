#include "pliant/io/progress.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace pliant::io {
namespace {

std::atomic<bool> enabled{false};
std::atomic<int> depth{0};  // live Progress objects

// Redraws at most this often: often enough to look alive, rarely enough to
// cost nothing.
constexpr std::chrono::milliseconds kRedraw{200};

double NowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string Clock(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

std::string Count(double value) {
  char text[32];
  std::snprintf(text, sizeof text, value == std::floor(value) ? "%.0f" : "%.1f", value);
  return text;
}

}  // namespace

void Progress::Enable(bool on) { enabled.store(on); }
bool Progress::Enabled() { return enabled.load(); }
bool Progress::ShowProgressOn(int fd, bool quiet) { return !quiet && ::isatty(fd) != 0; }

Progress::Progress(std::string task, std::string unit, double total)
    : task_(std::move(task)), unit_(std::move(unit)), total_(total), start_s_(NowS()),
      drawing_(Enabled()), level_(++depth) {
  if (!drawing_) return;
  Draw();
  ticker_ = std::thread([this] { Tick(); });
}

Progress::~Progress() {
  if (drawing_) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    ticker_.join();
    Draw();
    // Erase: what the command prints next starts clean (an outer task redraws).
    if (depth.load() == level_) std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
  --depth;
}

void Progress::Add(double amount) {
  double done = done_.load(std::memory_order_relaxed);
  while (!done_.compare_exchange_weak(done, done + amount, std::memory_order_relaxed)) {
  }
}

void Progress::Tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, kRedraw, [this] { return stop_; })) Draw();
}

void Progress::Draw() {
  if (depth.load() != level_) return;  // an inner task has the line
  const double done = done_.load(std::memory_order_relaxed);
  const double elapsed = NowS() - start_s_;
  std::string line = "\r" + task_ + ":";
  if (total_ > 0.0) {
    constexpr int kWidth = 30;
    const double share = std::min(1.0, std::max(0.0, done / total_));
    const int filled = static_cast<int>(kWidth * share);
    line += " [" + std::string(filled, '#') + std::string(kWidth - filled, ' ') + "] " +
            Count(done) + "/" + Count(total_) + " " + unit_;
    line += "  " + Clock(elapsed) + " elapsed";
    if (done > 0.0) line += "  ETA " + Clock(elapsed / done * (total_ - done));
  } else {
    if (!unit_.empty()) line += " " + Count(done) + " " + unit_ + ",";
    line += " " + Clock(elapsed) + " elapsed";
  }
  line += "\033[K";
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace pliant::io
