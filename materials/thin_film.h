#pragma once
// Thin-film interference (KHR_materials_iridescence), exact per wavelength: a film of thickness
// d and real index n_f between an ambient medium n_a and a base of complex index n_b, summed over
// all its internal reflections with their phase — Airy's formula (Born & Wolf, "Principles of
// Optics", §7.6.1), for s and p polarisation, averaged for unpolarised light:
//   r = (r_af + r_fb e^{2iβ}) / (1 + r_af r_fb e^{2iβ}),  β = 2π d q_f / λ,
//   q_j = n_j cos θ_j = √(n_j² − n_a² sin²θ_a)  (complex beyond a critical angle or in a metal),
//   r_ij⊥ = (q_i − q_j) / (q_i + q_j),  r_ij∥ = (n_j² q_i − n_i² q_j) / (n_j² q_i + n_i² q_j).
// d = 0 and n_f = n_a reduce it to the bare interface's Fresnel reflectance; so does the phase
// e^{2iβ} = 1 for any film, which is how the bare base's reflectance comes out of the same terms.
// Only the phase depends on the wavelength: a path's lanes share the interfaces' coefficients
// (FilmInterfaces) whenever they share the indices, and each lane adds one rotation e^{2iβ}.
// Where this departs from the extension's reference (Belcour & Barla 2017, "A Practical
// Extension to Microfacet Theory for the Modeling of Varying Iridescence"): they integrate this
// same sum against the CIE matching functions to get RGB (with a Gaussian fit of the spectra and
// F0-derived base indices); a spectral renderer evaluates it at each sampled wavelength, against
// the base's actual index (or measured n, k), so nothing is fitted and no colour is lost.

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <optional>
#include <type_traits>

#include "base/math.h"
#include "materials/albedo_tables.h"
#include "materials/fresnel.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace prism {

// A film over a surface: KHR_materials_iridescence's factor (a blend weight on the reflectance),
// thickness in nanometres and index.
struct ThinFilm {
  float weight = 0, thickness_nm = 0, ior = 1.3f;
};

// The film's two interfaces for light arriving from the ambient at cos θ_a: everything of Airy's
// sum but the wavelength, in float (within 4·10⁻⁵ of the double-precision sum at any thickness up
// to 1.2 µm). Complex arithmetic is written out (mul, norm, ratio, root): the library's products
// guard against NaN with a call per product, and its norm is |z|² through a scaled |z|.
struct FilmInterfaces {
  using C = std::complex<float>;
  // The ambient | film interface: what the lanes of one film index and ambient share.
  struct Top {
    float s2;    // (n_a sin θ_a)², conserved across the layers
    float n2f;   // n_f²
    C q_f;       // n_f cos θ_f (the phase is e^{i k q_f}, k = 4π d / λ)
    C r_s, r_p;  // amplitude reflection coefficients, s and p
    Top(float cos_theta, float n_ambient, float n_film) {
      const float c = std::min(std::abs(cos_theta), 1.f);
      s2 = n_ambient * n_ambient * (1 - c * c);
      n2f = n_film * n_film;
      q_f = s2 == 0 ? C(n_film) : root(C(n2f - s2));
      const float q_a = n_ambient * c;
      r_s = ratio(C(q_a), q_f), r_p = ratio(C(n2f * q_a), q_f * (n_ambient * n_ambient));
    }
  };
  C r_af_s, r_af_p, r_fb_s, r_fb_p, q_f;

  FilmInterfaces(const Top& top, C n_base) : r_af_s(top.r_s), r_af_p(top.r_p), q_f(top.q_f) {
    const C n2b = mul(n_base, n_base), q_b = top.s2 == 0 ? n_base : root(n2b - top.s2);
    r_fb_s = ratio(q_f, q_b), r_fb_p = ratio(mul(n2b, q_f), q_b * top.n2f);
  }
  FilmInterfaces(float cos_theta, float n_ambient, float n_film, C n_base)
      : FilmInterfaces(Top(cos_theta, n_ambient, n_film), n_base) {}

  // Unpolarised reflectance for the phase constant k = 4π d / λ (k = 0: the bare interface).
  float reflectance(float k) const {
    if (k == 0) return (airy(r_af_s, r_fb_s) + airy(r_af_p, r_fb_p)) / 2;
    const SinCos a = sin_cos(k * q_f.real());
    C phase(a.cos, a.sin);
    if (q_f.imag() != 0) phase *= std::exp(-k * q_f.imag());  // evanescent in the film
    return (airy(r_af_s, mul(r_fb_s, phase)) + airy(r_af_p, mul(r_fb_p, phase))) / 2;
  }

 private:
  static C mul(C a, C b) {
    return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
  }
  static float norm(C z) { return z.real() * z.real() + z.imag() * z.imag(); }
  // |r_1 + z|² / |1 + r_1 z|², z = r_2 e^{2iβ}; a vanishing denominator is the grazing limit, 1.
  static float airy(C r1, C z) {
    const float den = norm(1.f + mul(r1, z));
    return den == 0 ? 1.f : std::min(1.f, norm(r1 + z) / den);
  }
  // (a − b) / (a + b) as (a − b)(a + b)* / |a + b|².
  static C ratio(C a, C b) {
    const float den = norm(a + b);
    return den == 0 ? C(1) : mul(a - b, std::conj(a + b)) / den;
  }
  // The principal square root, from the larger of its parts (no cancellation).
  static C root(C x) {
    if (x.imag() == 0) return x.real() >= 0 ? C(std::sqrt(x.real()), 0) : C(0, std::sqrt(-x.real()));
    const float m = std::sqrt(norm(x));
    if (x.real() >= 0) {
      const float re = std::sqrt((m + x.real()) / 2);
      return {re, x.imag() / (2 * re)};
    }
    const float im = std::copysign(std::sqrt((m - x.real()) / 2), x.imag());
    return {x.imag() / (2 * im), im};
  }
};

// Unpolarised reflectance of a film (thickness d_nm, index n_film) between an ambient of index
// n_ambient and a base of complex index n_base, for light of vacuum wavelength lambda_nm
// arriving from the ambient at cos θ = cos_theta (its absolute value is used).
inline float thin_film_reflectance(float cos_theta, float lambda_nm, float d_nm, float n_ambient, float n_film,
                                   std::complex<float> n_base) {
  return FilmInterfaces(cos_theta, n_ambient, n_film, n_base).reflectance(4 * kPi * d_nm / lambda_nm);
}

// A diffuse base under a film is coupled to it as to a bare interface of index η_c, whose
// directional albedo tables exist (pbr_bsdf.h): the film's reflectance peaks at normal incidence
// as a quarter-wave layer's, an interface of index n_f²/η, and η_c is the largest of that and η.
inline float film_coupling_index(float n_film, float eta) {
  const float quarter_wave = n_film * n_film / eta;
  return std::max({eta, quarter_wave, 1 / quarter_wave});
}

// How far a film's reflectance can rise above that interface's Fresnel reflectance F(θ, η_c), at
// any angle, thickness and weight: Airy's sum is largest when its two reflections add in phase,
//   R ≤ ((|r_af| + |r_fb|) / (1 + |r_af| |r_fb|))²  per polarisation
// (the bare base, phase 1, lies under it too). That envelope meets F(η_c) at normal incidence but
// rises above it towards grazing, where no single index bounds it (n_f 1.8 over η 1.5: by 0.013 at
// 81°). x = max over θ of the envelope − F(θ, η_c), taken on 256 angles.
inline float film_reflectance_excess_exact(float n_film, float eta) {
  const float eta_c = film_coupling_index(n_film, eta);
  const auto envelope = [](std::complex<float> r1, std::complex<float> r2) {
    const float a = std::abs(r1), b = std::abs(r2);
    return sqr((a + b) / (1 + a * b));
  };
  float x = 0;
  for (int j = 0; j <= 256; ++j) {
    const float c = std::min(1.f, (j + 0.5f) / 256);
    const FilmInterfaces f(c, 1, n_film, eta);
    const float R = (envelope(f.r_af_s, f.r_fb_s) + envelope(f.r_af_p, f.r_fb_p)) / 2;
    x = std::max(x, R - fresnel_dielectric(c, eta_c));
  }
  return x;
}

// The same, tabulated over n_f, η ∈ [1, 3] at build time (albedo_tables.h) and read as the largest
// of a cell's corners; outside the table, computed.
inline float film_reflectance_excess(float n_film, float eta) {
  using namespace albedo_tables;
  const float u = (n_film - 1) * (kFilmSteps / 2.f), v = (eta - 1) * (kFilmSteps / 2.f);
  if (!(u >= 0 && v >= 0 && u < kFilmSteps && v < kFilmSteps)) return film_reflectance_excess_exact(n_film, eta);
  const int a = int(u), b = int(v);
  const auto at = [&](int i, int j) { return film_excess[(a + i) * (kFilmSteps + 1) + b + j]; };
  return std::max({at(0, 0), at(0, 1), at(1, 0), at(1, 1)});
}

// A ThinFilm for one path's wavelengths, in the units of the front medium (index n_front): the
// film's relative index n_film / n_front and the phase constants k = 4π d n_front / λ.
template <int N>
struct FilmLanes {
  float weight;
  SampledSpectrum<N> ior, k;

  FilmLanes(const ThinFilm& film, const SampledWavelengths<N>& wavelengths, const SampledSpectrum<N>& n_front)
      : weight(film.weight) {
    for (int i = 0; i < N; ++i)
      ior[i] = film.ior / n_front[i], k[i] = 4 * kPi * film.thickness_nm * n_front[i] / wavelengths[i];
  }

  // Each lane's reflectance: the bare base's blended by the weight with the filmed one, for the
  // base's relative index base(i) (complex for a metal). cos_theta < 0: light from inside a
  // dielectric base. In the complex sum, lanes of the same indices share the interfaces'
  // coefficients.
  template <typename BaseIndex>
  SampledSpectrum<N> reflectance(float cos_theta, const BaseIndex& base) const {
    if constexpr (std::is_floating_point_v<std::remove_cvref_t<std::invoke_result_t<BaseIndex, int>>>)
      if (const auto R = real_reflectance(cos_theta, base)) return *R;
    using C = std::complex<float>;
    SampledSpectrum<N> R;
    std::optional<FilmInterfaces::Top> top;
    std::optional<FilmInterfaces> f;
    float n_ambient = 0, n_film = 0, bare = 0;
    C n_base;
    for (int i = 0; i < N; ++i) {
      const C b = base(i);
      const float a = cos_theta >= 0 ? 1.f : b.real();  // from inside, the base is the ambient
      const C below = cos_theta >= 0 ? b : C(1);
      if (!top || a != n_ambient || ior[i] != n_film) {
        n_ambient = a, n_film = ior[i];
        top.emplace(cos_theta, n_ambient, n_film);
        f.reset();
      }
      if (!f || below != n_base) {
        n_base = below;
        f.emplace(*top, n_base);
        bare = f->reflectance(0);
      }
      R[i] = bare + weight * (f->reflectance(k[i]) - bare);
    }
    return R;
  }

 private:
  // The same in real arithmetic, for light from the ambient onto a dielectric base (index eta(i))
  // through a film in which it propagates (q_f, q_b > 0): every amplitude coefficient is then real
  // and the phase of modulus 1, so per polarisation, with φ = k q_f,
  //   R = |r_af + r_fb e^{iφ}|² / |1 + r_af r_fb e^{iφ}|²
  //     = ((r_af + r_fb cos φ)² + (r_fb sin φ)²) / ((1 + r_af r_fb cos φ)² + (r_af r_fb sin φ)²).
  // Nothing when some lane falls outside that case (the complex sum above takes it). The lanes'
  // loop has no branch and no library call, so it runs on all lanes at once (SIMD).
  template <typename Eta>
  std::optional<SampledSpectrum<N>> real_reflectance(float cos_theta, const Eta& eta) const {
    if (cos_theta < 0) return std::nullopt;
    const float c = std::min(cos_theta, 1.f), s2 = 1 - c * c;
    std::array<float, N> n2b;
    bool propagates = true;
    for (int i = 0; i < N; ++i) {
      n2b[i] = eta(i) * eta(i);
      propagates &= (ior[i] * ior[i] > s2) & (n2b[i] > s2);
    }
    if (!propagates) return std::nullopt;
    SampledSpectrum<N> R;
    for (int i = 0; i < N; ++i) {
      const float n2f = ior[i] * ior[i];
      const float q_f = std::sqrt(n2f - s2), q_b = std::sqrt(n2b[i] - s2);
      const float af_s = (c - q_f) / (c + q_f), af_p = (n2f * c - q_f) / (n2f * c + q_f);
      const float fb_s = (q_f - q_b) / (q_f + q_b), fb_p = (n2b[i] * q_f - n2f * q_b) / (n2b[i] * q_f + n2f * q_b);
      const float bare = (sqr((af_s + fb_s) / (1 + af_s * fb_s)) + sqr((af_p + fb_p) / (1 + af_p * fb_p))) / 2;
      const SinCos phi = sin_cos(k[i] * q_f);
      // A vanishing denominator (grazing) gives 1: min(1, x/0) is 1 for x/0 = inf or NaN.
      const auto airy = [&](float r1, float r2) {
        const float den = sqr(1 + r1 * r2 * phi.cos) + sqr(r1 * r2 * phi.sin);
        return std::min(1.f, (sqr(r1 + r2 * phi.cos) + sqr(r2 * phi.sin)) / den);
      };
      R[i] = bare + weight * ((airy(af_s, fb_s) + airy(af_p, fb_p)) / 2 - bare);
    }
    return R;
  }
};

}  // namespace prism
