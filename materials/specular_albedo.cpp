#include "materials/specular_albedo.h"

#include "base/kept_per_thread.h"
#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace prism {

using namespace albedo_tables;

namespace {

bool smooth(const SpecularAlbedo::Roughness& r) { return TrowbridgeReitz::effectively_smooth(r.alpha); }

}  // namespace

SpecularAlbedo::Roughness SpecularAlbedo::roughness(float alpha) {
  // The lobes of a material (metal, dielectric, coat, the diffuse coupling) ask for the same few α
  // at every hit, a path's hits alternating between materials: the cube root costs ~100 instructions.
  return kept_per_thread(alpha, [](float a) {
    const Lerp x = alpha_node(a);
    return Roughness{a, x.i, x.t};
  });
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

void SpecularAlbedo::average(const Roughness& r, int first, int last, bool compensated, std::span<float> out) const {
  const Lerp a{r.a, r.ta};
  for (int h = first; h <= last; ++h) out[h - first] = reflection(h, compensated).average(a);
}

float SpecularAlbedo::interface(float mu, const Roughness& r, float eta) const {
  if (smooth(r)) return 1.f;
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, r);
  return (1 - h.t) * specular[h.i].rt.at(p) + h.t * specular[h.i + 1].rt.at(p);
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
