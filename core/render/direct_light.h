#pragma once
// Light arriving at a surface point from one sample of one light, shadow ray included; the
// integrators weight it (MIS in the path tracer, plainly in the Whitted tracer).

#include <optional>

#include "core/base/frame.h"
#include "core/render/ray_counters.h"
#include "core/render/world.h"
#include "materials/bsdf.h"

namespace prism {

template <int N>
struct LightContribution {
  SampledSpectrum<N> f_L;  // f(wo, wi) · L_i · |cos θ_i| · transmittance, not yet divided by the pdf
  float light_pdf;         // solid-angle pdf of the light sample (1 for a point light)
  float bsdf_pdf;          // the BSDF's pdf of sampling the same direction (DispersiveBsdf: p̄)
  Vec3f wi;                // towards the light (world)
  float distance;          // to it along wi (the shadow ray's length; ∞ for a light at infinity)
};

// A direction must be on the side of the geometric surface that the lobe scattering into it
// says: wo's side for reflection, the other side for transmission. Shading normals can disagree,
// and would then leak light through the surface (Veach 1997, §5.3).
inline bool wrong_side(const SurfaceInteraction& si, const Vec3f& wi, bool transmission) {
  const bool crosses = dot(wi, si.n) * dot(si.wo, si.n) <= 0;
  return crosses != transmission;
}

// `bsdf` is a Bsdf<N> or a DispersiveBsdf<N> (anything bsdf_eval takes).
template <int N, class B>
std::optional<LightContribution<N>> light_contribution(const World& world, const SurfaceInteraction& si,
                                                       const Frame& frame, const B& bsdf, const Vec3f& wo,
                                                       const Light& light, Vec2f u, const SampledWavelengths<N>& lambda,
                                                       RayCounters& counters,
                                                       const Vec3f& reflect_axis = {0.f, 0.f, 0.f},
                                                       const PathSky<N>* sky = nullptr) {
  auto sample = sample_li(light, LightSampleContext{si.p, si.p_error, si.n, reflect_axis}, u, lambda, sky);
  if (!sample || sample->L.is_zero()) return std::nullopt;
  const Vec3f wi = frame.to_local(sample->wi);
  const bool transmission = wi.z * wo.z < 0;
  if (wrong_side(si, sample->wi, transmission)) return std::nullopt;
  if (transmission && !si.material->transmits()) return std::nullopt;  // it only reflects
  // The shadow ray before the BSDF (as Mitsuba 3): a blocked sample then costs no evaluation, and
  // in a scene with occluders many light samples are blocked (a layered BSDF costs more to evaluate
  // than a shadow ray). One into the closed object it leaves, towards a light outside it, is
  // blocked by that object without being traced.
  if (world.meets_own_surface(si, sample->shadow_ray)) return std::nullopt;
  ++counters.shadow;
  sample->shadow_ray.skip_instance = si.skip_towards(sample->wi);
  const float T = world.transmittance(sample->shadow_ray);
  if (T == 0) return std::nullopt;
  const BsdfEval<N> e = bsdf_eval(bsdf, wo, wi);
  const SampledSpectrum<N> f = e.f * abs_cos_theta(wi);
  if (f.is_zero()) return std::nullopt;
  return LightContribution<N>{f * sample->L * T, sample->pdf, e.pdf, sample->wi, sample->shadow_ray.tmax};
}

}  // namespace prism
