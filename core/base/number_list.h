#pragma once
// A list of comma-separated numbers, as command-line options take them ("1,0.5,2"): each cell a
// whole finite number, or one error naming the option, its value and the cell.

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/error.h"

namespace prism {

inline std::vector<double> parse_numbers(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    try {
      size_t used = 0;
      out.push_back(std::stod(cell, &used));
      if (used != cell.size() || !std::isfinite(out.back())) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      fail("{} '{}': '{}' is not a number", what, text, cell);
    }
  }
  return out;
}

// The same, each number also finite in single precision (coordinates, wavelengths, indices).
inline std::vector<float> parse_floats(const std::string& text, const std::string& what) {
  std::vector<float> out;
  for (const double v : parse_numbers(text, what)) {
    if (!std::isfinite(float(v))) fail("{} '{}': {:g} overflows single precision", what, text, v);
    out.push_back(float(v));
  }
  return out;
}

}  // namespace prism
