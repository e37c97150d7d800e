#pragma once
// The path tracer's definition, instantiated by path_integrator.cpp (8 lanes, the default) and
// path_integrator_narrow.cpp (1 and 4 lanes). Apart, because GCC's inlining budget is per file
// (--param inline-unit-growth): with all twelve variants in one file, the 8-lane loop's own
// helpers (offset_ray_origin, spawn_ray) were left out of line whenever a header it includes grew.

#include <new>

#include "core/render/direct_light.h"
#include "core/render/medium_sampling.h"
#include "core/render/medium_stack.h"
#include "core/render/path_integrator.h"
#include "core/render/russian_roulette.h"
#include "materials/bsdf_cache.h"
#include "materials/dispersive_bsdf.h"

namespace prism {

namespace {

// Next-event estimation: one light chosen for the point `at` (light_sampler.h), weighted against
// BSDF or phase sampling by MIS; contribution(light, u) is what that light's sample gives there.
template <int N, class Contribution>
SampledSpectrum<N> sample_direct(const World& world, const LightSampleContext& at, Sampler& sampler,
                                 const Contribution& contribution) {
  const float u_light = sampler.get_1d();
  const Vec2f u = sampler.get_2d();
  const auto chosen = world.light_sampler().sample(at, u_light);
  if (!chosen || chosen->pmf == 0.f) return SampledSpectrum<N>(0.f);
  const Light& light = world.lights()[chosen->light];
  const std::optional<LightContribution<N>> c = contribution(light, u);
  if (!c) return SampledSpectrum<N>(0.f);
  const float light_pdf = chosen->pmf * c->light_pdf;
  const float weight = is_delta(light) ? 1.f : balance_heuristic(light_pdf, c->bsdf_pdf);
  return c->f_L * (weight / light_pdf);
}

// A light sample from a point in a medium, the shadow ray crossing it: the light arrives attenuated
// by the medium's transmittance T, and, in a scattering medium, BSDF or phase sampling reaches the
// light only if the lanes' distance sampling then passes the segment, so its pdf for MIS is
// Σ q_j p_j(wi) T_j / Σ q_j (medium_sampling.h): p̄ × the mean T, with a dispersive BSDF's lanes'
// pdfs weighted by q_j T_j rather than q_j (the phase function's and other BSDFs' are the same in
// every lane). `bsdf` is the BSDF at a surface, or the phase function at a medium's point.
template <int N, class B>
void through_medium(LightContribution<N>& c, const MediumCoefficients<N>& medium, bool scattering, const B& bsdf,
                    const Vec3f& wo, const Frame& frame, SampledSpectrum<N>& path_pdfs) {
  const SampledSpectrum<N> T = medium.transmittance(c.distance);
  c.f_L *= T;
  if (!scattering) return;
  if constexpr (std::is_same_v<B, DispersiveBsdf<N>>) {  // (wo and frame serve only here)
    const SampledSpectrum<N> q = path_pdfs;
    path_pdfs *= T;  // the lanes' weights in the dispersive BSDF's p̄
    c.bsdf_pdf = path_pdfs.max() > 0 ? bsdf_eval(bsdf, wo, frame.to_local(c.wi)).pdf : 0.f;
    path_pdfs = q;
  }
  c.bsdf_pdf *= mean_transmittance(T, path_pdfs);
}

// Russian roulette at a path's vertex: ends the path (false), or keeps it with beta raised by the
// probability of surviving.
template <int N>
bool survives_roulette(SampledSpectrum<N>& beta, float eta_scale, Sampler& sampler) {
  const float q = roulette_termination(beta.max() * eta_scale);
  if (q <= 0.f) return true;
  if (sampler.get_1d() < q) return false;
  beta /= 1.f - q;
  return true;
}

// An alpha BLEND surface (opacity alpha) is the surface beside a hole, as Cycles' transparent BSDF
// mixed in by alpha. The path passes through (returns true) or stays with probabilities in
// proportion to the two shares' throughputs at this BSDF sample, 1 − α and α w (w: the sample's
// f cos / pdf, averaged over the lanes), and beta takes its share over that probability: unbiased
// for any such split (w is drawn first, the choice given w), and beta changes little whichever way
// the path goes, where choosing the surface with probability α followed a dark surface α of the
// time, with several times Cycles' variance. Light is sampled only where the path
// stays, so staying must stay possible: without a sample to follow (w ≤ 0: none, or one of no
// weight) the split is α to 1 − α, as if w were 1.
template <int N>
bool pass_through(float alpha, float w, float u, SampledSpectrum<N>& beta) {
  const float pass = (1 - alpha) / ((1 - alpha) + alpha * (w > 0 ? w : 1.f));
  const bool passes = u < pass;
  beta *= passes ? (1 - alpha) / pass : alpha / (1 - pass);
  return passes;
}

}  // namespace

template <int N, bool Media, bool Dispersion>
SampledSpectrum<N> path_radiance(const World& world, Ray ray, const SampledWavelengths<N>& lambda, Sampler& sampler,
                                 const PathOptions& options, RayCounters& counters,
                                 const std::optional<SurfaceInteraction>* first) {
  // At a dispersive interface the lanes' pdfs of a direction differ: path_pdfs are the path's pdfs
  // under each lane as the hero, relative to each other, for spectral MIS (dispersive_bsdf.h).
  SampledSpectrum<N> L(0.f), beta(1.f), path_pdfs(1.f);
  bool no_light_sampled = false;  // the last vertex sampled no light (specular, or in a closed medium)
  float bsdf_pdf_prev = 0.f;      // solid-angle pdf of the BSDF sample that made `ray`
  LightSampleContext prev;        // that vertex, as it chose a light (and sampled the environment)
  float eta_scale = 1.f;          // Π η² of the refractions so far: undoes radiance scaling for roulette
  bool roulette_due = false;      // a bounce since the last roulette, and past the first one
  // From the last scattering vertex to ray.o, over the BLEND surfaces passed: light met beyond them
  // is that much farther away (for area lights' solid-angle pdfs).
  float travelled = 0;
  int medium_events = 0;  // scatterings in media so far (they are not counted in depth)
  MediumStack media(Media ? world.scene_medium() : nullptr);
  MediumCoefficients<N> medium;         // of the medium the path is in, at its wavelengths
  MediumCoefficients<N> beyond_medium;  // of the one beyond a surface, for light sampled through it
  const LightSampler& light_sampler = world.light_sampler();
  const PathSky<N> sky(world.environment(), lambda);
  BsdfCache<N> bsdf_cache;

  // `vertex` counts every surface and medium event met, `depth` the surfaces the path scattered at
  // (not passed through): each vertex has its own block of sampler dimensions, the depth limit
  // counts bounces, and depth + medium_events all scatterings.
  for (int depth = 0, vertex = 0;; ++vertex) {
    sampler.start_bounce(vertex);
    ++(vertex == 0 ? counters.primary : counters.secondary);
    const auto si = vertex == 0 && first ? *first : world.intersect(ray, true);
    // Through the medium up to the surface: absorbed on the way, or, in a scattering medium,
    // scattered at a point before it (medium_sampling.h).
    const Medium* in = Media ? media.medium() : nullptr;
    const float t_surface = si ? si->t : kInfinity;
    std::optional<float> t_scatter;
    if (in) {
      medium.of(*in, lambda);
      if (!in->scatters()) {
        beta *= medium.transmittance(t_surface);
      } else {
        const MediumEvent<N> e = sample_medium_event(medium, t_surface, sampler.get_1d(), path_pdfs);
        beta *= e.weight;
        if (e.scattered)
          t_scatter = e.t;
        else
          bsdf_pdf_prev *= e.pdf;  // light met at the surface was reached by passing the segment
      }
    }
    if (t_scatter) {
      // A scattering event in the medium: light sampled towards it, and the path goes on in a
      // direction from the phase function, which samples itself exactly (weight 1). Inside a
      // closed dielectric (milk, wax) a shadow ray meets the enclosing surface before any light
      // outside it, so no light is sampled there: light the phase function finds then takes its
      // full weight, exactly as after a specular bounce (only a light inside the medium is found
      // less easily).
      const bool sample_light = options.next_event && !media.innermost();
      if (depth == options.max_depth || beta.is_zero() || ++medium_events > kMaxMediumEvents) break;
      if (roulette_due) {
        roulette_due = false;
        if (!survives_roulette(beta, eta_scale, sampler)) break;
      }
      const Vec3f p = ray.o + ray.d * *t_scatter;
      const HenyeyGreenstein& phase = in->phase;
      prev = {p, Vec3f(0.f, 0.f, 0.f), Vec3f(0.f, 0.f, 0.f)};
      if (sample_light)
        L += beta * sample_direct<N>(world, prev, sampler, [&](const Light& light, Vec2f u) {
               auto s = sample_li(light, prev, u, lambda, &sky);
               if (!s || s->L.is_zero()) return std::optional<LightContribution<N>>();
               ++counters.shadow;
               const float visible = world.transmittance(s->shadow_ray);
               const float f = phase.eval(ray.d, s->wi);
               if (visible == 0 || f == 0) return std::optional<LightContribution<N>>();
               LightContribution<N> c{s->L * (visible * f), s->pdf, f, s->wi, s->shadow_ray.tmax};
               through_medium(c, medium, true, phase, Vec3f(), Frame(), path_pdfs);
               return std::optional(c);
             });
      const Vec3f wi = phase.sample(ray.d, sampler.get_2d());
      no_light_sampled = !sample_light;
      bsdf_pdf_prev = phase.pdf(ray.d, wi);
      ::new (&ray) Ray{p, wi};
      travelled = 0;
      roulette_due = options.russian_roulette && depth + medium_events >= 2;
      continue;
    }
    const float alpha = si ? si->material->blend_opacity(si->at) : 1.f;  // < 1: an alpha BLEND surface, partly a hole

    // Light reached without sampling it: full weight after the camera or a vertex that sampled none,
    // otherwise the MIS weight of BSDF sampling against light sampling (whose solid-angle pdf,
    // a callable, is evaluated only then).
    const auto add_emitted = [&](const SampledSpectrum<N>& Le, int light, const auto& light_pdf_solid_angle) {
      if (depth + medium_events == 0 || no_light_sampled || !options.next_event) {
        L += beta * Le;
      } else {
        const float pmf = light_sampler.pmf(prev, uint32_t(light));
        const float light_pdf = pmf > 0 ? pmf * light_pdf_solid_angle() : 0.f;
        L += beta * Le * balance_heuristic(bsdf_pdf_prev, light_pdf);
      }
    };

    if (!si) {
      if (const Light* env = world.environment())
        add_emitted(environment_Le(*env, ray.d, lambda, &sky), world.environment_light(),
                    [&] { return environment_pdf(*env, ray.d, prev.reflect_axis); });
      break;
    }
    const Material& material = *si->material;
    if (material.emission) {
      const int light = world.area_light(si->instance, si->prim);
      const auto& area = std::get<AreaLight>(world.lights()[light]);
      if (area.emits_towards(si->wo))
        add_emitted(material.emitted(si->at, lambda) * alpha, light,
                    [&] { return area.pdf_solid_angle(travelled + si->t, ray.d, area.density_at(si->p)); });
    }
    // A fully clear BLEND texel is passed at once; past the last bounce, light beyond a BLEND
    // surface still counts: seen with probability 1 − α.
    const bool last = depth == options.max_depth;
    if (alpha <= 0 || (last && alpha < 1 && sampler.get_1d() < 1 - alpha)) {
      travelled += World::step_beyond(*si, ray);
      continue;
    }
    if (last) break;
    // Russian roulette from the third surface on, where the path meets it and before shading it
    // (Cycles' rule): a ray that leaves for the sky is never cut short, so the sky's light, most of
    // an open scene's, carries no roulette noise.
    if (roulette_due) {
      roulette_due = false;
      if (!survives_roulette(beta, eta_scale, sampler)) break;
    }

    const bool entering = si->front_face();
    const Dielectric* front = Media ? media.front_dielectric(material, entering) : nullptr;
    const Frame frame = si->shading_frame();
    const Vec3f wo = frame.to_local(si->wo);
    const Vec3f reflect_axis = material.transmits() ? Vec3f(0.f, 0.f, 0.f) : wo.z < 0 ? -frame.z : frame.z;
    // Light sampling, then the BSDF sample that continues the path, for either kind of BSDF; at a
    // BLEND surface, light sampling only where the path stays (see pass_through).
    bool passes = false;
    const SampledSpectrum<N> path_pdfs_before = path_pdfs;  // a dispersive sample updates them
    const auto scatter = [&](const auto& bsdf) {
      const auto direct = [&] {
        if (!options.next_event || bsdf_is_specular(bsdf)) return;
        const LightSampleContext at{si->p, si->p_error, si->n, reflect_axis};
        L += beta * sample_direct<N>(world, at, sampler, [&](const Light& light, Vec2f u) {
               auto c = light_contribution(world, *si, frame, bsdf, wo, light, u, lambda, counters, reflect_axis, &sky);
               if constexpr (Media)  // the shadow ray crosses the medium on the light's side of the surface
                 if (const Medium* m = c ? media.towards(*si, c->wi) : nullptr)
                   through_medium(*c, m == in ? medium : beyond_medium.of(*m, lambda), m->scatters(), bsdf, wo, frame,
                                  path_pdfs);
               return c;
             });
      };
      if (alpha == 1) direct();
      const float uc = sampler.get_1d();
      const auto b = bsdf_sample_f(bsdf, wo, uc, sampler.get_2d());
      if (alpha < 1) {
        const bool valid = b && b->pdf > 0.f && !wrong_side(*si, frame.to_world(b->wi), b->transmission);
        passes = pass_through(alpha, valid ? (b->f * (abs_cos_theta(b->wi) / b->pdf)).average() : 0.f, sampler.get_1d(),
                              beta);
        if (!passes) {  // light sampling's MIS weighs by the lanes' pdfs from before this sample
          const SampledSpectrum<N> sampled = path_pdfs;
          path_pdfs = path_pdfs_before;
          direct();
          path_pdfs = sampled;
        }
      }
      return b;
    };
    const auto bs = [&] {
      if constexpr (Dispersion && N > 1)
        if (disperses(material, front) && companions_alive(path_pdfs))
          return scatter(DispersiveBsdf<N>(material, si->at, lambda, front, path_pdfs));
      return scatter(bsdf_cache.of(material, si->at, lambda, front));
    }();
    if (passes) {
      path_pdfs = path_pdfs_before;
      travelled += World::step_beyond(*si, ray);
      continue;
    }
    if (!bs || bs->pdf == 0.f) break;
    const Vec3f wi = frame.to_world(bs->wi);
    if (wrong_side(*si, wi, bs->transmission)) break;
    beta *= bs->f * (abs_cos_theta(bs->wi) / bs->pdf);
    no_light_sampled = bs->specular;
    bsdf_pdf_prev = bs->pdf;
    prev = {si->p, si->p_error, si->n, reflect_axis};
    ::new (&ray) Ray(si->spawn(wi));  // in place, as render_tile's camera rays are (renderer.cpp)
    travelled = 0;
    if (bs->transmission) {
      eta_scale *= sqr(bs->eta);
      if constexpr (Media) media.cross(material, entering);
    }

    roulette_due = options.russian_roulette && depth + medium_events >= 1;
    if (beta.is_zero()) break;
    ++depth;
  }
  return L;
}

// path_radiance's four variants for N lanes (see PathFeatures), in the file that expands it.
#define PRISM_INSTANTIATE_PATH_RADIANCE_VARIANT(N, MEDIA, DISPERSION)                                              \
  template SampledSpectrum<N> path_radiance<N, MEDIA, DISPERSION>(const World&, Ray, const SampledWavelengths<N>&, \
                                                                  Sampler&, const PathOptions&, RayCounters&,      \
                                                                  const std::optional<SurfaceInteraction>*);
#define PRISM_INSTANTIATE_PATH_RADIANCE(N)                 \
  PRISM_INSTANTIATE_PATH_RADIANCE_VARIANT(N, false, false) \
  PRISM_INSTANTIATE_PATH_RADIANCE_VARIANT(N, false, true)  \
  PRISM_INSTANTIATE_PATH_RADIANCE_VARIANT(N, true, false)  \
  PRISM_INSTANTIATE_PATH_RADIANCE_VARIANT(N, true, true)

}  // namespace prism
