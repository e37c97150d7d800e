#pragma once
// A ray's hit on a surface, in world space, with what shading and ray spawning need.

#include <cstdint>

#include "core/base/frame.h"
#include "core/base/ray.h"
#include "materials/material.h"

namespace prism {

struct SurfaceInteraction {
  Vec3f p;                 // hit point (barycentric interpolation of the vertices)
  Vec3f p_error;           // per-axis bound on p's rounding error
  Vec3f n;                 // unit geometric normal; the glTF front side (counter-clockwise winding)
  Vec3f ns;                // unit shading normal, on the same side as n
  Vec3f wo;                // unit direction back along the incoming ray
  Vec3f tangent{0, 0, 0};  // unit, ⊥ ns: an anisotropic material's direction of anisotropy; else 0
  float t;                 // distance along the incoming ray
  const Material* material;
  SurfacePoint at;  // texture coordinates and vertex colour, for the material
  uint32_t instance, prim;
  // Where the triangle lies on a convex hull (Accel::hull), the distance of the hull's centroid from
  // the triangle's plane along n (the hull lies on that side; 0 elsewhere), and what a ray leaving
  // to the other side cannot meet: the instance, or every instance.
  float hull_side = 0;
  uint32_t hull_skip = kNoInstance;

  Ray spawn(const Vec3f& w) const {
    Ray r = spawn_ray(p, p_error, n, w);
    r.skip_instance = skip_towards(w);
    return r;
  }
  // What w cannot meet if it leaves the triangle away from the hull's side (hull_skip). A margin
  // beyond the normal's rounding keeps rays along the plane.
  uint32_t skip_towards(const Vec3f& w) const {
    const float out = dot(w, n);
    return (hull_side > 0 && out < -1e-4f) || (hull_side < 0 && out > 1e-4f) ? hull_skip : kNoInstance;
  }
  // The BSDFs' local frame: z = ns, x = the direction of anisotropy when there is one.
  Frame shading_frame() const {
    return tangent == Vec3f(0, 0, 0) ? Frame::from_z(ns) : Frame{tangent, cross(ns, tangent), ns};
  }
  // Whether the ray arrived on the front side (it enters a closed surface there).
  bool front_face() const { return dot(wo, n) > 0; }
};

}  // namespace prism
