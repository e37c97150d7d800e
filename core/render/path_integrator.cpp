#include "render/path_integrator.h"

#include "base/frame.h"
#include "materials/bsdf.h"

namespace prism {

namespace {

// Reflection that would cross to the other side of the geometric surface is refused: with
// shading normals it would leak light through (Veach 1997, §5.3).
bool crosses_surface(const SurfaceInteraction& si, const Vec3f& wi) {
  return dot(wi, si.n) * dot(si.wo, si.n) <= 0;
}

// Next-event estimation: one light sample, weighted against BSDF sampling by MIS.
template <int N>
SampledSpectrum<N> sample_direct(const World& world, const SurfaceInteraction& si, const Frame& frame,
                                 const Bsdf<N>& bsdf, const Vec3f& wo, const SampledWavelengths<N>& lambda,
                                 IndependentSampler& sampler, RayCounters& counters) {
  const float u_light = sampler.get_1d();
  const Vec2f u = sampler.get_2d();
  const PowerLightSampler& ls = world.light_sampler();
  if (ls.empty()) return SampledSpectrum<N>(0.f);
  const uint32_t index = ls.sample(u_light);
  const Light& light = world.lights()[index];
  const auto sample = sample_li(light, LightSampleContext{si.p, si.p_error, si.n}, u, lambda);
  const float pmf = ls.pmf(index);
  if (!sample || sample->L.is_zero() || pmf == 0.f || crosses_surface(si, sample->wi))
    return SampledSpectrum<N>(0.f);
  const Vec3f wi = frame.to_local(sample->wi);
  const SampledSpectrum<N> f = bsdf_f(bsdf, wo, wi) * abs_cos_theta(wi);
  if (f.is_zero()) return SampledSpectrum<N>(0.f);
  ++counters.shadow;
  if (world.occluded(sample->shadow_ray)) return SampledSpectrum<N>(0.f);
  const float light_pdf = pmf * sample->pdf;
  const float weight = is_delta(light) ? 1.f : power_heuristic(light_pdf, bsdf_pdf(bsdf, wo, wi));
  return f * sample->L * (weight / light_pdf);
}

}  // namespace

template <int N>
SampledSpectrum<N> path_radiance(const World& world, Ray ray, SampledWavelengths<N>& lambda,
                                 IndependentSampler& sampler, const PathOptions& options, RayCounters& counters) {
  SampledSpectrum<N> L(0.f), beta(1.f);
  bool specular_bounce = false;
  float bsdf_pdf_prev = 0.f;  // solid-angle pdf of the BSDF sample that made `ray`
  const PowerLightSampler& light_sampler = world.light_sampler();

  for (int depth = 0;; ++depth) {
    ++(depth == 0 ? counters.primary : counters.secondary);
    const auto si = world.intersect(ray);

    // Light reached without sampling it: full weight after a camera or specular vertex,
    // otherwise the MIS weight of BSDF sampling against light sampling.
    const auto add_emitted = [&](const SampledSpectrum<N>& Le, int light, float light_pdf_solid_angle) {
      if (depth == 0 || specular_bounce) {
        L += beta * Le;
      } else {
        const float light_pdf = light_sampler.pmf(uint32_t(light)) * light_pdf_solid_angle;
        L += beta * Le * power_heuristic(bsdf_pdf_prev, light_pdf);
      }
    };

    if (!si) {
      if (const EnvironmentLight* env = world.environment())
        add_emitted(sample(*env->radiance, lambda), world.environment_light(), env->pdf_li());
      break;
    }
    const Material& material = *si->material;
    if (material.emission) {
      const int light = world.area_light(si->instance, si->prim);
      const auto& area = std::get<AreaLight>(world.lights()[light]);
      if (area.emits_towards(si->wo)) add_emitted(sample(*material.emission, lambda), light,
                                                  area.pdf_solid_angle(si->t, ray.d));
    }
    if (depth == options.max_depth) break;

    const Bsdf<N> bsdf = make_bsdf(material, lambda);
    const Frame frame = Frame::from_z(si->ns);
    const Vec3f wo = frame.to_local(si->wo);
    if (!bsdf_is_specular(bsdf)) L += beta * sample_direct(world, *si, frame, bsdf, wo, lambda, sampler, counters);

    const float uc = sampler.get_1d();
    const auto bs = bsdf_sample_f(bsdf, wo, uc, sampler.get_2d());
    if (!bs || bs->pdf == 0.f) break;
    const Vec3f wi = frame.to_world(bs->wi);
    if (!bs->transmission && crosses_surface(*si, wi)) break;
    beta *= bs->f * (abs_cos_theta(bs->wi) / bs->pdf);
    specular_bounce = bs->specular;
    bsdf_pdf_prev = bs->pdf;
    ray = si->spawn(wi);

    // Russian roulette: continue with probability min(1, max throughput) after the first bounce.
    const float q = std::max(0.f, 1.f - beta.max());
    if (depth >= 1 && q > 0.f) {
      if (sampler.get_1d() < q) break;
      beta /= 1.f - q;
    }
    if (beta.is_zero()) break;
  }
  return L;
}

#define PRISM_INSTANTIATE(N)                                                                                  \
  template SampledSpectrum<N> path_radiance<N>(const World&, Ray, SampledWavelengths<N>&, IndependentSampler&, \
                                               const PathOptions&, RayCounters&);
PRISM_INSTANTIATE(1)
PRISM_INSTANTIATE(4)
PRISM_INSTANTIATE(8)
#undef PRISM_INSTANTIATE

}  // namespace prism
