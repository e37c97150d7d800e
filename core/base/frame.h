#pragma once
// Orthonormal frame around a unit vector: world <-> local coordinates, local z = the normal.

#include "core/base/vec.h"

namespace prism {

struct Frame {
  Vec3f x, y, z;

  // Branchless orthonormal basis from a unit vector (Duff et al. 2017, "Building an
  // Orthonormal Basis, Revisited", JCGT 6(1)).
  static Frame from_z(const Vec3f& n) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3f(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3f(b, sign + n.y * n.y * a, -n.y), n};
  }

  Vec3f to_local(const Vec3f& v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
  Vec3f to_world(const Vec3f& v) const { return x * v.x + y * v.y + z * v.z; }
};

}  // namespace prism
