#pragma once
// Progress report for long work on stderr: a bar with percentage and ETA on a terminal, plain
// lines at every 10% otherwise (logs stay readable). Thread-safe; cheap to call per work item.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace prism {

class Progress {
 public:
  Progress(std::string title, int64_t total, bool enabled = true);
  ~Progress();
  void advance(int64_t n = 1);
  void finish();  // prints the final state once; also called by the destructor

 private:
  void print(int64_t done, bool final);

  std::string title_;
  int64_t total_;
  bool enabled_, tty_;
  std::atomic<int64_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_print_;
  int last_decile_ = -1;
  bool finished_ = false;
};

}  // namespace prism
