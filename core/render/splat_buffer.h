#pragma once
// Light-tracing splats (bidirectional methods): contributions a light path makes to whatever
// pixel it reaches. Each worker thread adds into its own buffer of exact XYZ sums per pixel
// (fixed_point.h); integer sums are associative, so the buffers added into the film after a pass
// give the same bits whatever the thread count or which thread traced which path.

#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "core/render/fixed_point.h"
#include "spectral/rgb.h"

namespace prism {

class SplatBuffer {
 public:
  SplatBuffer(int width, int height) : width_(width), sums_(size_t(width) * size_t(height) * 3, 0) {}

  // Adds xyz to the pixel holding film position (x, y) (pixels, inside the frame). A NaN, Inf
  // or out-of-range contribution is dropped; returns false for it.
  bool add(float x, float y, const Xyz& xyz) {
    if (!(fixed_in_range(xyz.x) && fixed_in_range(xyz.y) && fixed_in_range(xyz.z))) return false;
    Fixed* s = &sums_[(size_t(y) * size_t(width_) + size_t(x)) * 3];
    s[0] += to_fixed(xyz.x), s[1] += to_fixed(xyz.y), s[2] += to_fixed(xyz.z);
    return true;
  }
  const std::vector<Fixed>& sums() const { return sums_; }
  void clear() { std::fill(sums_.begin(), sums_.end(), Fixed(0)); }

 private:
  int width_;
  std::vector<Fixed> sums_;
};

// One SplatBuffer per worker thread, made on the thread's first use.
using ThreadSplats = tbb::enumerable_thread_specific<SplatBuffer>;

}  // namespace prism
