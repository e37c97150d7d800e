#include "core/render/light_bounds.h"

namespace prism {

namespace {

// v rotated by angle θ about the unit axis k (Rodrigues' formula).
Vec3f rotate(const Vec3f& v, const Vec3f& k, float theta) {
  const float c = std::cos(theta), s = std::sin(theta);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

}  // namespace

LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (a.phi == 0) return b;
  if (b.phi == 0) return a;
  LightBounds m;
  m.bounds = a.bounds;
  m.bounds.extend(b.bounds);
  m.phi = a.phi + b.phi;
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  m.two_sided = a.two_sided || b.two_sided;
  // The cone: one holds the other (first the cheap cases: all directions, or the same axis), or a
  // cone of half the angles' sum about a direction between them.
  const auto with_cone_of = [&m](const LightBounds& c) {
    m.w = c.w, m.cos_theta_o = c.cos_theta_o;
    return m;
  };
  const bool same_axis = a.w == b.w;
  if (a.cos_theta_o <= -1 || (same_axis && a.cos_theta_o <= b.cos_theta_o)) return with_cone_of(a);
  if (b.cos_theta_o <= -1 || (same_axis && b.cos_theta_o <= a.cos_theta_o)) return with_cone_of(b);
  // Whether one cone holds the other, θ_d + θ_b ≤ θ_a, from the cosines (no arc cosine: most merges
  // of a build end here): θ_d + θ_b ≤ π, i.e. cos θ_d + cos θ_b ≥ 0, and cos(θ_d + θ_b) ≥ cos θ_a.
  const float cos_d = clamp(dot(a.w, b.w), -1.f, 1.f), sin_d = std::sqrt(1 - cos_d * cos_d);
  const auto holds = [&](const LightBounds& outer, const LightBounds& inner) {
    const float sin_i = std::sqrt(std::max(0.f, 1 - inner.cos_theta_o * inner.cos_theta_o));
    return cos_d + inner.cos_theta_o >= 0 && cos_d * inner.cos_theta_o - sin_d * sin_i >= outer.cos_theta_o;
  };
  if (holds(a, b)) return with_cone_of(a);
  if (holds(b, a)) return with_cone_of(b);
  // The same test on the angles, for the pairs at its boundary that the cosines' rounding leaves
  // out: so that the cone below, rotated by θ_o − θ_a, never comes out narrower than either.
  const float theta_a = safe_acos(a.cos_theta_o), theta_b = safe_acos(b.cos_theta_o);
  const float theta_d = safe_acos(cos_d);
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return with_cone_of(a);
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return with_cone_of(b);
  const float theta_o = (theta_a + theta_d + theta_b) / 2;
  const Vec3f axis = cross(a.w, b.w);
  if (theta_o >= kPi || length_squared(axis) == 0) {
    m.w = a.w, m.cos_theta_o = -1;  // every direction
    return m;
  }
  m.w = normalize(rotate(a.w, normalize(axis), theta_o - theta_a));
  m.cos_theta_o = std::cos(theta_o);
  return m;
}

}  // namespace prism
