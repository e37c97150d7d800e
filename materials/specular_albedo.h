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
// Tabulated over √μ, ∛α ∈ [0, 1] and x = (η − 1)/(η + 1) ∈ [−1/2, 1/2], axes on which E varies
// smoothly enough for linear interpolation; the tables are computed at build time
// (materials/albedo_tables.h), so a lookup only interpolates.

#include <span>

namespace prism {

class SpecularAlbedo {
 public:
  // Where a roughness α falls on the tables' α axis (a cube root): found once by a lobe that looks
  // up E at several μ per shading point.
  struct Roughness {
    float alpha;
    int a;
    float ta;
  };
  static Roughness roughness(float alpha);
  // Where a direction μ falls on the tables' μ axis (a square root), for that roughness: found
  // once by a lobe that looks up E at one μ for several indices (one per lane).
  struct Direction {
    float mu;
    bool smooth;
    int a, m;
    float ta, tm;
  };
  static Direction direction(float mu, const Roughness& r);
  // Where an index η falls on the tables' η axis: found once per lane by a lobe that looks up E
  // for each lane's own index at several μ (the lanes' reflectance coupling, pbr_bsdf.h).
  struct Index {
    float eta;
    int h;
    float th;
  };
  static void index(std::span<const float> eta, std::span<Index> out);

  static const SpecularAlbedo& table();
  // E at one direction for several indices (one per lane) at once: the tables of the η nodes
  // the lanes fall between are each read once, then every lane interpolates its own.
  void E(const Direction& d, std::span<const Index> eta, bool compensated, std::span<float> out) const;
  float E(float mu, const Roughness& r, float eta, bool compensated) const;
  float average(const Roughness& r, float eta, bool compensated) const;
  // The averages for several indices (one per lane) at once, as E above.
  void average(const Roughness& r, std::span<const Index> eta, bool compensated, std::span<float> out) const;
  float interface(float mu, const Roughness& r, float eta) const;
  float white(const Direction& d) const;
  float white(float mu, const Roughness& r) const;
  float white_average(const Roughness& r) const;
  float white_average(float alpha) const { return white_average(roughness(alpha)); }
};

}  // namespace prism
