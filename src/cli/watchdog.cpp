#include "cli/watchdog.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace fremond::cli {

Watchdog::Watchdog(std::string prefix, std::string what, double limit, int code)
    : prefix_(std::move(prefix)), what_(std::move(what)), limit_(limit), code_(code) {
  thread_ = std::thread([this] { watch(); });
}

Watchdog::~Watchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  done_signal_.notify_all();
  thread_.join();
}

void Watchdog::watch() {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const auto at = [&](double s) {
    return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  double note = 1.0;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!done_) {
    const double next = limit_ > 0.0 ? std::min(note, limit_) : note;
    if (done_signal_.wait_until(lock, at(next), [this] { return done_; })) return;
    if (limit_ > 0.0 && next >= limit_) {
      std::fprintf(stderr,
                   "%s: error: no answer within --time-limit %g s (%s); stopped, nothing "
                   "written\n",
                   prefix_.c_str(), limit_, what_.c_str());
      std::fflush(stderr);
      std::_Exit(code_);  // the solver cannot be interrupted; nothing is half-written yet
    }
    std::fprintf(stderr, "%s: still solving after %g s (%s)%s\n", prefix_.c_str(), note,
                 what_.c_str(), limit_ > 0.0 ? "" : "; --time-limit sets a bound");
    std::fflush(stderr);
    note *= 2.0;
  }
}

}  // namespace fremond::cli
