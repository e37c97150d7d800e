#pragma once
// Directional albedo E(μ) = ∫ f_sheen(wo, wi) |cos θ_i| dω_i of the white Charlie sheen lobe
// (sheen_bsdf.h), which scales the light left to the layers beneath it (Estevez & Kulla 2017 §3;
// KHR_materials_sheen's albedo scaling). A 32 × 32 table over √μ and √α, each entry a quadrature
// over the hemisphere of wi, computed at build time (materials/albedo_tables.h).
// The fitted Charlie lobe reflects more than it receives at grazing angles and low roughness (up
// to 1.03 at α ≈ 0.01): scale(α) = 1 / max(1, max_μ E) brings it back to at most 1, a constant
// per roughness, so the lobe stays reciprocal. E is that of the scaled lobe.

namespace prism {

class SheenAlbedo {
 public:
  // Where a roughness α falls on the table's α axis (a square root): found once by a layer that
  // looks up E at several μ.
  struct Roughness {
    int j;
    float t;
  };
  static Roughness roughness(float alpha);

  static const SheenAlbedo& table();
  float E(float mu, const Roughness& r) const;
  float scale(float alpha) const;
};

}  // namespace prism
