#pragma once
// Vertex connection and merging (Georgiev et al. 2012, "Light Transport Simulation with Vertex
// Connection and Merging"): bidirectional path tracing (bdpt.h) plus, at every non-specular
// camera vertex, a density estimate over the photons (light-subpath vertices) of all light paths
// of the iteration within radius r, MIS-combined with the connections (eqs. 22, 38–42).
//
// An iteration is one sample of every pixel: its W·H light paths are traced first and their
// photons stored in a PhotonGrid; then each pixel's camera path merges with them (and connects
// to its own light path, which it traces again from the same random numbers). The radius shrinks
// as r_i = r_0 · i^((α−1)/2) with α = 0.75 (Knaus & Zwicker 2011), so the estimate is
// consistent: its bias vanishes as the iterations grow while the variance still falls.
//
// Wavelengths: all paths of an iteration carry the same wavelengths (drawn per iteration from the
// sampler, stratified over iterations), so a photon and a camera vertex always agree lane by
// lane. A photon after a dispersive interface on its light path carries only the hero wavelength;
// merged with a camera path that kept all lanes, it counts in the hero lane with weight N
// (its lane's pdf is p(λ₀)/N), so every lane's estimate stays consistent.

#include <vector>

#include "core/render/path_vertex.h"
#include "core/render/photon_grid.h"

namespace prism {

// A light-subpath vertex as merging needs it.
template <int N>
struct Photon {
  SampledSpectrum<N> beta;  // the light subpath's throughput on arrival
  Vec3f wi;                 // world, unit: towards where the light came from
  float vcm, vm;            // the light subpath's MIS sums (path_vertex.h)
  int length;               // segments from the light
  bool hero_only;           // its light path met a dispersive interface before it
};

template <int N>
class VcmIteration {
 public:
  // r_0 · i^((α − 1)/2) for iteration i ≥ 1.
  static float radius(float initial, int iteration) {
    return initial * std::pow(float(std::max(iteration, 1)), (kAlpha - 1.f) * 0.5f);
  }

  VcmIteration(std::vector<Vec3f> positions, std::vector<Photon<N>> photons, float radius, float light_paths)
      : photons_(std::move(photons)),
        grid_(std::move(positions), radius),
        factors_(MisFactors::vcm(radius, light_paths)),
        normalization_(1.f / (kPi * radius * radius * light_paths)) {}

  const MisFactors& factors() const { return factors_; }

  // Σ over the photons within r of camera vertex si (depth bounces from the camera) of
  // w · f · β_photon / (π r² · light paths), with the shading-normal factor |ns·wi| / |ng·wi|
  // that turns the photons' area density into radiance; full-lane and hero-only photons apart.
  template <typename Bsdf>
  void merge(const SurfaceInteraction& si, const Frame& frame, const Bsdf& bsdf, const Vec3f& wo, const MisSums& m,
             int depth, int max_depth, SampledSpectrum<N>& all, SampledSpectrum<N>& hero) const {
    grid_.for_each_near(si.p, [&](uint32_t i) {
      const Photon<N>& ph = photons_[i];
      if (ph.length + depth + 1 > max_depth + 1) return;
      const Vec3f wi = frame.to_local(ph.wi);
      if ((dot(ph.wi, si.n) * dot(si.wo, si.n) <= 0) != (wi.z * wo.z < 0)) return;  // direct_light.h wrong_side
      const float cos_g = abs_dot(si.n, ph.wi);
      if (!(cos_g > 0.f)) return;
      const BsdfEval<N> e = bsdf_eval(bsdf, wo, wi);
      const SampledSpectrum<N> f = e.f * (abs_cos_theta(wi) / cos_g);
      if (f.is_zero()) return;
      const float w_light = ph.vcm * factors_.vc + ph.vm * mis(e.pdf);
      const float w_camera = m.vcm * factors_.vc + m.vm * mis(bsdf_pdf(bsdf, wi, wo));
      (ph.hero_only ? hero : all) += f * ph.beta * (normalization_ / (w_light + 1.f + w_camera));
    });
  }

 private:
  static constexpr float kAlpha = 0.75f;

  std::vector<Photon<N>> photons_;
  PhotonGrid grid_;
  MisFactors factors_;
  float normalization_;
};

}  // namespace prism
