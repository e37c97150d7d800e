#pragma once
// Directional albedo E(μ) = ∫ f_r(wo, wi) |cos θ_i| dω_i of a dielectric's GGX reflection lobe
// (exact Fresnel, relative index η ≥ 1), and its cosine-weighted mean E_avg = 2∫ E(μ) μ dμ.
// They make a diffuse base under the specular layer energy-consistent and reciprocal (Kelemen &
// Szirmay-Kalos 2001; Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks"):
//   f_diffuse = ρ/π · (1 − E(μ_o)) (1 − E(μ_i)) / (1 − E_avg).
// Tabulated over √μ, the roughness √α ∈ [0, 1] and x = (η − 1)/(η + 1) ∈ [0, 1/2] (η up to 3),
// axes on which E varies smoothly enough for linear interpolation; each η slice is computed the
// first time a material needs it (tens of milliseconds), so a scene pays only for its indices.

#include <array>
#include <mutex>
#include <vector>

namespace prism {

class SpecularAlbedo {
 public:
  static const SpecularAlbedo& table();  // computed once, thread-safe
  float E(float mu, float alpha, float eta) const;
  float average(float alpha, float eta) const;

 private:
  SpecularAlbedo();
  static constexpr int kMu = 32, kAlpha = 32, kEta = 16;
  void compute_slice(int h) const;
  float slice_E(int h, float mu, float alpha) const;  // bilinear in (√α, √μ) within slice h
  const float* slice(int h) const;                    // computes it on first use

  mutable std::vector<float> e_, e_avg_;  // [eta][alpha][mu], [eta][alpha]
  mutable std::array<std::once_flag, kEta> ready_;
};

}  // namespace prism
