#include "core/render/bdpt.h"

#include <vector>

#include "core/render/direct_light.h"
#include "core/render/medium_sampling.h"
#include "core/render/medium_stack.h"
#include "core/render/path_vertex.h"
#include "core/render/russian_roulette.h"
#include "materials/make_bsdf.h"
#include "spectral/cie.h"

namespace prism {

BdptScene::BdptScene(const World& w, const Camera& c, bool m, bool lt)
    : world(w),
      camera(c),
      disk{{0, 0, 0}, 1.f},
      light_paths(float(c.width()) * float(c.height())),
      media(m),
      light_tracing(lt) {
  const Bounds3f b = w.accel().bounds();
  if (is_finite(b.lo) && is_finite(b.hi) && b.lo.x <= b.hi.x) {
    disk.center = b.centroid();
    disk.radius = std::max(length(b.hi - b.lo) * 0.5f * 1.01f, 1e-3f);
  }
}

namespace {

// The light subpath: one light chosen by power, an emission from it, and a random walk with the
// adjoint BSDF; its non-specular vertices are kept for connections.
// Light sampling from a point may choose lights otherwise (a light tree): the density of the
// strategy that samples the light from the first vertex is completed there, when that vertex is known.
template <int N>
void trace_light_path(const BdptScene& scene, SampledWavelengths<N>& lambda, Sampler& sampler,
                      const PathOptions& options, const MisFactors& factors, RayCounters& counters,
                      std::vector<LightVertex<N>>& vertices) {
  vertices.clear();
  const World& world = scene.world;
  const PowerLightSampler& lights = world.light_sampler().by_power();
  if (lights.empty()) return;
  const int block = options.max_depth + 1;  // the sampler's bounce blocks after the camera path's
  sampler.start_bounce(block);
  const float u_light = sampler.get_1d();
  const Vec2f u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  const uint32_t index = lights.sample(u_light);
  const float pick = lights.pmf(index);
  const Light& light = world.lights()[index];
  const auto e = sample_le(light, u_pos, u_dir, lambda, scene.disk);
  if (!e || e->Le.is_zero() || pick == 0.f) return;

  // Georgiev et al. 2012 eqs. 31–33: the direct-sampling density of the light's point (an area
  // density; a solid-angle one for an environment; 1 for delta lights) over the emission density.
  const bool finite = !is_infinite(light);
  const float emission_pdf = pick * e->pdf_pos * e->pdf_dir;
  const float direct_pdf = pick * (is_delta(light) ? 1.f : finite ? e->pdf_pos : e->pdf_dir);
  SampledSpectrum<N> beta = e->Le * (e->cos_light / emission_pdf);
  MisSums m{mis(direct_pdf / emission_pdf), is_delta(light) ? 0.f : mis((finite ? e->cos_light : 1.f) / emission_pdf)};
  m.vm = m.vc * factors.vc;
  const float beta0 = beta.max();
  Ray ray = e->ray;
  MediumStack media(scene.world.scene_medium());

  for (int length = 1; length <= options.max_depth; ++length) {
    sampler.start_bounce(block + length);
    ++counters.secondary;
    const auto si = world.intersect(ray);
    if (!si) break;
    // (Light from infinitely far crosses an infinite extent of the scene's medium, as a shadow ray
    // to it does, not just the stretch from the disk its paths start on.)
    if (scene.media) beta *= transmittance(media.medium(), length > 1 || finite ? si->t : kInfinity, lambda);
    m.arrive(si->t, abs_dot(si->n, si->wo), length > 1 || finite);
    if (length == 1)
      m.vcm *= mis(world.light_sampler().pmf(LightSampleContext{si->p, si->p_error, si->n}, index) / pick);
    const Material& material = *si->material;
    const bool entering = si->front_face();
    const Dielectric* front = scene.media ? media.front_dielectric(material, entering) : nullptr;
    const Frame frame = si->shading_frame();
    LightVertex<N> v{*si,
                     frame,
                     make_hero_bsdf<N>(material, si->at, lambda, front),
                     frame.to_local(si->wo),
                     beta,
                     m,
                     length,
                     lambda.secondary_terminated()};
    if (!bsdf_is_specular(v.bsdf)) vertices.push_back(v);
    if (length == options.max_depth) break;

    const float uc = sampler.get_1d();
    const auto bs = bsdf_sample_f(v.bsdf, v.wo, uc, sampler.get_2d());
    if (!bs || bs->pdf == 0.f) break;
    const Vec3f wi = frame.to_world(bs->wi);
    if (wrong_side(*si, wi, bs->transmission)) break;
    // Importance is not scaled by 1/η² at a refraction as radiance is (Veach 1997 §5.2): the
    // delta lobe's value takes it back; the others are the BSDF with its arguments exchanged.
    const SampledSpectrum<N> f = bs->specular ? bs->f * sqr(bs->eta) : bsdf_f(v.bsdf, bs->wi, v.wo);
    beta *= f * (abs_cos_theta(v.wo) * abs_dot(si->n, wi) / (abs_dot(si->n, si->wo) * bs->pdf));
    m.scatter(bs->pdf, bs->specular ? bs->pdf : bsdf_pdf(v.bsdf, bs->wi, v.wo), abs_dot(si->n, wi), bs->specular,
              factors);
    ray = si->spawn(wi);
    if (bs->transmission && scene.media) media.cross(material, entering);

    // Russian roulette on the throughput relative to the emitted one, after the first bounce.
    const float q = roulette_termination(beta.max() / beta0);
    if (options.russian_roulette && length >= 2 && q > 0.f) {
      if (sampler.get_1d() < q) break;
      beta /= 1.f - q;
    }
    if (beta.is_zero()) break;
  }
}

// s = 1: a light sample seen from camera vertex si (Georgiev et al. 2012 eqs. 43–45).
template <int N>
SampledSpectrum<N> connect_light(const BdptScene& scene, const SurfaceInteraction& si, const Frame& frame,
                                 const Bsdf<N>& bsdf, const Vec3f& wo, const MisSums& m, const MisFactors& factors,
                                 const MediumStack& media, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 RayCounters& counters) {
  const float u_light = sampler.get_1d();
  const Vec2f u = sampler.get_2d();
  const LightSampler& lights = scene.world.light_sampler();
  const LightSampleContext ctx{si.p, si.p_error, si.n};
  const auto chosen = lights.sample(ctx, u_light);
  if (!chosen || chosen->pmf == 0.f) return SampledSpectrum<N>(0.f);
  const float pick = chosen->pmf, emission_pick = lights.by_power().pmf(chosen->light);
  const Light& light = scene.world.lights()[chosen->light];
  const auto s = sample_li(light, ctx, u, lambda);
  if (!s || s->L.is_zero() || !(s->pdf > 0.f)) return SampledSpectrum<N>(0.f);
  const Vec3f wi = frame.to_local(s->wi);
  if (wrong_side(si, s->wi, wi.z * wo.z < 0)) return SampledSpectrum<N>(0.f);
  const BsdfEval<N> e = bsdf_eval(bsdf, wo, wi);
  const SampledSpectrum<N> f = e.f * abs_cos_theta(wi);
  if (f.is_zero()) return SampledSpectrum<N>(0.f);

  // The direct sample's solid-angle density (a point light's is d², a directional light's 1,
  // as its L is already divided by d²), the light's cosine, and the distance for absorption.
  float direct_pdf = s->pdf, cos_light = 1.f, distance = kInfinity;
  if (const auto* a = std::get_if<AreaLight>(&light))
    cos_light = abs_dot(a->n, s->wi), distance = s->distance;
  else if (const auto* p = std::get_if<PointLightSource>(&light)) {
    direct_pdf = length_squared(p->position - si.p), distance = std::sqrt(direct_pdf);
  } else if (const auto* sp = std::get_if<SpotLightSource>(&light)) {
    direct_pdf = length_squared(sp->point.position - si.p), distance = std::sqrt(direct_pdf);
  }
  const float emission_pdf = pdf_le(light, -s->wi, scene.disk, s->density).product();
  const float bsdf_dir = is_delta(light) ? 0.f : e.pdf;
  const float w_light = mis(bsdf_dir / (pick * direct_pdf));
  const float w_camera = mis(emission_pick * emission_pdf * abs_dot(si.n, s->wi) / (pick * direct_pdf * cos_light)) *
                         m.connection(bsdf_pdf(bsdf, wi, wo), factors);
  ++counters.shadow;
  if (scene.world.occluded(s->shadow_ray)) return SampledSpectrum<N>(0.f);
  SampledSpectrum<N> c = f * s->L / (pick * s->pdf * (1.f + w_light + w_camera));
  if (scene.media) c *= transmittance(media.towards(si, s->wi), distance, lambda);
  return c;
}

// s ≥ 2, t ≥ 2: camera vertex si joined to light vertex v (eqs. 40–42).
template <int N>
SampledSpectrum<N> connect_vertices(const BdptScene& scene, const SurfaceInteraction& si, const Frame& frame,
                                    const Bsdf<N>& bsdf, const Vec3f& wo, const MisSums& m, const MisFactors& factors,
                                    const MediumStack& media, const LightVertex<N>& v,
                                    const SampledWavelengths<N>& lambda, RayCounters& counters) {
  const Vec3f d = v.si.p - si.p;
  const float dist2 = length_squared(d);
  if (!(dist2 > 0.f)) return SampledSpectrum<N>(0.f);
  const float dist = std::sqrt(dist2);
  const Vec3f w = d / dist;
  const Vec3f wi = frame.to_local(w), wl = v.frame.to_local(-w);
  if (wrong_side(si, w, wi.z * wo.z < 0) || wrong_side(v.si, -w, wl.z * v.wo.z < 0)) return SampledSpectrum<N>(0.f);
  const BsdfEval<N> e = bsdf_eval(bsdf, wo, wi);
  const SampledSpectrum<N> c = e.f * v.adjoint_f(wl, -w) * v.beta * (abs_cos_theta(wi) / dist2);
  if (c.is_zero()) return SampledSpectrum<N>(0.f);
  // Each side's density of making the other's vertex, as an area density there.
  const float camera_pdf = e.pdf * abs_dot(v.si.n, w) / dist2;
  const float light_pdf = bsdf_pdf(v.bsdf, v.wo, wl) * abs_dot(si.n, w) / dist2;
  const float w_light = mis(camera_pdf) * v.mis.connection(bsdf_pdf(v.bsdf, wl, v.wo), factors);
  const float w_camera = mis(light_pdf) * m.connection(bsdf_pdf(bsdf, wi, wo), factors);
  ++counters.shadow;
  if (scene.world.occluded(spawn_ray_to(si.p, si.p_error, si.n, v.si.p, v.si.p_error, v.si.n)))
    return SampledSpectrum<N>(0.f);
  SampledSpectrum<N> r = c / (1.f + w_light + w_camera);
  if (scene.media) r *= transmittance(media.towards(si, w), dist, lambda);
  return r;
}

// t = 1: light vertex v seen by the camera through the aperture point u_lens picks, splatted where
// it lands on the film (eqs. 46–47): β · f · |cos| · (camera ray density across the ray at v) /
// (light paths per pixel sample).
template <int N>
void splat_to_camera(const BdptScene& scene, const LightVertex<N>& v, Vec2f u_lens, const MisFactors& factors,
                     const SampledWavelengths<N>& lambda, SplatBuffer& splats, RayCounters& counters,
                     uint64_t& invalid) {
  const auto c = scene.camera.connect(v.si.p, u_lens);
  if (!c) return;
  const Vec3f wl = v.frame.to_local(c->w);
  if (wrong_side(v.si, c->w, wl.z * v.wo.z < 0)) return;
  const SampledSpectrum<N> f = v.adjoint_f(wl, c->w);
  if (f.is_zero()) return;
  const float camera_pdf = c->importance * abs_dot(v.si.n, c->w);  // an area density at v
  const float w_light = mis(camera_pdf / scene.light_paths) * v.mis.connection(bsdf_pdf(v.bsdf, wl, v.wo), factors);
  ++counters.shadow;
  if (scene.world.occluded(spawn_ray_to(v.si.p, v.si.p_error, v.si.n, c->point, {}, {}))) return;
  const float weight = scene.light_tracing ? 1.f : 1.f / (1.f + w_light);
  SampledSpectrum<N> L = v.beta * f * (c->importance * weight / scene.light_paths);
  // The camera is in the scene's medium, and so is any vertex it sees unoccluded.
  if (scene.media) L *= transmittance(scene.world.scene_medium(), length(c->point - v.si.p), lambda);
  if (!splats.add(c->raster.x, c->raster.y, to_xyz(v.hero_only ? hero_lane(L) : L, lambda))) ++invalid;
}

}  // namespace

template <int N>
void trace_photons(const BdptScene& scene, SampledWavelengths<N> lambda, Sampler& sampler, const PathOptions& options,
                   const MisFactors& factors, RayCounters& counters, std::vector<Vec3f>& positions,
                   std::vector<Photon<N>>& photons) {
  thread_local std::vector<LightVertex<N>> light;
  trace_light_path(scene, lambda, sampler, options, factors, counters, light);
  for (const LightVertex<N>& v : light) {
    positions.push_back(v.si.p);
    photons.push_back({v.beta, v.si.wo, v.mis.vcm, v.mis.vm, v.length, v.hero_only});
  }
}

template <int N>
SampledSpectrum<N> bdpt_radiance(const BdptScene& scene, Ray ray, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 const PathOptions& options, const VcmIteration<N>* vcm, SplatBuffer& splats,
                                 RayCounters& counters, uint64_t& invalid) {
  const MisFactors factors = vcm ? vcm->factors() : MisFactors{};
  thread_local std::vector<LightVertex<N>> light;
  SampledWavelengths<N> light_lambda = lambda, camera_lambda = lambda;  // each subpath terminates its own
  trace_light_path(scene, light_lambda, sampler, options, factors, counters, light);
  // t = 1: the light path seen by the camera (through an aperture point of its own, with a lens).
  for (const LightVertex<N>& v : light) {
    const Vec2f u_lens = scene.camera.has_lens() ? sampler.get_2d() : Vec2f{};
    splat_to_camera(scene, v, u_lens, factors, lambda, splats, counters, invalid);
  }

  const World& world = scene.world;
  const LightSampler& lights = world.light_sampler();
  LightSampleContext prev{};  // the camera vertex before this one, as it chose a light
  // The densities of choosing `light` from the previous vertex, and for a light path.
  const auto picks = [&](int depth, uint32_t light) {
    return std::pair(depth > 0 ? lights.pmf(prev, light) : 0.f, lights.by_power().pmf(light));
  };
  // Contributions valid for all lanes, and those only the hero wavelength could make: a camera
  // vertex after a dispersive interface, or a light vertex after one (or a photon).
  SampledSpectrum<N> L(0.f), hero(0.f), beta(1.f);
  const auto add = [&](const SampledSpectrum<N>& c, bool hero_only) { (hero_only ? hero : L) += c; };
  MisSums m{mis(scene.light_paths / scene.camera.ray_density(ray)), 0.f, 0.f};
  float eta_scale = 1.f;  // Π η² of the refractions so far: undoes radiance scaling for roulette
  MediumStack media(scene.world.scene_medium());
  // s = 0: a light the camera path reached; full weight when seen directly (eq. 38).
  const auto add_emitted = [&](int depth, const SampledSpectrum<N>& Le, float direct_pdf, float emission_pdf) {
    add(depth == 0 ? beta * Le : beta * Le / (1.f + mis(direct_pdf) * m.vcm + mis(emission_pdf) * m.vc),
        camera_lambda.secondary_terminated());
  };

  for (int depth = 0;; ++depth) {
    sampler.start_bounce(depth);
    ++(depth == 0 ? counters.primary : counters.secondary);
    const auto si = world.intersect(ray);
    if (scene.media) beta *= transmittance(media.medium(), si ? si->t : kInfinity, camera_lambda);
    if (!si) {
      if (const Light* env = world.environment()) {
        const auto [pick, emission_pick] = picks(depth, uint32_t(world.environment_light()));
        const float pdf = environment_pdf(*env, ray.d);
        add_emitted(depth, environment_Le(*env, ray.d, camera_lambda), pick * pdf,
                    emission_pick * pdf * scene.disk.pdf());
      }
      break;
    }
    m.arrive(si->t, abs_dot(si->n, si->wo), depth > 0 || scene.camera.perspective());
    const Material& material = *si->material;
    if (material.emission) {
      const int index = world.area_light(si->instance, si->prim);
      const Light& light = world.lights()[index];
      if (const auto& area = std::get<AreaLight>(light); area.emits_towards(si->wo)) {
        const auto [pick, emission_pick] = picks(depth, uint32_t(index));
        const EmissionPdf e = pdf_le(light, si->wo, scene.disk, area.density_at(si->p));
        add_emitted(depth, material.emitted(si->at, camera_lambda), pick * e.pdf_pos, emission_pick * e.product());
      }
    }
    if (depth == options.max_depth || scene.light_tracing) break;

    const bool entering = si->front_face();
    const Dielectric* front = scene.media ? media.front_dielectric(material, entering) : nullptr;
    const Bsdf<N> bsdf = make_hero_bsdf<N>(material, si->at, camera_lambda, front);
    const Frame frame = si->shading_frame();
    const Vec3f wo = frame.to_local(si->wo);
    if (!bsdf_is_specular(bsdf)) {
      const bool camera_hero = camera_lambda.secondary_terminated();
      add(beta * connect_light(scene, *si, frame, bsdf, wo, m, factors, media, camera_lambda, sampler, counters),
          camera_hero);
      // Paths of at most max_depth + 1 segments, as the path tracer's.
      for (const LightVertex<N>& v : light) {
        if (v.length + depth + 2 > options.max_depth + 1) break;
        add(beta * connect_vertices(scene, *si, frame, bsdf, wo, m, factors, media, v, camera_lambda, counters),
            camera_hero || v.hero_only);
      }
      if (vcm) {
        SampledSpectrum<N> all(0.f), hero_photons(0.f);
        vcm->merge(*si, frame, bsdf, wo, m, depth, options.max_depth, all, hero_photons);
        add(beta * all, camera_hero);
        hero += beta * hero_photons;
      }
    }

    const float uc = sampler.get_1d();
    const auto bs = bsdf_sample_f(bsdf, wo, uc, sampler.get_2d());
    if (!bs || bs->pdf == 0.f) break;
    const Vec3f wi = frame.to_world(bs->wi);
    if (wrong_side(*si, wi, bs->transmission)) break;
    beta *= bs->f * (abs_cos_theta(bs->wi) / bs->pdf);
    m.scatter(bs->pdf, bs->specular ? bs->pdf : bsdf_pdf(bsdf, bs->wi, wo), abs_dot(si->n, wi), bs->specular, factors);
    ray = si->spawn(wi);
    prev = {si->p, si->p_error, si->n};
    if (bs->transmission) {
      eta_scale *= sqr(bs->eta);
      if (scene.media) media.cross(material, entering);
    }
    const float q = roulette_termination(beta.max() * eta_scale);
    if (options.russian_roulette && depth >= 1 && q > 0.f) {
      if (sampler.get_1d() < q) break;
      beta /= 1.f - q;
    }
    if (beta.is_zero()) break;
  }

  return L + hero_lane(hero);
}

#define PRISM_INSTANTIATE(N)                                                                                           \
  template SampledSpectrum<N> bdpt_radiance<N>(const BdptScene&, Ray, const SampledWavelengths<N>&, Sampler&,          \
                                               const PathOptions&, const VcmIteration<N>*, SplatBuffer&, RayCounters&, \
                                               uint64_t&);                                                             \
  template void trace_photons<N>(const BdptScene&, SampledWavelengths<N>, Sampler&, const PathOptions&,                \
                                 const MisFactors&, RayCounters&, std::vector<Vec3f>&, std::vector<Photon<N>>&);
PRISM_INSTANTIATE(1)
PRISM_INSTANTIATE(4)
PRISM_INSTANTIATE(8)
#undef PRISM_INSTANTIATE

}  // namespace prism
