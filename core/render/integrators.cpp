#include "core/render/integrators.h"

#include <array>

#include "core/render/whitted_integrator.h"

namespace prism {

namespace {

// Each integrator's estimator in the RadianceFn form, and its choice per scene.

template <int N, bool Media, bool Dispersion>
SampledSpectrum<N> path_estimate(const EstimateContext<N>& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                                 Sampler& sampler, RayCounters& counters,
                                 const std::optional<SurfaceInteraction>* first) {
  return path_radiance<N, Media, Dispersion>(c.world, ray, lambda, sampler, c.path, counters, first);
}
// The path tracer compiled with the machinery the scene needs (PathFeatures).
template <int N>
RadianceFn<N> path_estimator(const PathFeatures& f) {
  if (f.media) return f.dispersion ? &path_estimate<N, true, true> : &path_estimate<N, true, false>;
  return f.dispersion ? &path_estimate<N, false, true> : &path_estimate<N, false, false>;
}

template <int N>
SampledSpectrum<N> whitted_estimate(const EstimateContext<N>& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                                    Sampler& sampler, RayCounters& counters, const std::optional<SurfaceInteraction>*) {
  return whitted_radiance<N>(c.world, ray, lambda, sampler, c.path, counters);
}
template <int N>
RadianceFn<N> whitted_estimator(const PathFeatures&) {
  return &whitted_estimate<N>;
}

// BDPT, VCM (with the iteration's photons) and light tracing alone (as the scene of lights says).
template <int N>
SampledSpectrum<N> bidirectional_estimate(const EstimateContext<N>& c, const Ray& ray,
                                          const SampledWavelengths<N>& lambda, Sampler& sampler, RayCounters& counters,
                                          const std::optional<SurfaceInteraction>*) {
  return bdpt_radiance<N>(*c.bidirectional, ray, lambda, sampler, c.path, c.vcm, *c.splats, counters,
                          *c.invalid_splats);
}
template <int N>
RadianceFn<N> bidirectional_estimator(const PathFeatures&) {
  return &bidirectional_estimate<N>;
}

constexpr RadianceEstimators kPath{&path_estimator<1>, &path_estimator<4>, &path_estimator<8>};
constexpr RadianceEstimators kWhitted{&whitted_estimator<1>, &whitted_estimator<4>, &whitted_estimator<8>};
constexpr RadianceEstimators kBidirectional{&bidirectional_estimator<1>, &bidirectional_estimator<4>,
                                            &bidirectional_estimator<8>};

//                kind                     name       description
//                radiance  light_paths  light_tracing_only  photon_iterations  first_hit  check_only  scattering
constexpr std::array kIntegrators{
    Integrator{IntegratorKind::path, "path", "unidirectional path tracing with next-event estimation and MIS", kPath,
               false, false, false, true, false, true},
    Integrator{IntegratorKind::whitted, "whitted",
               "recursive Fresnel splitting (Whitted 1980): no indirect diffuse light", kWhitted, false, false, false,
               false, false, false},
    Integrator{IntegratorKind::bdpt, "bdpt", "bidirectional path tracing", kBidirectional, true, false, false, false,
               false, false},
    Integrator{IntegratorKind::vcm, "vcm",
               "bidirectional path tracing with vertex merging (caustics, dispersion seen through glass)",
               kBidirectional, true, false, true, false, false, false},
    Integrator{IntegratorKind::light, "light", "light tracing alone (a check of the others)", kBidirectional, true,
               true, false, false, true, false},
};
static_assert(
    [] {
      for (size_t i = 0; i < kIntegrators.size(); ++i)
        if (size_t(kIntegrators[i].kind) != i) return false;
      return true;
    }(),
    "the table is in IntegratorKind order");

}  // namespace

std::span<const Integrator> integrators() { return kIntegrators; }

const Integrator& integrator(IntegratorKind kind) { return kIntegrators[size_t(kind)]; }

const Integrator* find_integrator(std::string_view name) {
  for (const Integrator& i : kIntegrators)
    if (i.name == name) return &i;
  return nullptr;
}

std::string integrator_names() {
  std::string names;
  for (const Integrator& i : kIntegrators) names += std::string(names.empty() ? "" : ", ") + std::string(i.name);
  return names;
}

IntegratorChoice choose_integrator(const SceneFeatures& f, bool per_pixel) {
  if (f.scattering) return {IntegratorKind::path, "the scene has scattering media, which only path renders"};
  const bool lights_in_scene = f.emissive_triangles || f.point_lights || f.spot_lights || f.directional_lights;
  if (!f.dielectric_volumes || !lights_in_scene)
    return {IntegratorKind::path, f.dielectric_volumes ? "the closed dielectrics are lit by the environment alone"
                                                       : "no closed dielectric makes caustics"};
  if (per_pixel)
    return {IntegratorKind::path,
            "the scene's caustics suit vcm, but the render needs per-pixel estimates (a noise threshold or spectral "
            "bins)"};
  return {IntegratorKind::vcm, "light reaches closed dielectrics from lights in the scene: caustics"};
}

}  // namespace prism
