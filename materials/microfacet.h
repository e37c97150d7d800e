#pragma once
// The Trowbridge–Reitz (GGX) microfacet distribution (Trowbridge & Reitz 1975; Walter et al.
// 2007), isotropic with roughness α (glTF: α = roughness²), with the height-correlated Smith
// masking-shadowing term (Heitz 2014, "Understanding the Masking-Shadowing Function") and
// sampling of the visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4)). Directions in the local frame, z = macro-surface normal.

#include <cmath>

#include "base/vec.h"
#include "base/warp.h"

namespace prism {

class TrowbridgeReitz {
 public:
  explicit TrowbridgeReitz(float alpha) : alpha_(std::max(alpha, 1e-4f)) {}

  // Below this α the lobe is rendered as the smooth (delta) interface it converges to.
  static constexpr float kSmoothAlpha = 1e-3f;
  static bool effectively_smooth(float alpha) { return alpha < kSmoothAlpha; }
  float alpha() const { return alpha_; }

  // tan²θ from the components, not from 1 − cos²θ, which cancels to nothing near the normal
  // where the narrowest lobes live.
  static float tan2_theta(const Vec3f& w) { return (w.x * w.x + w.y * w.y) / (w.z * w.z); }

  // D(m) = 1 / (π α² cos⁴θ_m (1 + tan²θ_m / α²)²)
  float D(const Vec3f& m) const {
    const float cos2 = m.z * m.z;
    if (cos2 <= 0) return 0;
    const float tan2 = tan2_theta(m);
    const float e = 1 + tan2 / (alpha_ * alpha_);
    return 1 / (kPi * alpha_ * alpha_ * cos2 * cos2 * e * e);
  }

  // Λ(w) = (√(1 + α² tan²θ) − 1) / 2
  float lambda(const Vec3f& w) const {
    if (w.z == 0) return kInfinity;
    const float tan2 = tan2_theta(w);
    return (std::sqrt(1 + alpha_ * alpha_ * tan2) - 1) / 2;
  }
  float G1(const Vec3f& w) const { return 1 / (1 + lambda(w)); }
  float G(const Vec3f& wo, const Vec3f& wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }

  // Density of visible normals seen from w: D_w(m) = G1(w) |w·m| D(m) / |cos θ_w| (for w below
  // the surface, the normals visible from −w).
  float D_visible(const Vec3f& w, const Vec3f& m) const {
    const float cos_w = std::abs(w.z);
    return cos_w > 0 ? G1(w) * abs_dot(w, m) * D(m) / cos_w : 0.f;
  }

  // A visible normal from w (taken in the upper hemisphere), distributed as D_visible(w, ·).
  Vec3f sample_visible_normal(Vec3f w, Vec2f u) const {
    if (w.z < 0) w = -w;
    const Vec3f wh = normalize(Vec3f(alpha_ * w.x, alpha_ * w.y, w.z));  // stretch to the hemisphere configuration
    const Vec3f t1 = wh.z < 0.99999f ? normalize(cross(Vec3f(0, 0, 1), wh)) : Vec3f(1, 0, 0);
    const Vec3f t2 = cross(wh, t1);
    Vec2f p = sample_uniform_disk_concentric(u);  // projected area of the visible hemisphere:
    const float h = std::sqrt(1 - p.x * p.x);     // a disk warped by the view's foreshortening
    p.y = lerp((1 + wh.z) / 2, h, p.y);
    const float pz = std::sqrt(std::max(0.f, 1 - p.x * p.x - p.y * p.y));
    const Vec3f nh = t1 * p.x + t2 * p.y + wh * pz;
    return normalize(Vec3f(alpha_ * nh.x, alpha_ * nh.y, std::max(1e-6f, nh.z)));  // unstretch
  }

 private:
  float alpha_;
};

}  // namespace prism
