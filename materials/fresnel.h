#pragma once
// Reflection and refraction at a smooth interface, and the Fresnel equations:
//   dielectric: exact unpolarised reflectance with total internal reflection (R + T = 1);
//   conductor:  exact reflectance for a complex relative index η = n + ik.
// Convention (pbrt-v4): η = n_t / n_i is the index of the side opposite the normal over the
// index of the normal's side, and cos θ_i > 0 when the incident direction is on the normal's
// side; a negative cos θ_i means the light arrives from the other side and η is inverted.

#include <cmath>
#include <optional>

#include "core/base/vec.h"

namespace prism {

// Mirror direction of w about the normal n (both unit; w points away from the surface).
inline Vec3f reflect(const Vec3f& w, const Vec3f& n) { return -w + n * (2 * dot(w, n)); }

struct Refraction {
  Vec3f wt;     // transmitted direction, unit
  float eta_p;  // the η that applied: η, or 1/η when w was on the other side of n
};

// Snell's law in vector form (Hecht, "Optics", §4.3; pbrt-v4 §9.3.2): with η cos θ_t = g,
// g² = η² − 1 + cos²θ_i (sin²θ_t = sin²θ_i / η²), w_t = −w/η + (cos θ_i − g)/η n. Returns nothing
// on total internal reflection (g² ≤ 0).
inline std::optional<Refraction> refract(const Vec3f& w, Vec3f n, float eta) {
  double cos_i = std::clamp(double(dot(n, w)), -1.0, 1.0), e = eta;
  if (cos_i < 0) {
    e = 1 / e;
    cos_i = -cos_i;
    n = -n;
  }
  if (e == 1) return Refraction{-w, float(e)};  // index-matched: straight through
  // In double, exactly as fresnel_dielectric_polarized decides total internal reflection, so that
  // R = 1 − T holds to the last bit near the critical angle.
  const double g2 = e * e - 1 + cos_i * cos_i;
  if (g2 <= 0) return std::nullopt;
  const Vec3d wt = (-Vec3d(w) + Vec3d(n) * (cos_i - std::sqrt(g2))) / e;
  return Refraction{Vec3f(normalize(wt)), float(e)};
}

// Reflectance of s- (⊥) and p- (∥) polarised light and their average, the unpolarised R.
struct FresnelReflectance {
  float R, Rs, Rp;
};

// Fresnel equations for a dielectric interface (Born & Wolf, "Principles of Optics", §1.5.3):
//   r⊥ = (cos θ_i − η cos θ_t) / (cos θ_i + η cos θ_t),  r∥ = (η cos θ_i − cos θ_t) / (η cos θ_i + cos θ_t),
// with η cos θ_t = g = √(η² − 1 + cos²θ_i) and r∥ multiplied through by η (Walter et al. 2007,
// eq. 22): r⊥ = (c − g)/(c + g), r∥ = (η² c − g)/(η² c + g), c = cos θ_i; no division before the
// square root. Computed in double: stable for η from 1e-3 to 1e3 and cos θ_i ∈ [−1, 1]; R = 0
// exactly for an index-matched interface and R = 1 under total internal reflection (g² ≤ 0).
inline FresnelReflectance fresnel_dielectric_polarized(float cos_theta_i, float eta) {
  double c = std::clamp(double(cos_theta_i), -1.0, 1.0), e = eta;
  if (c < 0) {
    e = 1 / e;
    c = -c;
  }
  if (e == 1) return {0, 0, 0};
  const double e2 = e * e, g2 = e2 - 1 + c * c;
  if (g2 <= 0) return {1, 1, 1};
  const double g = std::sqrt(g2);
  const double r_s = (c - g) / (c + g), r_p = (e2 * c - g) / (e2 * c + g);
  const double Rs = r_s * r_s, Rp = r_p * r_p;
  return {float((Rs + Rp) / 2), float(Rs), float(Rp)};
}

inline float fresnel_dielectric(float cos_theta_i, float eta) {
  return fresnel_dielectric_polarized(cos_theta_i, eta).R;
}

// Fresnel equations with a complex relative index η = n + ik (Born & Wolf §14.2): the same
// amplitudes as above with complex cos θ_t = sqrt(1 − sin²θ_i / η²). Exact, not the usual
// approximation in n, k and cos θ. cos θ_i is taken on the incident side (|cos θ_i|).
// In real arithmetic (pbrt-v3's FrConductor; Lagarde 2013, "Memo on Fresnel equations"): with
// η² cos²θ_t = (a + ib)², a² + b² = |n² − k² − sin²θ + 2ink| and a² = (a² + b² + n² − k² − sin²θ)/2,
//   R⊥ = (a² + b² − 2a cos θ + cos²θ) / (a² + b² + 2a cos θ + cos²θ),
//   R∥ = R⊥ (cos²θ (a² + b²) − 2a cos θ sin²θ + sin⁴θ) / (cos²θ (a² + b²) + 2a cos θ sin²θ + sin⁴θ).
// A vanishing denominator (grazing onto an index-matched k = 0 surface) is the grazing limit, R = 1.
// Branch-free (selects, not jumps), so that a loop over a spectrum's lanes runs as vector code.
inline FresnelReflectance fresnel_conductor_polarized(float cos_theta_i, float n, float k) {
  const double c = std::min(1.0, std::abs(double(cos_theta_i))), c2 = c * c, s2 = 1 - c2;
  const double n2 = double(n) * n, k2 = double(k) * k, t0 = n2 - k2 - s2;
  const double a2b2 = std::sqrt(t0 * t0 + 4 * n2 * k2), a = std::sqrt(std::max(0.0, (a2b2 + t0) / 2));
  const double t1 = a2b2 + c2, t2 = 2 * c * a, t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
  // (η = 0, the ideal conductor, needs no case of its own: a = 0, so t2 = t4 = 0 and R = 1.)
  const double rs = std::min(1.0, (t1 - t2) / (t1 + t2));
  const double Rs = t1 + t2 == 0 ? 1.0 : rs;
  const double rp = std::min(1.0, Rs * (t3 - t4) / (t3 + t4));
  const double Rp = t3 + t4 == 0 ? 1.0 : rp;
  return {float((Rs + Rp) / 2), float(Rs), float(Rp)};
}

inline float fresnel_conductor(float cos_theta_i, float n, float k) {
  return fresnel_conductor_polarized(cos_theta_i, n, k).R;
}

}  // namespace prism
