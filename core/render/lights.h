#pragma once
// Light sources as the renderer samples them: emissive triangles (area lights), point, spot and
// directional lights, and a constant or image environment. Each offers sample_li (a direction
// towards the light from a point, with its solid-angle pdf and the shadow ray to test); the
// environments also give the radiance and pdf of any direction a ray escapes in.

#include <new>
#include <optional>
#include <type_traits>
#include <variant>

#include "core/base/frame.h"
#include "core/base/warp.h"
#include "core/render/environment_map.h"
#include "core/render/interaction.h"
#include "core/render/textured_emission.h"
#include "core/scene/scene.h"
#include "spectral/spectrum.h"

namespace prism {

// The shading point a light is sampled from.
struct LightSampleContext {
  Vec3f p, p_error, n;
  // The hemisphere an opaque surface reflects into (its shading normal on wo's side), or zero
  // when the surface may also transmit: the constant environment samples its cosine there.
  Vec3f reflect_axis{0.f, 0.f, 0.f};
};

template <int N>
struct LightSample {
  SampledSpectrum<N> L;  // radiance arriving along wi (delta lights: irradiance normal to wi)
  Vec3f wi;
  float pdf;  // solid-angle density; 1 for a delta light
  Ray shadow_ray;
  float distance = kInfinity;  // to an area light's point
  float density = 1;           // an area light's: the point's density over the uniform one
};

// A light sample made in the optional its caller keeps (returned by NRVO), its shadow ray made in
// place by make_ray(): built aside and copied in, it was read with wide loads before the narrow
// stores that wrote it had landed, a stalled load in every light sample (as render_tile's camera
// rays were, renderer.cpp).
template <int N, typename MakeRay>
std::optional<LightSample<N>> light_sample(const SampledSpectrum<N>& L, const Vec3f& wi, float pdf,
                                           const MakeRay& make_ray) {
  std::optional<LightSample<N>> s(std::in_place);
  s->L = L, s->wi = wi, s->pdf = pdf;
  ::new (&s->shadow_ray) Ray(make_ray());
  return s;
}

// One emissive triangle, emitting from its front side (or both) its material's radiance,
// uniform or textured, where its alpha leaves it (Material::coverage: 0 where MASK cuts it away,
// alpha of it under BLEND), as a path that hits it counts it.
struct AreaLight {
  Vec3f p0, p1, p2;
  Vec3f n;  // unit front normal
  float area;
  const Material* material;
  const Mesh* mesh;  // triangle `prim` of it, for the texture coordinates and vertex colour
  uint32_t prim;
  bool two_sided;
  const TexturedEmission* texels = nullptr;  // a textured emitter's: points sampled by their light

  template <int N>
  SampledSpectrum<N> radiance(const Vec3f& b, const SampledWavelengths<N>& lambda) const {
    if (!material->emission_texture && material->alpha_mode == AlphaMode::opaque)
      return material->emitted(SurfacePoint{}, lambda);
    const float bary[3] = {b.x, b.y, b.z};
    const SurfacePoint at = mesh->attributes_at(prim, bary);
    return material->emitted(at, lambda) * material->coverage(at);
  }

  bool emits_towards(const Vec3f& w) const { return two_sided || dot(n, w) > 0; }

  // pdf of sampling the direction towards a point at distance d, of the given density over the
  // uniform one: density · d² / (|cos θ_light| · A).
  float pdf_solid_angle(float distance, const Vec3f& w_to_light, float density = 1) const {
    const float cos_l = abs_dot(n, w_to_light);
    return cos_l > 0 ? density * distance * distance / (cos_l * area) : 0.f;
  }
  // sample_point's density at a point p of the triangle, over the uniform one (1 untextured).
  float density_at(const Vec3f& p) const { return texels ? texels->density(barycentrics(p)) : 1.f; }
  Vec3f barycentrics(const Vec3f& p) const {
    const Vec3f e1 = p1 - p0, e2 = p2 - p0, d = p - p0;
    const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), d1 = dot(d, e1), d2 = dot(d, e2);
    const float det = d11 * d22 - d12 * d12;
    const float b1 = det != 0 ? (d22 * d1 - d12 * d2) / det : 0.f, b2 = det != 0 ? (d11 * d2 - d12 * d1) / det : 0.f;
    return {1 - b1 - b2, b1, b2};
  }

  // A point on the triangle, uniform or by a texture's light: its barycentrics b, position p, p's
  // rounding bound, and its density over the uniform one.
  struct Point {
    Vec3f b, p, p_error;
    float density;
  };
  Point sample_point(Vec2f u) const {
    Vec3f b;
    float density = 1;
    if (texels) {
      const auto s = texels->sample(u);
      b = s.b, density = s.density;
    } else {
      b = sample_uniform_triangle(u);
    }
    return {b, p0 * b.x + p1 * b.y + p2 * b.z, (abs(p0 * b.x) + abs(p1 * b.y) + abs(p2 * b.z)) * gamma(6), density};
  }

  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f u,
                                          const SampledWavelengths<N>& lambda) const {
    const Point q = sample_point(u);
    Vec3f wi = q.p - ctx.p;
    const float distance = length(wi);
    if (distance == 0.f) return std::nullopt;
    wi = wi / distance;
    if (!emits_towards(-wi)) return std::nullopt;
    const float pdf = pdf_solid_angle(distance, wi, q.density);
    if (!(pdf > 0.f) || std::isinf(pdf)) return std::nullopt;
    auto s = light_sample(radiance(q.b, lambda), wi, pdf,
                          [&] { return spawn_ray_to(ctx.p, ctx.p_error, ctx.n, q.p, q.p_error, n); });
    s->distance = distance, s->density = q.density;
    return s;
  }
};

struct PointLightSource {
  Vec3f position;
  const Spectrum* intensity;

  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f,
                                          const SampledWavelengths<N>& lambda) const {
    Vec3f wi = position - ctx.p;
    const float d2 = length_squared(wi);
    if (d2 == 0.f) return std::nullopt;
    wi = wi / std::sqrt(d2);
    return light_sample(sample(*intensity, lambda) / d2, wi, 1.f,
                        [&] { return spawn_ray_to(ctx.p, ctx.p_error, ctx.n, position, {}, {}); });
  }
};

// glTF's spot light: intensity I on the axis, scaled by the angular attenuation of
// KHR_lights_punctual, a = clamp(cos θ · scale + offset, 0, 1)² with
// scale = 1 / max(1e-3, cos θ_inner − cos θ_outer) and offset = −cos θ_outer · scale.
struct SpotLightSource {
  PointLightSource point;  // the same source without the cone
  Vec3f direction;         // unit cone axis
  float scale, offset;

  explicit SpotLightSource(const SpotLight& s)
      : point{s.position, &s.intensity},
        direction(s.direction),
        scale(1.f / std::max(1e-3f, std::cos(s.inner_angle) - std::cos(s.outer_angle))),
        offset(-std::cos(s.outer_angle) * scale) {}

  float attenuation(float cos_theta) const { return sqr(clamp(cos_theta * scale + offset, 0.f, 1.f)); }

  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f u,
                                          const SampledWavelengths<N>& lambda) const {
    auto s = point.sample_li(ctx, u, lambda);  // every return names s (see light_sample)
    const float a = s ? attenuation(dot(direction, -s->wi)) : 0.f;
    if (a == 0.f)
      s.reset();
    else
      s->L *= a;
    return s;
  }
};

// Parallel light from infinitely far: irradiance E on a surface facing it, shadow rays unbounded.
struct DirectionalLightSource {
  Vec3f direction;  // unit, the way the light travels
  const Spectrum* illuminance;

  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f,
                                          const SampledWavelengths<N>& lambda) const {
    return light_sample(sample(*illuminance, lambda), -direction, 1.f,
                        [&] { return spawn_ray(ctx.p, ctx.p_error, ctx.n, -direction); });
  }
};

// Constant radiance from every direction. Seen from an opaque surface it is sampled by the cosine
// about the surface's reflection hemisphere, so that a diffuse lobe's f L cos θ / pdf is constant
// and no sample is spent below the surface; otherwise uniformly over the sphere.
struct EnvironmentLight {
  const Spectrum* radiance;

  // `sky`, when given, is the radiance at lambda already (see PathSky).
  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f u, const SampledWavelengths<N>& lambda,
                                          const SampledSpectrum<N>* sky = nullptr) const {
    const bool cosine = ctx.reflect_axis != Vec3f(0.f, 0.f, 0.f);
    const Vec3f wi =
        cosine ? Frame::from_z(ctx.reflect_axis).to_world(sample_cosine_hemisphere(u)) : sample_uniform_sphere(u);
    const float pdf = pdf_li(wi, ctx.reflect_axis);
    if (!(pdf > 0)) return std::nullopt;
    return light_sample(Le(wi, lambda, sky), wi, pdf, [&] { return spawn_ray(ctx.p, ctx.p_error, ctx.n, wi); });
  }
  template <int N>
  SampledSpectrum<N> Le(const Vec3f&, const SampledWavelengths<N>& lambda,
                        const SampledSpectrum<N>* sky = nullptr) const {
    return sky ? *sky : sample(*radiance, lambda);
  }
  // The pdf of sample_li from a point of that reflect_axis.
  float pdf_li(const Vec3f& w, const Vec3f& reflect_axis = {0.f, 0.f, 0.f}) const {
    if (reflect_axis == Vec3f(0.f, 0.f, 0.f)) return uniform_sphere_pdf();
    return cosine_hemisphere_pdf(std::max(0.f, dot(w, reflect_axis)));
  }
};

// An environment image, importance-sampled by luminance. Each lookup's RGB becomes an
// illuminant spectrum as RGB emission does, over the map's white (the upsampling table lookup is
// cheap).
struct EnvironmentMapLight {
  const EnvironmentMap* map;

  template <int N>
  std::optional<LightSample<N>> sample_li(const LightSampleContext& ctx, Vec2f u,
                                          const SampledWavelengths<N>& lambda) const {
    const auto s = map->sample(u);
    if (!s) return std::nullopt;
    return light_sample(Le(s->w, lambda), s->w, s->pdf, [&] { return spawn_ray(ctx.p, ctx.p_error, ctx.n, s->w); });
  }
  template <int N>
  SampledSpectrum<N> Le(const Vec3f& w, const SampledWavelengths<N>& lambda) const {
    const RgbIlluminantSpectrum L(map->radiance(w), map->white());
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) r[i] = L(lambda[i]);
    return r;
  }
  float pdf_li(const Vec3f& w) const { return map->pdf(w); }
};

using Light = std::variant<AreaLight, PointLightSource, SpotLightSource, DirectionalLightSource, EnvironmentLight,
                           EnvironmentMapLight>;

inline bool is_delta(const Light& light) {
  return std::holds_alternative<PointLightSource>(light) || std::holds_alternative<SpotLightSource>(light) ||
         std::holds_alternative<DirectionalLightSource>(light);
}

// A path's wavelengths are fixed when it starts, and a constant environment's radiance is the same
// in every direction: the path tracer finds it once per path, not at every escaped ray and light
// sample. Holds nothing for the other lights.
template <int N>
class PathSky {
 public:
  PathSky(const Light* environment, const SampledWavelengths<N>& lambda) {
    const auto* constant = environment ? std::get_if<EnvironmentLight>(environment) : nullptr;
    if (constant) radiance_ = sample(*constant->radiance, lambda), known_ = true;
  }
  // The constant environment's radiance at the path's wavelengths, or null.
  const SampledSpectrum<N>* radiance() const { return known_ ? &radiance_ : nullptr; }

 private:
  SampledSpectrum<N> radiance_;
  bool known_ = false;
};

template <int N>
std::optional<LightSample<N>> sample_li(const Light& light, const LightSampleContext& ctx, Vec2f u,
                                        const SampledWavelengths<N>& lambda, const PathSky<N>* sky = nullptr) {
  return std::visit(
      [&](const auto& l) {
        if constexpr (std::is_same_v<std::decay_t<decltype(l)>, EnvironmentLight>)
          return l.sample_li(ctx, u, lambda, sky ? sky->radiance() : nullptr);
        else
          return l.sample_li(ctx, u, lambda);
      },
      light);
}

// Radiance arriving along a ray that escaped the scene in direction w, and the solid-angle pdf
// of sample_li choosing w, for an environment light (either kind).
template <int N>
SampledSpectrum<N> environment_Le(const Light& environment, const Vec3f& w, const SampledWavelengths<N>& lambda,
                                  const PathSky<N>* sky = nullptr) {
  if (const auto* map = std::get_if<EnvironmentMapLight>(&environment)) return map->Le(w, lambda);
  return std::get<EnvironmentLight>(environment).Le(w, lambda, sky ? sky->radiance() : nullptr);
}
// The pdf of sample_li towards w from a point of that reflect_axis (see LightSampleContext).
inline float environment_pdf(const Light& environment, const Vec3f& w, const Vec3f& reflect_axis = {0.f, 0.f, 0.f}) {
  if (const auto* map = std::get_if<EnvironmentMapLight>(&environment)) return map->pdf_li(w);
  return std::get<EnvironmentLight>(environment).pdf_li(w, reflect_axis);
}

}  // namespace prism
