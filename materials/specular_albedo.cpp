#include "materials/specular_albedo.h"

#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace prism {

using namespace albedo_tables;

const SpecularAlbedo& SpecularAlbedo::table() {
  static const SpecularAlbedo t;
  return t;
}

float SpecularAlbedo::E(float mu, float alpha, float eta, bool compensated) const {
  if (TrowbridgeReitz::effectively_smooth(alpha)) return fresnel_dielectric(mu, eta);
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, alpha);
  const auto grid = [&](int i) -> const Grid& { return compensated ? specular[i].r_compensated : specular[i].r; };
  return (1 - h.t) * grid(h.i).at(p) + h.t * grid(h.i + 1).at(p);
}

float SpecularAlbedo::average(float alpha, float eta, bool compensated) const {
  const Lerp h = locate_eta(eta);
  const auto grid = [&](int i) -> const Grid& { return compensated ? specular[i].r_compensated : specular[i].r; };
  return (1 - h.t) * grid(h.i).average(alpha) + h.t * grid(h.i + 1).average(alpha);
}

float SpecularAlbedo::interface(float mu, float alpha, float eta) const {
  if (TrowbridgeReitz::effectively_smooth(alpha)) return 1.f;
  const Lerp h = locate_eta(eta);
  const Point p = point(mu, alpha);
  return (1 - h.t) * specular[h.i].rt.at(p) + h.t * specular[h.i + 1].rt.at(p);
}

float SpecularAlbedo::white(float mu, float alpha) const {
  return TrowbridgeReitz::effectively_smooth(alpha) ? 1.f : specular_white.at(point(mu, alpha));
}

float SpecularAlbedo::white_average(float alpha) const { return specular_white.average(alpha); }

}  // namespace prism
