#pragma once
// The process's resident set now and at its peak [MB] (Linux: /proc/self/status), for the
// benchmarks that report memory.

#include <fstream>
#include <string>
#include <utility>

namespace prism {

inline std::pair<double, double> resident_mb() {
  std::ifstream in("/proc/self/status");
  double now = 0, peak = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("VmRSS:", 0) == 0) now = std::stod(line.substr(6)) / 1024;
    if (line.rfind("VmHWM:", 0) == 0) peak = std::stod(line.substr(6)) / 1024;
  }
  return {now, peak};
}

}  // namespace prism
