#pragma once
// Rays, and the robust spawning of secondary rays from surface points.

#include <cstdint>

#include "core/base/vec.h"

namespace prism {

inline constexpr uint32_t kNoInstance = 0xFFFFFFFF;
inline constexpr uint32_t kEveryInstance = 0xFFFFFFFE;  // as Ray::skip_instance: the ray meets nothing

struct Ray {
  Vec3f o;
  Vec3f d;
  float tmax = kInfinity;
  // An instance the ray cannot meet, which the accel then does not enter: the one it leaves from a
  // triangle on its convex hull, away from the hull (SurfaceInteraction::skip_towards); or
  // kEveryInstance, when that hull is the whole scene's.
  uint32_t skip_instance = kNoInstance;
};

// Moves a surface point p, known to lie within ±error (per axis) of the true surface, off the
// surface along the geometric normal n to the side of direction w, then rounds away from the
// surface, so that a ray leaving from it cannot re-hit that surface (pbrt-v4 §6.8.6). Always
// inlined: a call costs about as much as its body, and GCC left it out of line in the path loop
// whenever the loop's file ran out of inlining budget.
[[gnu::always_inline]] inline Vec3f offset_ray_origin(const Vec3f& p, const Vec3f& error, const Vec3f& n,
                                                      const Vec3f& w) {
  const float d = dot(abs(n), error);
  Vec3f offset = n * d;
  if (dot(w, n) < 0) offset = -offset;
  Vec3f po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0)
      po[i] = next_float_up(po[i]);
    else if (offset[i] < 0)
      po[i] = next_float_down(po[i]);
  }
  return po;
}

// A ray from a surface point towards direction w.
inline Ray spawn_ray(const Vec3f& p, const Vec3f& error, const Vec3f& n, const Vec3f& w) {
  return {offset_ray_origin(p, error, n, w), w, kInfinity};
}

// A shadow ray between two surface points, shortened so that it stops just short of the target
// point's own surface (1 − ε of the offset-to-offset distance, as in pbrt-v4's SpawnRayTo).
inline Ray spawn_ray_to(const Vec3f& p_from, const Vec3f& err_from, const Vec3f& n_from, const Vec3f& p_to,
                        const Vec3f& err_to, const Vec3f& n_to) {
  const Vec3f o = offset_ray_origin(p_from, err_from, n_from, p_to - p_from);
  const Vec3f target = offset_ray_origin(p_to, err_to, n_to, o - p_to);
  const Vec3f d = target - o;
  const float len = length(d);
  return {o, d / len, len * (1.f - 1e-4f)};
}

}  // namespace prism
