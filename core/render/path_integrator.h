#pragma once
// Unidirectional path tracing over a path's sampled wavelengths, with next-event estimation
// and multiple importance sampling of light and BSDF samples (power heuristic; Veach 1997,
// ch. 9), and Russian roulette on the path throughput (Arvo & Kirk 1990).

#include "base/sampler.h"
#include "render/ray_counters.h"
#include "render/world.h"

namespace prism {

struct PathOptions {
  int max_depth = 16;            // bounces; 0 shows only what the camera sees emitting
  bool russian_roulette = true;  // off: every path runs to max_depth (for exact checks)
  bool next_event = true;        // off: BSDF sampling only (lights found by chance; point lights never)
};

// Machinery a scene may not need, compiled in or out per render (the renderer picks from the
// scene's features): Media, the stack of closed dielectrics a path is inside with Beer–Lambert
// absorption; Dispersion, the check for λ-dependent index ratios that keeps only the hero
// wavelength. A scene without them runs code that does not contain them.
struct PathFeatures {
  bool media = true, dispersion = true;
};

// Radiance arriving along `ray` at the path's wavelengths: what a path that met a dispersive
// interface found after it is carried by the hero wavelength alone (lane 0, N times over), what
// it found before by every lane.
template <int N, bool Media, bool Dispersion>
SampledSpectrum<N> path_radiance(const World& world, Ray ray, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 const PathOptions& options, RayCounters& counters);

}  // namespace prism
