#pragma once
// Parallel loops over independent work items (oneTBB underneath). Results must never depend on
// which thread runs an item: every item owns its output and its random numbers.

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <memory>

namespace prism {

// Limits the worker threads while alive; threads <= 0 means all hardware threads.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
    if (threads > 0)
      control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  }
  static int available() {
    return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  }

 private:
  std::unique_ptr<tbb::global_control> control_;
};

// Calls f(i) for i in [0, count) on all allowed threads, one item at a time.
template <typename F>
void parallel_for(int64_t count, F&& f) {
  tbb::parallel_for(
      tbb::blocked_range<int64_t>(0, count, 1),
      [&](const tbb::blocked_range<int64_t>& r) {
        for (int64_t i = r.begin(); i < r.end(); ++i) f(i);
      },
      tbb::simple_partitioner());
}

}  // namespace prism
