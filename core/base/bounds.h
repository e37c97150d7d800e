#pragma once
// Axis-aligned bounding box.

#include "base/vec.h"

namespace prism {

struct Bounds3f {
  Vec3f lo{kInfinity, kInfinity, kInfinity};
  Vec3f hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3f& p) { lo = min(lo, p), hi = max(hi, p); }
  void extend(const Bounds3f& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
  Vec3f diagonal() const { return hi - lo; }
  Vec3f centroid() const { return (lo + hi) * 0.5f; }
};

}  // namespace prism
