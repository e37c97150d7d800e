#pragma once
// The integrators: each registered once, as a row of the table in integrators.cpp, with its name,
// what it is, its radiance estimator and how the renderer runs it (which says what it supports).
// Adding an integrator is its estimator in a file of its own and one row of the table; the CLI's
// choices, `prism converge` and the EXR header read the table (as pbrt-v4's Integrator::Create
// does by name).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/base/sampler.h"
#include "core/render/bdpt.h"
#include "core/render/path_integrator.h"
#include "core/render/ray_counters.h"
#include "core/render/splat_buffer.h"
#include "core/render/vcm.h"
#include "core/render/world.h"
#include "core/scene/scene_features.h"

namespace prism {

// The order is that of the table (tests name integrators by index).
enum class IntegratorKind { path, whitted, bdpt, vcm, light };

// What an estimate along a camera ray may use besides the ray: the world and the path options, and
// for the integrators that trace light paths, their scene of lights, the thread's splat buffer,
// VCM's iteration of photons (else null), and the count of splats dropped as NaN or Inf.
template <int N>
struct EstimateContext {
  const World& world;
  const PathOptions& path;
  const BdptScene* bidirectional = nullptr;
  SplatBuffer* splats = nullptr;
  const VcmIteration<N>* vcm = nullptr;
  uint64_t* invalid_splats = nullptr;
};

// An integrator's estimate of the radiance arriving along a camera ray at the sample's wavelengths.
// `first`, given only to integrators that take it (Integrator::first_hit), is the ray's first hit,
// world.intersect(ray, true), found already by the renderer.
template <int N>
using RadianceFn = SampledSpectrum<N> (*)(const EstimateContext<N>& context, const Ray& ray,
                                          const SampledWavelengths<N>& lambda, Sampler& sampler, RayCounters& counters,
                                          const std::optional<SurfaceInteraction>* first);

// An integrator's estimator for 1, 4 and 8 wavelengths per path, compiled for the scene's features.
struct RadianceEstimators {
  RadianceFn<1> (*one)(const PathFeatures&);
  RadianceFn<4> (*four)(const PathFeatures&);
  RadianceFn<8> (*eight)(const PathFeatures&);

  template <int N>
  RadianceFn<N> make(const PathFeatures& features) const {
    if constexpr (N == 1) return one(features);
    if constexpr (N == 4) return four(features);
    if constexpr (N == 8) return eight(features);
  }
};

struct Integrator {
  IntegratorKind kind;
  std::string_view name;         // --integrator NAME, prism.integrator
  std::string_view description;  // one line, for --help
  RadianceEstimators radiance;
  // How the renderer runs it:
  bool light_paths;         // every camera sample also traces a light path, which splats onto any pixel: the
                            // whole frame at once, so no noise threshold, crop window or spectral bins, and no
                            // error-estimate replicates (a light path per sample index)
  bool light_tracing_only;  // of the light path's strategies, light tracing onto the film alone
  bool photon_iterations;   // an iteration per sample index traces every pixel's light path first and keeps
                            // its photons (VCM)
  bool first_hit;           // takes the camera ray's first hit from the renderer, so a constant sky seen at once
                            // is its exact colour (sky.h)
  bool check_only;          // a check of the others, not a way to render images: `prism converge` leaves it out
  bool scattering;          // renders media that scatter light (the others refuse such a scene)

  // Whether it renders per pixel (a noise threshold, crop windows and spectral bins need that).
  bool per_pixel() const { return !light_paths; }
};

// The table, in IntegratorKind order.
std::span<const Integrator> integrators();
const Integrator& integrator(IntegratorKind kind);
// The integrator of that name, if any.
const Integrator* find_integrator(std::string_view name);
// Every name, comma-separated (for messages).
std::string integrator_names();

// `--integrator auto`: the integrator a scene needs, with the reason, for a render that needs
// per-pixel estimates (a noise threshold or spectral bins) or not. Light through
// closed glass, water or gems from a light inside the scene makes caustics (specular–diffuse–
// specular paths) that only VCM's merging samples well; anything else the path tracer renders
// faster to equal error (the measurements `prism converge` makes, docs/performance.md).
struct IntegratorChoice {
  IntegratorKind kind;
  std::string reason;
};
IntegratorChoice choose_integrator(const SceneFeatures& features, bool per_pixel);

}  // namespace prism
