#pragma once
// Unidirectional path tracing over a path's sampled wavelengths, with next-event estimation
// and multiple importance sampling of light and BSDF samples (balance heuristic; Veach 1997,
// ch. 9), and Russian roulette on the path throughput (Arvo & Kirk 1990).

#include "core/base/sampler.h"
#include "core/render/ray_counters.h"
#include "core/render/world.h"

namespace prism {

// Scattering events in media a path may take: a random walk through a dense medium takes hundreds
// or thousands, so they do not count as bounces (PathOptions::max_depth), and this bound, beyond
// the walks that carry light, only ends a walk in an endless non-absorbing medium.
inline constexpr int kMaxMediumEvents = 100000;

struct PathOptions {
  int max_depth = 16;            // bounces at surfaces (kMaxMediumEvents in media); 0 shows only emitters
  bool russian_roulette = true;  // off: every path runs to max_depth (for exact checks)
  bool next_event = true;        // off: BSDF sampling only (lights found by chance; point lights never)
};

// Machinery a scene may not need, compiled in or out per render (the renderer picks from the
// scene's features): Media, the stack of closed dielectrics a path is inside and the media that fill
// them and the scene (absorption, scattering; medium_sampling.h); Dispersion, the check for λ-dependent index ratios,
// where the lanes are weighed by spectral MIS (materials/dispersive_bsdf.h). A scene without them runs code that does
// not contain them.
struct PathFeatures {
  bool media = true, dispersion = true;
};

// Radiance arriving along `ray` at the path's wavelengths. Past a dispersive interface every lane
// keeps its own estimate f_k / ((1/N) Σ_j p_j), p_j the path's pdf with lane j as the hero
// (hero-wavelength spectral MIS, dispersive_bsdf.h); past a delta sample there (a smooth refraction
// or reflection), only the hero's (lane 0, N times over). `first`, when given, is what
// world.intersect(ray, true) returns, found already by the caller.
template <int N, bool Media, bool Dispersion>
SampledSpectrum<N> path_radiance(const World& world, Ray ray, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 const PathOptions& options, RayCounters& counters,
                                 const std::optional<SurfaceInteraction>* first = nullptr);

}  // namespace prism
