#include "materials/specular_albedo.h"

#include <algorithm>
#include <cmath>

#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace prism {

namespace {

constexpr float kMaxX = 0.5f;  // x = (η − 1)/(η + 1) = 1/2 at η = 3

float eta_of(float x) { return (1 + x) / (1 - x); }

// E(μ) by stratified visible-normal sampling: each sample's weight is F(wo·m) G(wo, wi)/G1(wo).
float directional_albedo(float mu, float alpha, float eta) {
  if (TrowbridgeReitz::effectively_smooth(alpha)) return fresnel_dielectric(mu, eta);
  const TrowbridgeReitz d(alpha);
  const Vec3f wo(std::sqrt(std::max(0.f, 1 - mu * mu)), 0, mu);
  constexpr int kStrata = 24;
  double sum = 0;
  for (int i = 0; i < kStrata; ++i)
    for (int j = 0; j < kStrata; ++j) {
      const Vec3f wm = d.sample_visible_normal(wo, {(i + 0.5f) / kStrata, (j + 0.5f) / kStrata});
      const Vec3f wi = reflect(wo, wm);
      if (wi.z <= 0) continue;
      sum += fresnel_dielectric(dot(wo, wm), eta) * d.G(wo, wi) / d.G1(wo);
    }
  return float(sum / (kStrata * kStrata));
}

// Linear interpolation weights of v on a uniform grid of n nodes over [0, hi].
struct Lerp {
  int i;
  float t;
};
Lerp locate(float v, float hi, int n) {
  const float x = std::clamp(v / hi, 0.f, 1.f) * float(n - 1);
  const int i = std::min(int(x), n - 2);
  return {i, x - float(i)};
}

}  // namespace

SpecularAlbedo::SpecularAlbedo() : e_(size_t(kEta) * kAlpha * kMu), e_avg_(size_t(kEta) * kAlpha) {}

const SpecularAlbedo& SpecularAlbedo::table() {
  static const SpecularAlbedo t;
  return t;
}

void SpecularAlbedo::compute_slice(int h) const {
  const float eta = eta_of(kMaxX * float(h) / (kEta - 1));
  for (int a = 0; a < kAlpha; ++a)
    for (int m = 0; m < kMu; ++m) {
      // Nodes uniform in √μ, dense where E changes fastest (grazing); μ = 0 itself is never
      // met, a grazing neighbour stands in.
      const float mu = std::max(sqr(float(m) / (kMu - 1)), 1e-4f);
      e_[(size_t(h) * kAlpha + a) * kMu + m] = directional_albedo(mu, sqr(float(a) / (kAlpha - 1)), eta);
    }
  // E_avg of exactly the function E() returns (the exact Fresnel when smooth, the interpolated
  // table otherwise), so that the coupled diffuse lobe's albedo is exactly (1 − E(μ_o)) ρ.
  constexpr int kSteps = 1024;
  for (int a = 0; a < kAlpha; ++a) {
    const float alpha = sqr(float(a) / (kAlpha - 1));
    double avg = 0;
    for (int k = 0; k < kSteps; ++k) {
      const float mu = (k + 0.5f) / kSteps;
      const float e = TrowbridgeReitz::effectively_smooth(alpha) ? fresnel_dielectric(mu, eta) : slice_E(h, mu, alpha);
      avg += 2.0 * e * mu / kSteps;
    }
    e_avg_[size_t(h) * kAlpha + a] = float(avg);
  }
}

const float* SpecularAlbedo::slice(int h) const {
  std::call_once(ready_[h], [this, h] { compute_slice(h); });
  return &e_[size_t(h) * kAlpha * kMu];
}

float SpecularAlbedo::slice_E(int h, float mu, float alpha) const {
  const float* e = &e_[size_t(h) * kAlpha * kMu];
  const Lerp a = locate(std::sqrt(alpha), 1, kAlpha), m = locate(std::sqrt(std::max(mu, 0.f)), 1, kMu);
  float r = 0;
  for (int k = 0; k < 4; ++k) {
    const int da = k & 1, dm = k >> 1;
    r += (da ? a.t : 1 - a.t) * (dm ? m.t : 1 - m.t) * e[(a.i + da) * kMu + (m.i + dm)];
  }
  return r;
}

float SpecularAlbedo::E(float mu, float alpha, float eta) const {
  if (TrowbridgeReitz::effectively_smooth(alpha)) return fresnel_dielectric(mu, eta);
  const Lerp h = locate((eta - 1) / (eta + 1), kMaxX, kEta);
  slice(h.i), slice(h.i + 1);
  return (1 - h.t) * slice_E(h.i, mu, alpha) + h.t * slice_E(h.i + 1, mu, alpha);
}

float SpecularAlbedo::average(float alpha, float eta) const {
  const Lerp h = locate((eta - 1) / (eta + 1), kMaxX, kEta), a = locate(std::sqrt(alpha), 1, kAlpha);
  slice(h.i), slice(h.i + 1);
  float r = 0;
  for (int k = 0; k < 4; ++k) {
    const int dh = k & 1, da = k >> 1;
    r += (dh ? h.t : 1 - h.t) * (da ? a.t : 1 - a.t) * e_avg_[size_t(h.i + dh) * kAlpha + (a.i + da)];
  }
  return r;
}

}  // namespace prism
