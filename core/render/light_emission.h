#pragma once
// Lights as emitters of light paths (bidirectional methods): sample_le picks a point and a
// direction leaving the light with their densities (pdf_pos, pdf_dir), and pdf_le gives the same
// densities for a given emission, so that MIS can weigh emission against the other strategies
// (pbrt-v4 §12 SampleLe/PDF_Le; Georgiev et al. 2012's emissionPdfW and directPdfA). Infinite
// lights (directional, environment) emit through a disk of the scene's bounding radius facing
// the direction of travel.

#include <optional>

#include "core/render/lights.h"
#include "materials/bsdf_sample.h"

namespace prism {

// The disk that parallel light enters the scene through: the bounding sphere's centre and radius.
struct SceneDisk {
  Vec3f center;
  float radius;
  float pdf() const { return 1.f / (kPi * radius * radius); }
  // A point of the disk facing direction d (unit), on the side light comes from.
  Vec3f point(const Vec3f& d, Vec2f u) const {
    const Frame f = Frame::from_z(d);
    const Vec2f q = sample_uniform_disk_concentric(u) * radius;
    return center - d * radius + f.x * q.x + f.y * q.y;
  }
};

template <int N>
struct EmissionSample {
  SampledSpectrum<N> Le;   // radiance (point, spot: intensity; directional: irradiance normal to the ray)
  Ray ray;                 // leaving the light
  float pdf_pos, pdf_dir;  // area (or disk) density of the origin; solid-angle density of the direction
  float cos_light;         // |cos| of the direction at an area light; 1 for the others
};

// The densities pdf_le reports: pdf_pos · pdf_dir is the emission density of one direction w (the
// way light travels) from the light's point, with cos_light as in EmissionSample.
struct EmissionPdf {
  float pdf_pos, pdf_dir;
  float product() const { return pdf_pos * pdf_dir; }
};

inline bool is_infinite(const Light& light) {
  return std::holds_alternative<DirectionalLightSource>(light) || std::holds_alternative<EnvironmentLight>(light) ||
         std::holds_alternative<EnvironmentMapLight>(light);
}

// The cosine of a spot light's outer cone (attenuation zero beyond it).
inline float spot_cos_outer(const SpotLightSource& s) { return -s.offset / s.scale; }
inline float uniform_cone_pdf(float cos_max) { return 1.f / (2.f * kPi * (1.f - cos_max)); }

template <int N>
std::optional<EmissionSample<N>> sample_le(const Light& light, Vec2f u_pos, Vec2f u_dir,
                                           const SampledWavelengths<N>& lambda, const SceneDisk& disk) {
  using Sample = std::optional<EmissionSample<N>>;
  if (const auto* a = std::get_if<AreaLight>(&light)) {
    // Uniform on the triangle, cosine-weighted about the emitting side (either, for two sides).
    const auto [b, p, p_error, density] = a->sample_point(u_pos);
    Vec3f n = a->n;
    float side_pdf = 1.f;
    if (a->two_sided) {  // the side chosen by u_dir.x, as a BSDF chooses its lobe
      side_pdf = 0.5f;
      const bool back = u_dir.x >= 0.5f;
      u_dir.x = within_lobe(u_dir.x, back ? 0.5f : 0.f, 0.5f);
      if (back) n = -n;
    }
    const Vec3f local = sample_cosine_hemisphere(u_dir);
    const Vec3f w = Frame::from_z(n).to_world(local);
    const float pdf_dir = cosine_hemisphere_pdf(local.z) * side_pdf;
    if (!(pdf_dir > 0.f)) return std::nullopt;
    return Sample{{a->radiance(b, lambda), spawn_ray(p, p_error, n, w), density / a->area, pdf_dir, local.z}};
  }
  if (const auto* pt = std::get_if<PointLightSource>(&light))
    return Sample{{sample(*pt->intensity, lambda), Ray{pt->position, sample_uniform_sphere(u_dir), kInfinity}, 1.f,
                   uniform_sphere_pdf(), 1.f}};
  if (const auto* s = std::get_if<SpotLightSource>(&light)) {
    // Uniform in the outer cone, weighted by the cone's attenuation.
    const float cos_max = spot_cos_outer(*s);
    const float cos_t = 1.f - u_dir.x * (1.f - cos_max), sin_t = safe_sqrt(1.f - cos_t * cos_t);
    const float phi = 2.f * kPi * u_dir.y;
    const Vec3f w = Frame::from_z(s->direction).to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
    return Sample{{sample(*s->point.intensity, lambda) * s->attenuation(cos_t), Ray{s->point.position, w, kInfinity},
                   1.f, uniform_cone_pdf(cos_max), 1.f}};
  }
  if (const auto* d = std::get_if<DirectionalLightSource>(&light))
    return Sample{{sample(*d->illuminance, lambda), Ray{disk.point(d->direction, u_pos), d->direction, kInfinity},
                   disk.pdf(), 1.f, 1.f}};
  // Environments: a direction w towards the sky as direct lighting samples it, travelling −w.
  Vec3f w;
  float pdf_dir;
  if (const auto* m = std::get_if<EnvironmentMapLight>(&light)) {
    const auto s = m->map->sample(u_dir);
    if (!s || !(s->pdf > 0.f)) return std::nullopt;
    w = s->w, pdf_dir = s->pdf;
  } else {
    w = sample_uniform_sphere(u_dir), pdf_dir = uniform_sphere_pdf();
  }
  return Sample{
      {environment_Le(light, w, lambda), Ray{disk.point(-w, u_pos), -w, kInfinity}, disk.pdf(), pdf_dir, 1.f}};
}

// The densities of sample_le emitting along w (unit, the way light travels) from the light's
// point; for an area light, from a point of its surface of that density over the uniform one.
inline EmissionPdf pdf_le(const Light& light, const Vec3f& w, const SceneDisk& disk, float density = 1) {
  if (const auto* a = std::get_if<AreaLight>(&light)) {
    if (!a->emits_towards(w)) return {0.f, 0.f};
    return {density / a->area, cosine_hemisphere_pdf(abs_dot(a->n, w)) * (a->two_sided ? 0.5f : 1.f)};
  }
  if (std::holds_alternative<PointLightSource>(light)) return {1.f, uniform_sphere_pdf()};
  if (const auto* s = std::get_if<SpotLightSource>(&light)) {
    const float cos_max = spot_cos_outer(*s);
    return {1.f, dot(s->direction, w) >= cos_max ? uniform_cone_pdf(cos_max) : 0.f};
  }
  if (std::holds_alternative<DirectionalLightSource>(light)) return {disk.pdf(), 1.f};
  return {disk.pdf(), environment_pdf(light, -w)};
}

}  // namespace prism
