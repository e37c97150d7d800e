#pragma once
// The Henyey–Greenstein phase function (Henyey & Greenstein 1941), the angular distribution of
// light scattered in a medium: with θ the angle between the direction light travelled before the
// event and after it, and g = E[cos θ] its asymmetry (> 0 forwards, < 0 backwards, 0 isotropic),
//   p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}).
// sample, eval and pdf mirror each other: sampling is exact (the CDF inverted in cos θ), so a
// sample's weight p / pdf is 1. Directions are world vectors; `d` is the direction of travel
// before the event (a ray's direction, not the BSDFs' wo that points back along it).

#include <cmath>

#include "core/base/frame.h"
#include "core/base/math.h"

namespace prism {

struct HenyeyGreenstein {
  float g = 0;  // in (−1, 1)

  float eval(const Vec3f& d, const Vec3f& wi) const { return density(dot(d, wi)); }
  float pdf(const Vec3f& d, const Vec3f& wi) const { return density(dot(d, wi)); }

  // A direction about d with density pdf(d, ·), from u ∈ [0, 1)².
  Vec3f sample(const Vec3f& d, Vec2f u) const {
    const float cos_theta = std::clamp(inverse_cdf(u.x), -1.f, 1.f);
    const float sin_theta = std::sqrt(std::max(0.f, 1 - cos_theta * cos_theta));
    const float phi = 2 * kPi * u.y;
    const Frame f = Frame::from_z(d);
    return f.to_world(Vec3f(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
  }

  float density(float cos_theta) const {
    const float denom = 1 + g * g - 2 * g * cos_theta;
    return kInv4Pi * (1 - g * g) / (denom * std::sqrt(denom));
  }

  // cos θ of the CDF value u: (1 + g² − ((1 − g²) / (1 − g + 2gu))²) / (2g), which runs from −1
  // at u = 0 to 1 at u = 1; 2u − 1 (isotropic) as g → 0, where that form loses its digits.
  float inverse_cdf(float u) const {
    if (std::abs(g) < 1e-3f) return 2 * u - 1;
    const float s = (1 - g * g) / (1 - g + 2 * g * u);
    return (1 + g * g - s * s) / (2 * g);
  }
};

}  // namespace prism
