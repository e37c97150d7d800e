#include "materials/specular_albedo.h"

#include "core/base/per_thread_cache.h"
#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace prism {

using namespace albedo_tables;

SpecularAlbedo::Roughness SpecularAlbedo::roughness(float alpha) {
  // The lobes of a material (metal, dielectric, coat, the diffuse coupling) ask for the same few α
  // at every hit, a path's hits alternating between materials, and finding α's node takes a cube
  // root, which costs more than the look-up.
  return per_thread_cached(alpha, [](float a) {
    const Lerp x = alpha_node(a);
    return Roughness{a, x.i, x.t};
  });
}

SpecularAlbedo::AlphaSlice SpecularAlbedo::slice_of(float alpha, bool compensated) {
  const Lerp a = alpha_node(alpha);
  const auto at = [&](const Grid& g, int m) { return (1 - a.t) * g.e[a.i * kMu + m] + a.t * g.e[(a.i + 1) * kMu + m]; };
  AlphaSlice s{};
  for (int h = 0; h < kEta; ++h) {
    for (int m = 0; m < kMu; ++m) s.e[m][h] = at(reflection(h, compensated), m);
    s.average[h] = reflection(h, compensated).average(a);
  }
  for (int m = 0; m < kMu; ++m) s.white[m] = at(specular_white, m);
  return s;
}

const SpecularAlbedo::AlphaSlice& SpecularAlbedo::alpha_slice(float alpha, bool compensated) {
  // A material's few α recur at every hit; one store for each of compensated or not.
  return compensated ? per_thread_cached_ref<4>(alpha, [](float a) { return slice_of(a, true); })
                     : per_thread_cached_ref<4>(alpha, [](float a) { return slice_of(a, false); });
}

const SpecularAlbedo& SpecularAlbedo::table() {
  static const SpecularAlbedo t;
  return t;
}

SpecularAlbedo::Curve SpecularAlbedo::curve(const Roughness& r, float eta, bool compensated) const {
  const Index h = index(eta);
  const Grid &below = reflection(h.h, compensated), &above = reflection(h.h + 1, compensated);
  // The four (α, η) corners' rows over μ, weighted bilinearly: one pass over contiguous nodes (SIMD).
  const float* rows[4] = {&below.e[r.a * kMu], &below.e[(r.a + 1) * kMu], &above.e[r.a * kMu],
                          &above.e[(r.a + 1) * kMu]};
  const float w[4] = {(1 - h.t) * (1 - r.ta), (1 - h.t) * r.ta, h.t * (1 - r.ta), h.t * r.ta};
  Curve c;
  for (int m = 0; m < kMu; ++m) c.e[m] = w[0] * rows[0][m] + w[1] * rows[1][m] + w[2] * rows[2][m] + w[3] * rows[3][m];
  const Lerp a{r.a, r.ta};
  c.average = (1 - h.t) * below.average(a) + h.t * above.average(a);
  c.eta = eta;
  c.smooth = smooth(r);
  return c;
}

float SpecularAlbedo::interface(float mu, const Roughness& r, float eta) const {
  if (smooth(r)) return 1.f;
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, r);
  return (1 - h.t) * specular[h.i].rt.at(p) + h.t * specular[h.i + 1].rt.at(p);
}

float SpecularAlbedo::valid(float mu, const Roughness& r, float eta) const {
  if (smooth(r)) return 1.f;
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, r);
  return (1 - h.t) * specular[h.i].valid.at(p) + h.t * specular[h.i + 1].valid.at(p);
}

float SpecularAlbedo::white_valid(float mu, const Roughness& r) const {
  return smooth(r) ? 1.f : specular_white_valid.at(point(mu, r));
}

void SpecularAlbedo::interface(const Direction& d, int first, int last, std::span<float> out) const {
  const Point p = point(d);
  for (int h = first; h <= last; ++h) out[h - first] = specular[h].rt.at(p);
}

float SpecularAlbedo::white_average(const Roughness& r) const { return specular_white.average({r.a, r.ta}); }

float SpecularAlbedo::white(float mu, const Roughness& r) const {
  return smooth(r) ? 1.f : specular_white.at(point(mu, r));
}

}  // namespace prism
