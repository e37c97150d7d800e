#pragma once
// The Trowbridge–Reitz (GGX) microfacet distribution (Trowbridge & Reitz 1975; Walter et al.
// 2007), anisotropic with roughness α_x along the local x axis (the tangent frame's direction of
// anisotropy) and α_y along y (glTF: α = roughness²; isotropic when α_x = α_y, through the same
// code, so that an anisotropy of 0 is the isotropic lobe bit for bit), with the height-correlated
// Smith masking-shadowing term (Heitz 2014, "Understanding the Masking-Shadowing Function") and
// sampling of the visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4)). Directions in the local frame, z = macro-surface normal.

#include <cmath>

#include "core/base/vec.h"
#include "core/base/warp.h"

namespace prism {

class TrowbridgeReitz {
 public:
  explicit TrowbridgeReitz(float alpha) : TrowbridgeReitz(alpha, alpha) {}
  TrowbridgeReitz(float alpha_x, float alpha_y) : ax_(std::max(alpha_x, 1e-4f)), ay_(std::max(alpha_y, 1e-4f)) {}

  // Below this α the lobe is rendered as the smooth (delta) interface it converges to.
  static constexpr float kSmoothAlpha = 1e-3f;
  static bool effectively_smooth(float alpha) { return alpha < kSmoothAlpha; }
  bool effectively_smooth() const { return effectively_smooth(std::max(ax_, ay_)); }
  bool isotropic() const { return ax_ == ay_; }
  // The isotropic roughness of equal area, √(α_x α_y), for tables over isotropic lobes.
  float alpha() const { return ax_ == ay_ ? ax_ : std::sqrt(ax_ * ay_); }

  // D(m) = 1 / (π α_x α_y cos⁴θ_m (1 + tan²θ_m (cos²φ_m/α_x² + sin²φ_m/α_y²))²)
  //      = 1 / (π α_x α_y (m_z² + m_x²/α_x² + m_y²/α_y²)²)  for a unit m,
  // the tangent term from the components, not from 1 − cos²θ, which cancels to nothing near the
  // normal where the narrowest lobes live.
  float D(const Vec3f& m) const {
    const float cos2 = m.z * m.z;
    if (cos2 <= 0) return 0;
    const float s = cos2 + sqr(m.x / ax_) + sqr(m.y / ay_);
    return 1 / (kPi * ax_ * ay_ * s * s);
  }

  // Λ(w) = (√(1 + α²(φ) tan²θ) − 1) / 2,  α²(φ) tan²θ = (α_x² x² + α_y² y²) / z²
  float lambda(const Vec3f& w) const {
    if (w.z == 0) return kInfinity;
    return (std::sqrt(1 + (sqr(ax_ * w.x) + sqr(ay_ * w.y)) / (w.z * w.z)) - 1) / 2;
  }
  float G1(const Vec3f& w) const { return 1 / (1 + lambda(w)); }
  float G(const Vec3f& wo, const Vec3f& wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }

  // What a lobe's f and pdf share at one microfacet normal m (Tungsten's eval: one pass for both):
  // D(m), G(wo, wi) and G1(wo), Λ(wo) found once for the two.
  struct Facet {
    float D, G, G1_o;
  };
  // (Always inlined: called out of line, its result came back through memory, read at once.)
  [[gnu::always_inline]] Facet facet(const Vec3f& wo, const Vec3f& wi, const Vec3f& m) const {
    const float lambda_o = lambda(wo);
    return {D(m), 1 / (1 + lambda_o + lambda(wi)), 1 / (1 + lambda_o)};
  }
  // Density of visible normals seen from wo: D_wo(m) = G1(wo) |wo·m| D(m) / |cos θ_o| (for wo below
  // the surface, the normals visible from −wo), from the facet's terms (G unused).
  static float D_visible(const Vec3f& wo, const Vec3f& m, const Facet& t) {
    const float cos_w = std::abs(wo.z);
    return cos_w > 0 ? t.G1_o * abs_dot(wo, m) * t.D / cos_w : 0.f;
  }
  // The pdf of wo reflected about a visible normal m: D_wo(m) / (4 |wo·m|) = G1(wo) D(m) / (4 |cos θ_o|),
  // the reflection's Jacobian 1 / (4 |wo·m|) cancelling D_wo's |wo·m|.
  static float reflected_pdf(const Vec3f& wo, const Facet& t) {
    const float cos_w = std::abs(wo.z);
    return cos_w > 0 ? t.G1_o * t.D / (4 * cos_w) : 0.f;
  }
  float reflected_pdf(const Vec3f& wo, const Vec3f& m) const { return reflected_pdf(wo, Facet{D(m), 0, G1(wo)}); }

  // A visible normal from w (taken in the upper hemisphere), distributed as D_w(m) (D_visible).
  Vec3f sample_visible_normal(Vec3f w, Vec2f u) const {
    if (w.z < 0) w = -w;
    const Vec3f wh = normalize(Vec3f(ax_ * w.x, ay_ * w.y, w.z));  // stretch to the hemisphere configuration
    const Vec3f t1 = wh.z < 0.99999f ? normalize(cross(Vec3f(0, 0, 1), wh)) : Vec3f(1, 0, 0);
    const Vec3f t2 = cross(wh, t1);
    Vec2f p = sample_uniform_disk_concentric(u);  // projected area of the visible hemisphere:
    const float h = std::sqrt(1 - p.x * p.x);     // a disk warped by the view's foreshortening
    p.y = lerp((1 + wh.z) / 2, h, p.y);
    const float pz = std::sqrt(std::max(0.f, 1 - p.x * p.x - p.y * p.y));
    const Vec3f nh = t1 * p.x + t2 * p.y + wh * pz;
    return normalize(Vec3f(ax_ * nh.x, ay_ * nh.y, std::max(1e-6f, nh.z)));  // unstretch
  }

 private:
  float ax_, ay_;
};

}  // namespace prism
