#pragma once
// Axis-aligned bounding box.

#include "core/base/vec.h"

namespace prism {

struct Bounds3f {
  Vec3f lo{kInfinity, kInfinity, kInfinity};
  Vec3f hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3f& p) { lo = min(lo, p), hi = max(hi, p); }
  void extend(const Bounds3f& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
  Vec3f diagonal() const { return hi - lo; }
  Vec3f centroid() const { return (lo + hi) * 0.5f; }
  // Whether p lies in the box, its faces included (never for an infinite or NaN coordinate).
  bool inside(const Vec3f& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
  // Corner c (0 to 7): bit 0 picks hi's x, bit 1 its y, bit 2 its z.
  Vec3f corner(int c) const { return {(c & 1 ? hi : lo).x, (c & 2 ? hi : lo).y, (c & 4 ? hi : lo).z}; }
};

}  // namespace prism
