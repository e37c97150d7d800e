#pragma once
// Light-tracing splats (bidirectional methods): contributions a light path makes to whatever
// pixel it reaches. Each worker thread adds into its own buffer of exact XYZ sums per pixel
// (fixed_point.h); integer sums are associative, so the buffers added into the film after a pass
// give the same bits whatever the thread count or which thread traced which path.

#include <tbb/enumerable_thread_specific.h>

#include <cmath>
#include <vector>

#include "core/render/fixed_point.h"
#include "spectral/rgb.h"

namespace prism {

class SplatBuffer {
 public:
  SplatBuffer(int width, int height) : width_(width), sums_(size_t(width) * size_t(height) * 3, 0) {}

  // Adds xyz to the pixel holding film position (x, y) (pixels, inside the frame). A NaN or Inf
  // contribution is dropped; returns false for it. One beyond the fixed-point range is kept
  // apart (wide()), for the film's wide sums.
  bool add(float x, float y, const Xyz& xyz) {
    if (!(std::isfinite(xyz.x) && std::isfinite(xyz.y) && std::isfinite(xyz.z))) return false;
    const size_t p = size_t(y) * size_t(width_) + size_t(x);
    if (!(fixed_in_range(xyz.x) && fixed_in_range(xyz.y) && fixed_in_range(xyz.z))) {
      wide_.push_back({p, xyz});
      return true;
    }
    Fixed* s = &sums_[p * 3];
    s[0] += to_fixed(xyz.x), s[1] += to_fixed(xyz.y), s[2] += to_fixed(xyz.z);
    return true;
  }
  // The XYZ sums per pixel, and the splats beyond the fixed-point range (pixel, value).
  struct WideSplat {
    size_t pixel;
    Xyz xyz;
  };
  const std::vector<Fixed>& sums() const { return sums_; }
  const std::vector<WideSplat>& wide() const { return wide_; }
  void clear() {
    std::fill(sums_.begin(), sums_.end(), Fixed(0));
    wide_.clear();
  }

 private:
  int width_;
  std::vector<Fixed> sums_;
  std::vector<WideSplat> wide_;
};

// One SplatBuffer per worker thread, made on the thread's first use.
using ThreadSplats = tbb::enumerable_thread_specific<SplatBuffer>;

}  // namespace prism
