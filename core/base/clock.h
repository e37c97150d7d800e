#pragma once
// Wall-clock timing of the steps Prism reports (load, build, render, fit).

#include <chrono>

namespace prism {

// Seconds elapsed since t.
inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace prism
