#pragma once
// A ray's hit on a surface, in world space, with what shading and ray spawning need.

#include <cstdint>

#include "base/frame.h"
#include "base/ray.h"
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

  Ray spawn(const Vec3f& w) const { return spawn_ray(p, p_error, n, w); }
  // The BSDFs' local frame: z = ns, x = the direction of anisotropy when there is one.
  Frame shading_frame() const {
    return tangent == Vec3f(0, 0, 0) ? Frame::from_z(ns) : Frame{tangent, cross(ns, tangent), ns};
  }
  // Whether the ray arrived on the front side (it enters a closed surface there).
  bool front_face() const { return dot(wo, n) > 0; }
};

}  // namespace prism
