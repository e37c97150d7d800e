#pragma once
// The film: per-pixel sums of CIE XYZ estimates (box filter over each pixel's area). Each
// pixel is written by one thread only, in sample order, so images are deterministic.

#include <vector>

#include "spectral/rgb.h"

namespace prism {

class Film {
 public:
  Film(int width, int height) : width_(width), height_(height), sum_(size_t(width) * height * 3, 0.0) {}

  void add(int x, int y, const Xyz& xyz) {
    double* p = &sum_[(size_t(y) * width_ + x) * 3];
    p[0] += xyz.x;
    p[1] += xyz.y;
    p[2] += xyz.z;
  }

  // Interleaved XYZ per pixel: the sums divided by the samples per pixel.
  std::vector<float> xyz_image(int samples_per_pixel) const {
    std::vector<float> out(sum_.size());
    for (size_t i = 0; i < sum_.size(); ++i) out[i] = float(sum_[i] / samples_per_pixel);
    return out;
  }

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  std::vector<double> sum_;
};

}  // namespace prism
