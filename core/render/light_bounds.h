#pragma once
// What a light tree knows of a light or of a group of lights: where they are, the power they emit,
// and the cone of directions they emit into (Conty Estevez & Kulla, "Importance Sampling of Many
// Lights with Adaptive Tree Splitting", HPG 2018, §4; in the form of pbrt-v4's LightBounds,
// §12.6.3). LightTree's nodes keep them compactly and bound from them the light at a point.

#include "core/base/bounds.h"
#include "core/base/math.h"

namespace prism {

struct LightBounds {
  Bounds3f bounds;
  Vec3f w{0.f, 0.f, 1.f};  // unit axis of the cone holding the emitters' normals
  float phi = 0;           // power (luminous: the tree steers, the pdf keeps it exact)
  float cos_theta_o = 1;   // every normal lies within θ_o of w ...
  float cos_theta_e = 0;   // ... and each emits within θ_e of its normal (π/2: a Lambertian surface)
  bool two_sided = false;  // emits about −w too
};

// The bounds of two groups together: the box around both, the summed power, the smallest cone
// holding both cones (pbrt-v4 §12.6.3, DirectionCone's Union) and the wider emission angle.
LightBounds merge(const LightBounds& a, const LightBounds& b);

}  // namespace prism
