#pragma once
// One camera sample of a pixel: its camera ray, its wavelengths, the integrator's estimate of the
// radiance they carry, and what the film keeps of it (CIE XYZ; with AOVs, what the first surface
// shows). The sampler's first dimension jitters the ray in the pixel, the next picks a thin lens's
// aperture point (a pinhole draws none), the next draws the wavelengths, and the integrator takes
// the rest.

#include <new>
#include <optional>

#include "core/base/sampler.h"
#include "core/render/camera.h"
#include "core/render/film.h"
#include "core/render/integrators.h"
#include "spectral/cie.h"

namespace prism {

template <int N>
struct CameraSample {
  SampledWavelengths<N> lambda;
  SampledSpectrum<N> L;
  Xyz xyz;
};

// The camera ray of sample s of a pixel: the sampler's first dimension jitters it in the pixel,
// and a thin lens's aperture point is the next.
inline Ray camera_ray(const Camera& camera, Sampler& sampler, Vec2i pixel, int s) {
  sampler.start_sample(s);
  const Vec2f jitter = sampler.get_2d();
  const Vec2f lens = camera.has_lens() ? sampler.get_2d() : Vec2f{};
  return camera.generate_ray(float(pixel.x) + jitter.x, float(pixel.y) + jitter.y, lens);
}

// A sample's camera ray (camera_ray) through the radiance estimator to CIE XYZ, from the sampler's
// stream for (pixel, sample index, seed) alone, the sampler started at the sample and past its
// jitter. Its wavelengths are the sampler's, or VCM's iteration's when given (`iteration_lambda`).
// With a constant sky (sky_xyz), the camera ray is traced here first, and a ray that leaves the
// scene at once gives nothing (false): its value is the sky's. The sample is written into `c`, the
// caller's: returned, it was copied there by wide loads of its xyz's narrow stores, which x86
// cannot forward (a stall per sample).
template <int N>
bool camera_sample(const EstimateContext<N>& context, RadianceFn<N> radiance,
                   const SampledWavelengths<N>* iteration_lambda, const std::optional<Xyz>& sky, Sampler& sampler,
                   const Ray& ray, RayCounters& rays, CameraSample<N>& c) {
  const std::optional<SurfaceInteraction> first =
      sky ? context.world.intersect(ray, true) : std::nullopt;  // as path_radiance would
  if (sky && !first) {
    ++rays.primary;
    return false;
  }
  const Vec2f u_lambda = sampler.get_2d();  // the camera's second dimension, drawn only for a path that needs it
  // (Made in place, as the renderer's camera rays are, for the same reason.)
  ::new (&c.lambda)
      SampledWavelengths<N>(iteration_lambda ? *iteration_lambda : SampledWavelengths<N>::sample(u_lambda));
  c.L = radiance(context, ray, c.lambda, sampler, rays, sky ? &first : nullptr);
  c.xyz = to_xyz(c.L, c.lambda);
  return true;
}

// What the first surface along a camera ray shows: its albedo under D65 (as XYZ, converted like
// the image), shading normal and distance.
template <int N>
void first_hit(const World& world, const Ray& ray, const SampledWavelengths<N>& lambda, FilmSample& out) {
  const auto si = world.intersect(ray);
  if (!si) return;
  const Material& m = *si->material;
  SampledSpectrum<N> albedo;
  if (const auto* d = std::get_if<DiffuseMaterial>(&m.kind)) {
    albedo = sample(d->reflectance, lambda);
  } else {
    const PbrMaterial& pbr = std::get<PbrMaterial>(m.kind);
    const Rgb base_color = pbr.inputs(si->at).base_color;
    if (pbr.base_reflectance) {
      albedo = pbr.base_spectrum(base_color, RgbAlbedoSpectrum(base_color), lambda);
    } else {
      const RgbAlbedoSpectrum base(base_color);
      for (int i = 0; i < N; ++i) albedo[i] = base(lambda[i]);
    }
  }
  for (int i = 0; i < N; ++i) albedo[i] *= cie().d65(lambda[i]);
  out.albedo = to_xyz(albedo, lambda);
  out.normal = si->ns;
  out.depth = si->t;
  out.hit = true;
}

}  // namespace prism
