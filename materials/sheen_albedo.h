#pragma once
// Directional albedo E(μ) = ∫ f_sheen(wo, wi) |cos θ_i| dω_i of the white Charlie sheen lobe
// (sheen_bsdf.h), which scales the light left to the layers beneath it (Estevez & Kulla 2017 §3;
// KHR_materials_sheen's albedo scaling). Computed by the project at first use: a 32 × 32 table
// over √μ and √α, each entry a quadrature over the hemisphere of wi; a roughness row is computed
// the first time a material needs it (tens of milliseconds).
// The fitted Charlie lobe reflects more than it receives at grazing angles and low roughness (up
// to 1.03 at α ≈ 0.01): scale(α) = 1 / max(1, max_μ E) brings it back to at most 1, a constant
// per roughness, so the lobe stays reciprocal. E is that of the scaled lobe.

#include <array>
#include <mutex>

namespace prism {

class SheenAlbedo {
 public:
  static const SheenAlbedo& table();  // computed once, thread-safe
  float E(float mu, float alpha) const;
  float scale(float alpha) const;

 private:
  SheenAlbedo() = default;
  static constexpr int kMu = 32, kAlpha = 32;
  const float* row(int a) const;  // computes it on first use
  mutable std::array<float, kMu * kAlpha> e_{};
  mutable std::array<float, kAlpha> scale_{};
  mutable std::array<std::once_flag, kAlpha> ready_;
};

}  // namespace prism
