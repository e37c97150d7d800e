#pragma once
// A convex region bounded by planes: the pencil of a camera's rays through a rectangle of its
// film (Camera::frustum), tested against the accel's boxes and triangles (Accel::may_meet) to find
// what no ray of it can hit.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/base/bounds.h"
#include "core/base/transform.h"
#include "core/base/vec.h"

namespace prism {

// The points x with dot(n, x − origin) ≤ d for each plane (n unit length), in double.
struct Frustum {
  struct Plane {
    Vec3d n;
    double d;
  };
  Vec3d origin;
  std::array<Plane, 5> planes;
  int count = 0;

  // How far outside a plane a point must lie to be surely outside: 10⁻⁵ of the magnitude of the
  // coordinates in play (the origin's and those within `extent`), at least 10⁻²⁵. Far beyond the
  // float rounding of points, rays and the test itself (a few 2⁻²⁴ of it), so that what a ray of
  // the region touches is always kept.
  double margin(const Bounds3f& extent) const {
    const Vec3d a = max(max(abs(Vec3d(extent.lo)), abs(Vec3d(extent.hi))), abs(origin));
    return 1e-5 * std::max({a.x, a.y, a.z, 1e-25});
  }
  // The region in the space that `to_world` maps into this one's (to_object its inverse): each
  // plane's normal by the transpose of to_world's linear part.
  Frustum in_space_of(const AffineTransform& to_world, const Transform& to_object) const {
    Frustum f = *this;
    f.origin = to_object.point(origin);
    const Transform normals = transpose(to_world.transform());
    for (int i = 0; i < count; ++i) {
      const Vec3d n = normals.vector(planes[i].n);
      const double l = length(n);
      f.planes[i] = {n / l, planes[i].d / l};
    }
    return f;
  }
};

}  // namespace prism
