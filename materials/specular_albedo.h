#pragma once
// Directional albedos of the GGX lobes, E(μ) = ∫ f(wo, wi) |cos θ_i| dω_i with cos θ_o = μ
// (transmission counted as energy), computed by the project and tabulated:
//   white(μ, α)        reflection with F = 1: what a lossless rough conductor keeps of the light
//                      after one scattering (its E_avg is 0.41 at α = 1: the rest is multiple scattering);
//   interface(μ, α, η) reflection + transmission of a lossless dielectric interface, η ∈ [1/3, 3]
//                      (both sides of an interface of index up to 3);
//   E(μ, α, η)         the reflection alone with the exact Fresnel (η ≥ 1), optionally
//                      compensated (divided by interface()), and its cosine-weighted mean
//                      E_avg = 2∫ E(μ) μ dμ: they couple a diffuse base under the specular layer
//                      (Kelemen & Szirmay-Kalos 2001; Kulla & Conty 2017, "Revisiting Physically
//                      Based Shading at Imageworks"): f_diffuse = ρ/π · (1 − E(μ_o))(1 − E(μ_i))/(1 − E_avg).
// white() and interface() are the single-scattering albedos that the multiple-scattering
// compensation divides by (Turquin 2019; see conductor_bsdf.h, dielectric_bsdf.h).
// Tabulated over √μ, ∛α ∈ [0, 1] and x = (η − 1)/(η + 1) ∈ [−1/2, 1/2], axes on
// which E varies smoothly enough for linear interpolation; each table (the white one, or one η
// slice) is computed by stratified sampling the first time a material needs it (tens of
// milliseconds), deterministically, so a scene pays only for the indices it uses.

#include <array>
#include <mutex>
#include <vector>

namespace prism {

class SpecularAlbedo {
 public:
  static const SpecularAlbedo& table();  // computed once, thread-safe
  float E(float mu, float alpha, float eta, bool compensated) const;
  float average(float alpha, float eta, bool compensated) const;
  float interface(float mu, float alpha, float eta) const;
  float white(float mu, float alpha) const;
  float white_average(float alpha) const;

  static constexpr int kMu = 32, kAlpha = 32, kEta = 31;

 private:
  SpecularAlbedo();
  // Where (μ, α) falls on the grids' axes (∛α, √μ): cell and weights, shared by the grids read.
  struct Point {
    int a, m;
    float ta, tm;
  };
  static Point point(float mu, float alpha);
  // One table of E over (α, μ) and its averages over μ, per α.
  struct Grid {
    std::vector<float> e = std::vector<float>(size_t(kAlpha) * kMu), avg = std::vector<float>(kAlpha);
    float at(const Point& p) const;    // bilinear
    float average(float alpha) const;  // linear in ∛α
  };
  // An η slice: reflection, reflection compensated, reflection + transmission.
  struct Slice {
    Grid r, r_compensated, rt;
  };
  const Slice& slice(int h) const;  // computes it on first use
  const Grid& white_grid() const;

  mutable std::array<Slice, kEta> slices_;
  mutable std::array<std::once_flag, kEta> slice_ready_;
  mutable Grid white_;
  mutable std::once_flag white_ready_;
};

}  // namespace prism
