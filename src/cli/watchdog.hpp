#pragma once
// A long computation watched from a second thread: notes on standard error that it is still
// working (after 1 s, then 2, 4, 8, ... s), and, past its time limit, says so and ends the process
// with a given exit status, before anything was written.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace fremond::cli {

class Watchdog {
 public:
  /// `prefix` starts each line ("fremond impact"); `what` says what is being computed; `limit`
  /// in seconds, 0 for none; `code` the exit status past it.
  Watchdog(std::string prefix, std::string what, double limit, int code);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  void watch();

  std::string prefix_, what_;
  double limit_;
  int code_;
  std::mutex mutex_;
  std::condition_variable done_signal_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace fremond::cli
