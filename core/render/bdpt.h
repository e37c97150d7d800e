#pragma once
// Bidirectional path tracing (Veach 1997, ch. 10) over a camera sample's wavelengths: a light
// subpath and a camera subpath, every connection strategy (s = 0: the camera path finds a light;
// s = 1: light sampling; s ≥ 2, t ≥ 2: vertex connection; t = 1: light tracing onto the film,
// splatted), combined by the power heuristic with the recursive weights of Georgiev et al. 2012
// (path_vertex.h).
//
// Wavelengths: both subpaths carry the camera sample's wavelengths, and each terminates its own
// secondary wavelengths at a dispersive interface (the decision is made before any λ-dependent
// direction is taken). A contribution counts for all lanes when neither of the subpath prefixes
// it is made of met such an interface, and for the hero lane alone (N times over) otherwise, so
// that a light path through the prism does not turn the camera path's own estimates into the
// hero wavelength's too; each strategy's estimate stays unbiased lane by lane.

#include "core/base/sampler.h"
#include "core/render/camera.h"
#include "core/render/light_emission.h"
#include "core/render/path_integrator.h"
#include "core/render/ray_counters.h"
#include "core/render/splat_buffer.h"
#include "core/render/vcm.h"
#include "core/render/world.h"

namespace prism {

// What the bidirectional estimator needs besides a path tracer's arguments.
struct BdptScene {
  const World& world;
  const Camera& camera;
  SceneDisk disk;      // where infinite lights emit from
  float light_paths;   // light paths per sample of every pixel: the pixel count
  bool media;          // track closed dielectrics (absorption, nested indices)
  bool light_tracing;  // the t = 1 strategy alone (and what the camera sees directly), unweighted

  BdptScene(const World& world, const Camera& camera, bool media, bool light_tracing = false);
};

// The camera sample's estimate along `ray` (its own pixel's share), and its light path's splats;
// with `vcm`, merging with the iteration's photons too (vcm.h). Counts dropped (NaN, Inf)
// splats in `invalid`.
template <int N>
SampledSpectrum<N> bdpt_radiance(const BdptScene& scene, Ray ray, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 const PathOptions& options, const VcmIteration<N>* vcm, SplatBuffer& splats,
                                 RayCounters& counters, uint64_t& invalid);

// The photons of the light path that bdpt_radiance traces for the same sampler state (the
// pixel sample's), for an iteration of VCM with these factors: appended to positions, photons.
template <int N>
void trace_photons(const BdptScene& scene, SampledWavelengths<N> lambda, Sampler& sampler, const PathOptions& options,
                   const MisFactors& factors, RayCounters& counters, std::vector<Vec3f>& positions,
                   std::vector<Photon<N>>& photons);

}  // namespace prism
