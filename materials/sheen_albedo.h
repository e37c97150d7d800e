#pragma once
// Directional albedo E(μ) = ∫ f_sheen(wo, wi) |cos θ_i| dω_i of the white Charlie sheen lobe
// (sheen_bsdf.h), which scales the light left to the layers beneath it (Estevez & Kulla 2017 §3;
// KHR_materials_sheen's albedo scaling). A 32 × 32 table over √μ and √α, each entry a quadrature
// over the hemisphere of wi, computed at build time (materials/albedo_tables.h).
// The fitted Charlie lobe reflects more than it receives at grazing angles and low roughness (up
// to 1.03 at α ≈ 0.01): scale(α) = 1 / max(1, max_μ E) brings it back to at most 1, a constant
// per roughness, so the lobe stays reciprocal. E is that of the scaled lobe.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/base/math.h"
#include "materials/albedo_tables.h"

namespace prism {

class SheenAlbedo {
 public:
  // E along the table's μ nodes for one α (its α axis interpolated away): found once per α by a
  // layer that looks up E at several μ, so that each look-up is one interpolation along μ.
  struct Curve {
    std::array<float, albedo_tables::kSheenMu> e;
  };
  static Curve curve(float alpha);
  static float E(const Curve& c, float mu) {
    const albedo_tables::Lerp m = albedo_tables::mu_node(mu, albedo_tables::kSheenMu);
    return lerp(m.t, c.e[m.i], c.e[m.i + 1]);
  }
  static float scale(float alpha);
};

}  // namespace prism
