#include "materials/specular_albedo.h"

#include <limits>

#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace prism {

using namespace albedo_tables;

namespace {

bool smooth(const SpecularAlbedo::Roughness& r) { return TrowbridgeReitz::effectively_smooth(r.alpha); }

Point point(float mu, const SpecularAlbedo::Roughness& r) { return albedo_tables::point(mu, Lerp{r.a, r.ta}); }

const Grid& reflection(int h, bool compensated) { return compensated ? specular[h].r_compensated : specular[h].r; }

}  // namespace

SpecularAlbedo::Roughness SpecularAlbedo::roughness(float alpha) {
  // The lobes of one material (metal, dielectric, the diffuse coupling) ask for the same α in a
  // row at every hit; the last answer is kept per thread, as the cube root costs ~100 instructions.
  thread_local Roughness last{std::numeric_limits<float>::quiet_NaN(), 0, 0.f};
  if (alpha != last.alpha) {
    const Lerp a = alpha_node(alpha);
    last = {alpha, a.i, a.t};
  }
  return last;
}

const SpecularAlbedo& SpecularAlbedo::table() {
  static const SpecularAlbedo t;
  return t;
}

float SpecularAlbedo::E(float mu, const Roughness& r, float eta, bool compensated) const {
  if (smooth(r)) return fresnel_dielectric(mu, eta);
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, r);
  return (1 - h.t) * reflection(h.i, compensated).at(p) + h.t * reflection(h.i + 1, compensated).at(p);
}

float SpecularAlbedo::average(const Roughness& r, float eta, bool compensated) const {
  const Lerp h = locate_eta(eta);
  const Lerp a{r.a, r.ta};
  return (1 - h.t) * reflection(h.i, compensated).average(a) + h.t * reflection(h.i + 1, compensated).average(a);
}

float SpecularAlbedo::interface(float mu, const Roughness& r, float eta) const {
  if (smooth(r)) return 1.f;
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, r);
  return (1 - h.t) * specular[h.i].rt.at(p) + h.t * specular[h.i + 1].rt.at(p);
}

float SpecularAlbedo::white(float mu, const Roughness& r) const {
  return smooth(r) ? 1.f : specular_white.at(point(mu, r));
}

float SpecularAlbedo::white_average(float alpha) const {
  const Roughness r = roughness(alpha);
  return specular_white.average({r.a, r.ta});
}

}  // namespace prism
