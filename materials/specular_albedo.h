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
// compensation divides by (Turquin 2019; see conductor_bsdf.h, dielectric_bsdf.h). Beside them, the
// probability that sampling a visible normal gives a direction on the side it meant to:
//   valid(μ, α, η)     of the lossless interface (reflection chosen with probability F, else refraction);
//   white_valid(μ, α)  of the reflection alone (and of a thin wall, whose far side mirrors it);
// a compensated dielectric samples again where a sample fails, and its pdf needs them.
// Tabulated over √μ, ∛α ∈ [0, 1] and x = (η − 1)/(η + 1) ∈ [−1/2, 1/2], axes on which E varies
// smoothly enough for linear interpolation; the tables are computed at build time
// (materials/albedo_tables.h), so a lookup only interpolates.

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "core/base/math.h"
#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

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
  static Direction direction(float mu, const Roughness& r) {
    if (smooth(r)) return {mu, true, 0, 0, 0, 0};
    const albedo_tables::Point p = point(mu, r);
    return {mu, false, p.a, p.m, p.ta, p.tm};
  }
  // Where an index η falls on the tables' η axis: between the nodes h and h + 1, at t from h.
  struct Index {
    int h;
    float t;
  };
  static Index index(float eta) {
    const albedo_tables::Lerp h = albedo_tables::locate_eta(eta);
    return {h.i, h.t};
  }
  // Each lane's index placed on the η axis once, when a lobe is built (the lanes' reflectance
  // coupling, pbr_bsdf.h), with the nodes the lanes span, first … last; kept as arrays over the
  // lanes, so that a loop over them runs on all of them at once (SIMD).
  template <int N>
  struct Lanes {
    std::array<float, N> eta, t;
    std::array<int, N> h;
    int first, last;

    explicit Lanes(const std::array<float, N>& etas) : eta(etas) {
      for (int i = 0; i < N; ++i) {
        const Index x = index(eta[i]);
        h[i] = x.h, t[i] = x.t;
      }
      first = h[0], last = h[0];
      for (int i = 1; i < N; ++i) first = std::min(first, h[i]), last = std::max(last, h[i]);  // a reduction (SIMD)
      ++last;
    }
    // Each lane's value of a quantity known at the nodes first … last (value[k − first]),
    // interpolated to its index, v_λ = (1 − t_λ) v_h + t_λ v_{h+1}.
    std::array<float, N> interpolate(std::span<const float> value) const {
      std::array<float, N> v;
      for (int i = 0; i < N; ++i) v[i] = (1 - t[i]) * value[h[i] - first] + t[i] * value[h[i] + 1 - first];
      return v;
    }
  };

  static const SpecularAlbedo& table();
  // E at one μ for each lane's index, and the white lobe's: for a lobe of one α that looks them up
  // at several μ (the lanes' diffuse coupling, pbr_bsdf.h). Read from the α's slice of the tables
  // (alpha_slice), at each η node the lanes span, then every lane interpolates its own. A smooth
  // lobe's E is the exact Fresnel, and its white albedo 1.
  template <int N>
  struct AtLanes {
    std::array<float, N> e;
    float white;
  };
  template <int N>
  AtLanes<N> at_lanes(float mu, const Roughness& r, const Lanes<N>& lanes, bool compensated) const {
    AtLanes<N> x;
    if (smooth(r)) {
      for (int i = 0; i < N; ++i) x.e[i] = fresnel_dielectric(mu, lanes.eta[i]);
      x.white = 1;
      return x;
    }
    const AlphaSlice& slice = alpha_slice(r.alpha, compensated);
    const albedo_tables::Lerp m = albedo_tables::mu_node(mu);
    // Every η node at once along μ (two rows of contiguous nodes: vector code), then the lanes'.
    const AlphaSlice::Row &below = slice.e[m.i], &above = slice.e[m.i + 1];
    AlphaSlice::Row at_nodes;
    for (int h = 0; h < AlphaSlice::kNodes; ++h) at_nodes[h] = (1 - m.t) * below[h] + m.t * above[h];
    x.e = lanes.interpolate(std::span<const float>(at_nodes).subspan(lanes.first));
    x.white = lerp(m.t, slice.white[m.i], slice.white[m.i + 1]);
    return x;
  }
  // E along the tables' μ nodes for one α and η, and its E_avg: found once by a lobe of one index
  // that looks up E at several μ per shading point (the diffuse coupling: μ_o, then each μ_i), so
  // that each look-up is one interpolation along μ. A smooth lobe's E is the exact Fresnel.
  struct Curve {
    std::array<float, albedo_tables::kMu> e;
    float average, eta;
    bool smooth;
  };
  Curve curve(const Roughness& r, float eta, bool compensated) const;
  static float E(const Curve& c, float mu) {
    if (c.smooth) return fresnel_dielectric(mu, c.eta);
    const albedo_tables::Lerp m = albedo_tables::mu_node(mu);
    return lerp(m.t, c.e[m.i], c.e[m.i + 1]);
  }
  // The averages for each lane's index, as the lanes' E above (from the same slice).
  template <int N>
  std::array<float, N> average(const Roughness& r, const Lanes<N>& lanes, bool compensated) const {
    return lanes.interpolate(std::span<const float>(alpha_slice(r.alpha, compensated).average).subspan(lanes.first));
  }
  float interface(float mu, const Roughness& r, float eta) const;
  // interface() at one direction for each lane's index, as the lanes' E above.
  template <int N>
  std::array<float, N> interface(const Direction& d, const Lanes<N>& lanes) const {
    if (d.smooth) {
      std::array<float, N> one;
      one.fill(1.f);
      return one;
    }
    std::array<float, albedo_tables::kEta> at_nodes;
    interface(d, lanes.first, lanes.last, at_nodes);
    return lanes.interpolate(at_nodes);
  }
  float white(float mu, const Roughness& r) const;
  float valid(float mu, const Roughness& r, float eta) const;
  float white_valid(float mu, const Roughness& r) const;
  float white_average(const Roughness& r) const;
  float white_average(float alpha) const { return white_average(roughness(alpha)); }

 private:
  // E at every (μ, η) node for one α (the tables' α axis interpolated away), E_avg at every η
  // node, and the white lobe's E along μ: made once per α and thread (per_thread_cached_ref), for
  // at_lanes, whose lanes span several η nodes at each of a BSDF's
  // few evaluations. A row holds one μ node's E at every η node, padded to a whole number of
  // vectors (8 floats).
  struct AlphaSlice {
    static constexpr int kNodes = (albedo_tables::kEta + 7) / 8 * 8;
    using Row = std::array<float, kNodes>;
    std::array<Row, albedo_tables::kMu> e;
    Row average;
    std::array<float, albedo_tables::kMu> white;
  };
  // The slice of α, valid until the next call (in this thread).
  static const AlphaSlice& alpha_slice(float alpha, bool compensated);
  static AlphaSlice slice_of(float alpha, bool compensated);
  // A lobe smooth enough to be a mirror: its E is the exact Fresnel, not the tables'.
  static bool smooth(const Roughness& r) { return TrowbridgeReitz::effectively_smooth(r.alpha); }
  static albedo_tables::Point point(const Direction& d) { return {d.a, d.m, d.ta, d.tm}; }
  static albedo_tables::Point point(float mu, const Roughness& r) { return albedo_tables::point(mu, {r.a, r.ta}); }
  // The reflection grid of the η node h, compensated (divided by reflection + transmission) or not.
  static const albedo_tables::Grid& reflection(int h, bool compensated) {
    return compensated ? albedo_tables::specular[h].r_compensated : albedo_tables::specular[h].r;
  }
  void interface(const Direction& d, int first, int last, std::span<float> out) const;
};

}  // namespace prism
