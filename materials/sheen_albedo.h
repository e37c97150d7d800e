#pragma once
// Directional albedo E(μ) = ∫ f_sheen(wo, wi) |cos θ_i| dω_i of the white Charlie sheen lobe
// (sheen_bsdf.h), which scales the light left to the layers beneath it (Estevez & Kulla 2017 §3;
// KHR_materials_sheen's albedo scaling). Computed by the project at first use: a 32 × 32 table
// over √μ and the roughness α, each entry a midpoint quadrature over the hemisphere of wi.

#include <array>
#include <mutex>

namespace prism {

class SheenAlbedo {
 public:
  static const SheenAlbedo& table();  // computed once, thread-safe
  float E(float mu, float alpha) const;

 private:
  SheenAlbedo();
  static constexpr int kMu = 32, kAlpha = 32;
  std::array<float, kMu * kAlpha> e_;
};

}  // namespace prism
