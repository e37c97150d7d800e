#pragma once
// Warps from the unit square to directions and points, each with its pdf.

#include <algorithm>
#include <cmath>

#include "core/base/vec.h"

namespace prism {

// Concentric map of the square to the unit disk (Shirley & Chiu 1997).
inline Vec2f sample_uniform_disk_concentric(Vec2f u) {
  const float ox = 2.f * u.x - 1.f, oy = 2.f * u.y - 1.f;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = (kPi / 4) * (oy / ox);
  } else {
    r = oy;
    theta = kPi / 2 - (kPi / 4) * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

// Cosine-weighted hemisphere about +z by Malley's method: pdf = cos θ / π.
inline Vec3f sample_cosine_hemisphere(Vec2f u) {
  const Vec2f d = sample_uniform_disk_concentric(u);
  const float z = safe_sqrt(1.f - d.x * d.x - d.y * d.y);
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta * kInvPi; }

// Uniform sphere: pdf = 1 / 4π.
inline Vec3f sample_uniform_sphere(Vec2f u) {
  const float z = 1.f - 2.f * u.x;
  const float r = safe_sqrt(1.f - z * z);
  const float phi = 2.f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform hemisphere about +z: pdf = 1 / 2π.
inline Vec3f sample_uniform_hemisphere(Vec2f u) {
  const float z = u.x;
  const float r = safe_sqrt(1.f - z * z);
  const float phi = 2.f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_hemisphere_pdf() { return kInv2Pi; }

// Uniform barycentrics (b0, b1, b2) on a triangle, area-preserving (Heitz 2019, "A
// Low-Distortion Map Between Triangle and Square").
inline Vec3f sample_uniform_triangle(Vec2f u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2;
    b0 = u.x - b1;
  }
  return {b0, b1, 1 - b0 - b1};
}

// Uniform on the regular polygon of `sides` ≥ 3 vertices on the unit circle, the first at angle
// `rotation` [radians]: u.x picks a wedge (centre and two neighbouring vertices), the rest of u.x
// and u.y a point uniform in it. (Its area, (sides/2) sin(2π/sides), is less than the disk's π.)
inline Vec2f sample_uniform_polygon(Vec2f u, int sides, float rotation) {
  const float scaled = u.x * float(sides);
  const int wedge = std::min(int(scaled), sides - 1);
  const float a0 = rotation + 2 * kPi * float(wedge) / float(sides), a1 = a0 + 2 * kPi / float(sides);
  const Vec3f b = sample_uniform_triangle({scaled - float(wedge), u.y});
  return Vec2f(std::cos(a0), std::sin(a0)) * b.y + Vec2f(std::cos(a1), std::sin(a1)) * b.z;  // b.x: the centre
}

}  // namespace prism
