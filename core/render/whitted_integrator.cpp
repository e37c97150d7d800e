#include "render/whitted_integrator.h"

#include "render/direct_light.h"
#include "render/medium_stack.h"

namespace prism {

namespace {

// Branches whose weight falls below this are not traced (adaptive depth control; Hall &
// Greenberg 1983): the bias is at most this fraction of the branch's radiance.
constexpr float kMinBranchWeight = 1e-4f;

struct Context {
  const World& world;
  IndependentSampler& sampler;
  const PathOptions& options;
  RayCounters& counters;
};

template <int N>
SampledSpectrum<N> trace(const Context& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                         const MediumStack& media, int depth, float weight);

// Direct light at a diffuse surface: every delta (point, spot, directional) light, and one
// power-sampled sample of the area lights and the environment (constant or image).
template <int N>
SampledSpectrum<N> direct_light(const Context& c, const SurfaceInteraction& si, const Frame& frame,
                                const Bsdf<N>& bsdf, const Vec3f& wo, const SampledWavelengths<N>& lambda) {
  SampledSpectrum<N> L(0.f);
  const auto& lights = c.world.lights();
  for (uint32_t i : c.world.delta_lights())
    if (const auto d = light_contribution(c.world, si, frame, bsdf, wo, lights[i], {}, lambda, c.counters))
      L += d->f_L;
  const PowerLightSampler& area = c.world.area_light_sampler();
  const float u_light = c.sampler.get_1d();
  const Vec2f u = c.sampler.get_2d();
  if (!area.empty()) {
    const uint32_t k = area.sample(u_light);
    const auto d = light_contribution(c.world, si, frame, bsdf, wo, lights[c.world.area_lights()[k]], u, lambda,
                                      c.counters);
    if (d && area.pmf(k) > 0) L += d->f_L / (area.pmf(k) * d->light_pdf);
  }
  return L;
}

// The light leaving a dielectric surface towards wo: the reflected plus the transmitted branch.
template <int N>
SampledSpectrum<N> split_dielectric(const Context& c, const SurfaceInteraction& si, const Material& material,
                                    SampledWavelengths<N> lambda, const MediumStack& media, int depth,
                                    float weight) {
  const bool entering = si.front_face();
  const auto bsdf = std::get<DielectricBsdf<N>>(make_bsdf(material, lambda, media.front_dielectric(material, entering)));
  const Frame frame = Frame::from_z(si.ns);
  const Vec3f wo = frame.to_local(si.wo);
  const float R = bsdf.reflectance(wo);
  SampledSpectrum<N> L(0.f);
  if (R > 0) L += trace(c, si.spawn(frame.to_world({-wo.x, -wo.y, wo.z})), lambda, media, depth + 1, weight * R) * R;
  if (const auto t = bsdf.transmission(wo)) {
    MediumStack beyond = media;
    beyond.cross(material, entering);
    L += t->weight * trace(c, si.spawn(frame.to_world(t->wi)), lambda, beyond, depth + 1, weight * t->weight.max());
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
    if (area.emits_towards(si.wo)) L += sample(*material.emission, lambda);
  }
  if (depth == c.options.max_depth || weight < kMinBranchWeight) return L;

  if (const DielectricMaterial* d = material.dielectric()) {
    const DielectricMaterial* front = media.front_dielectric(material, si.front_face());
    if constexpr (N > 1) {
      if (d->dispersive || (front && front->dispersive)) {  // one trace per wavelength
        for (int i = 0; i < N; ++i)
          L[i] += split_dielectric(c, si, material, lambda.lane(i), media, depth, weight)[0];
        return L;
      }
    }
    return L + split_dielectric(c, si, material, lambda, media, depth, weight);
  }

  SampledWavelengths<N> lambda_copy = lambda;  // make_bsdf may only terminate for dielectrics
  const Bsdf<N> bsdf = make_bsdf(material, lambda_copy, media.front_dielectric(material, si.front_face()));
  const Frame frame = Frame::from_z(si.ns);
  const Vec3f wo = frame.to_local(si.wo);
  if (const auto* conductor = std::get_if<ConductorBsdf<N>>(&bsdf)) {
    const SampledSpectrum<N> F = conductor->reflectance(cos_theta(wo));
    const Vec3f wi = frame.to_world({-wo.x, -wo.y, wo.z});
    if (crosses_surface(si, wi)) return L;
    return L + F * trace(c, si.spawn(wi), lambda, media, depth + 1, weight * F.max());
  }
  return L + direct_light(c, si, frame, bsdf, wo, lambda);
}

template <int N>
SampledSpectrum<N> trace(const Context& c, const Ray& ray, const SampledWavelengths<N>& lambda,
                         const MediumStack& media, int depth, float weight) {
  ++(depth == 0 ? c.counters.primary : c.counters.secondary);
  const auto si = c.world.intersect(ray);
  const SampledSpectrum<N> transmittance = media.transmittance(si ? si->t : kInfinity, lambda);
  if (!si) {
    const Light* env = c.world.environment();
    return env ? transmittance * environment_Le(*env, ray.d, lambda) : SampledSpectrum<N>(0.f);
  }
  return transmittance * shade(c, *si, lambda, media, depth, weight * transmittance.max());
}

}  // namespace

template <int N>
SampledSpectrum<N> whitted_radiance(const World& world, const Ray& ray, const SampledWavelengths<N>& lambda,
                                    IndependentSampler& sampler, const PathOptions& options, RayCounters& counters) {
  return trace(Context{world, sampler, options, counters}, ray, lambda, MediumStack{}, 0, 1.f);
}

#define PRISM_INSTANTIATE(N)                                                                  \
  template SampledSpectrum<N> whitted_radiance<N>(const World&, const Ray&, const SampledWavelengths<N>&, \
                                                  IndependentSampler&, const PathOptions&, RayCounters&);
PRISM_INSTANTIATE(1)
PRISM_INSTANTIATE(4)
PRISM_INSTANTIATE(8)
#undef PRISM_INSTANTIATE

}  // namespace prism
