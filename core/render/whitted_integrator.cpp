#include "core/render/whitted_integrator.h"

#include "core/render/direct_light.h"
#include "core/render/medium_sampling.h"
#include "core/render/medium_stack.h"
#include "materials/make_bsdf.h"

namespace prism {

namespace {

// Branches whose weight falls below this are not traced (adaptive depth control; Hall &
// Greenberg 1983): the bias is at most this fraction of the branch's radiance.
constexpr float kMinBranchWeight = 1e-4f;

struct Context {
  const World& world;
  Sampler& sampler;
  const PathOptions& options;
  RayCounters& counters;
};

template <int N>
SampledSpectrum<N> trace(const Context& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                         const MediumStack& media, int depth, float weight);

// Direct light at a diffuse surface: every delta (point, spot, directional) light, and one
// power-sampled sample of the area lights and the environment (constant or image).
// The light arrives through the medium on its side of the surface.
template <int N>
SampledSpectrum<N> direct_light(const Context& c, const SurfaceInteraction& si, const Frame& frame, const Bsdf<N>& bsdf,
                                const Vec3f& wo, const SampledWavelengths<N>& lambda, const MediumStack& media) {
  SampledSpectrum<N> L(0.f);
  const auto& lights = c.world.lights();
  const auto through = [&](const LightContribution<N>& d) {
    return d.f_L * transmittance(media.towards(si, d.wi), d.distance, lambda);
  };
  for (uint32_t i : c.world.delta_lights())
    if (const auto d = light_contribution(c.world, si, frame, bsdf, wo, lights[i], {}, lambda, c.counters))
      L += through(*d);
  const PowerLightSampler& area = c.world.area_light_sampler();
  const float u_light = c.sampler.get_1d();
  const Vec2f u = c.sampler.get_2d();
  if (!area.empty()) {
    const uint32_t k = area.sample(u_light);
    const auto d =
        light_contribution(c.world, si, frame, bsdf, wo, lights[c.world.area_lights()[k]], u, lambda, c.counters);
    if (d && area.pmf(k) > 0) L += through(*d) / (area.pmf(k) * d->light_pdf);
  }
  return L;
}

// Light leaving the hit towards wo: direct light through the BSDF's non-delta part, plus each
// delta branch (mirror, refraction) traced recursively with its weight.
template <int N>
SampledSpectrum<N> scatter(const Context& c, const SurfaceInteraction& si, const SampledWavelengths<N>& lambda,
                           const MediumStack& media, int depth, float weight) {
  const Material& material = *si.material;
  const bool entering = si.front_face();
  // (a dispersive interface only reaches here one wavelength at a time)
  const Bsdf<N> bsdf = make_bsdf(material, si.at, lambda, media.front_dielectric(material, entering));
  const Frame frame = si.shading_frame();
  const Vec3f wo = frame.to_local(si.wo);
  SampledSpectrum<N> L(0.f);
  if (!bsdf_is_specular(bsdf)) L += direct_light(c, si, frame, bsdf, wo, lambda, media);
  for (const DeltaLobe<N>& lobe : bsdf_delta_lobes(bsdf, wo)) {
    const Vec3f wi = frame.to_world(lobe.wi);
    if (wrong_side(si, wi, lobe.transmission)) continue;
    MediumStack beyond = media;
    if (lobe.transmission) beyond.cross(material, entering);
    L += lobe.weight * trace(c, si.spawn(wi), lambda, beyond, depth + 1, weight * lobe.weight.max());
  }
  return L;
}

// Radiance leaving the hit si towards the ray's origin.
template <int N>
SampledSpectrum<N> shade(const Context& c, const SurfaceInteraction& si, const SampledWavelengths<N>& lambda,
                         const MediumStack& media, int depth, float weight) {
  const Material& material = *si.material;
  SampledSpectrum<N> L(0.f);
  if (material.emission) {
    const auto& area = std::get<AreaLight>(c.world.lights()[c.world.area_light(si.instance, si.prim)]);
    if (area.emits_towards(si.wo)) L += material.emitted(si.at, lambda);
  }
  if (depth == c.options.max_depth || weight < kMinBranchWeight) return L;
  if constexpr (N > 1) {
    if (disperses(material, media.front_dielectric(material, si.front_face()))) {  // one trace per wavelength
      for (int i = 0; i < N; ++i) L[i] += scatter(c, si, lambda.lane(i), media, depth, weight)[0];
      return L;
    }
  }
  return L + scatter(c, si, lambda, media, depth, weight);
}

template <int N>
SampledSpectrum<N> trace(const Context& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                         const MediumStack& media, int depth, float weight) {
  ++(depth == 0 ? c.counters.primary : c.counters.secondary);
  const auto si = c.world.intersect(ray);
  const SampledSpectrum<N> T = transmittance(media.medium(), si ? si->t : kInfinity, lambda);
  if (!si) {
    const Light* env = c.world.environment();
    return env ? T * environment_Le(*env, ray.d, lambda) : SampledSpectrum<N>(0.f);
  }
  return T * shade(c, *si, lambda, media, depth, weight * T.max());
}

}  // namespace

template <int N>
SampledSpectrum<N> whitted_radiance(const World& world, const Ray& ray, const SampledWavelengths<N>& lambda,
                                    Sampler& sampler, const PathOptions& options, RayCounters& counters) {
  return trace(Context{world, sampler, options, counters}, ray, lambda, MediumStack(world.scene_medium()), 0, 1.f);
}

#define PRISM_INSTANTIATE(N)                                                                                        \
  template SampledSpectrum<N> whitted_radiance<N>(const World&, const Ray&, const SampledWavelengths<N>&, Sampler&, \
                                                  const PathOptions&, RayCounters&);
PRISM_INSTANTIATE(1)
PRISM_INSTANTIATE(4)
PRISM_INSTANTIATE(8)
#undef PRISM_INSTANTIATE

}  // namespace prism
