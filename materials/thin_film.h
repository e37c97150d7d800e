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

#include "core/base/math.h"
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
  return std::max(eta, std::max(quarter_wave, 1 / quarter_wave));
}

// How far a film's reflectance can rise above that interface's Fresnel reflectance F(θ, η_c), at
// any angle, thickness and weight: Airy's sum is largest when its two reflections add in phase,
//   R ≤ ((|r_af| + |r_fb|) / (1 + |r_af| |r_fb|))²  per polarisation
// (the bare base, phase 1, lies under it too). That envelope meets F(η_c) at normal incidence but
// rises above it towards grazing, where no single index bounds it (n_f 1.8 over η 1.5: by 0.013 at
// 81°). x = max over θ of the envelope − F(θ, η_c), taken on 256 angles.
// (Not inlined: film_reflectance_excess, which falls back on it, is read per lane at every hit.)
[[gnu::noinline]] inline float film_reflectance_excess_exact(float n_film, float eta) {
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

// The excess table's cell (albedo_tables.h) holding n_f, η, or −1 outside the table.
inline int film_excess_cell(float n_film, float eta) {
  using namespace albedo_tables;
  const float u = (n_film - 1) * (kFilmSteps / 2.f), v = (eta - 1) * (kFilmSteps / 2.f);
  return ((u >= 0) & (v >= 0) & (u < kFilmSteps) & (v < kFilmSteps)) ? int(u) * kFilmSteps + int(v) : -1;
}
// film_reflectance_excess_exact, tabulated over n_f, η ∈ [1, 3) at build time and read as the
// largest of a cell's corners; outside the table, computed.
inline float film_reflectance_excess(float n_film, float eta) {
  const int cell = film_excess_cell(n_film, eta);
  return cell < 0 ? film_reflectance_excess_exact(n_film, eta) : albedo_tables::film_excess[cell];
}
// The same for each lane's indices: when all fall in the table, one loop without branches or
// calls (vector code, a gather); else lane by lane.
template <int N>
SampledSpectrum<N> film_reflectance_excess(const SampledSpectrum<N>& n_film, const SampledSpectrum<N>& eta) {
  std::array<int, N> cell;
  for (int i = 0; i < N; ++i) cell[i] = film_excess_cell(n_film[i], eta[i]);
  int all = 1;
  for (int i = 0; i < N; ++i) all &= cell[i] >= 0;
  SampledSpectrum<N> x;
  if (all)
    for (int i = 0; i < N; ++i) x[i] = albedo_tables::film_excess[cell[i]];
  else
    for (int i = 0; i < N; ++i) x[i] = film_reflectance_excess(n_film[i], eta[i]);
  return x;
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
  // base's relative index base(i) (real for a dielectric, complex for a metal). cos_theta < 0:
  // light from inside a dielectric base. In the complex sum, lanes of the same indices share the
  // interfaces' coefficients.
  template <typename BaseIndex>
  SampledSpectrum<N> reflectance(float cos_theta, const BaseIndex& base) const {
    if (const auto R = propagating_reflectance(cos_theta, base)) return *R;
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
  // The same for light from the ambient through a film in which it propagates (q_f real), onto a
  // base of real or complex index: the phase e^{iφ}, φ = k q_f, has modulus 1 and r_af is real,
  // so per polarisation, with z = r_fb e^{iφ} in real and imaginary parts,
  //   R = |r_af + z|² / |1 + r_af z|² = ((r_af + z_re)² + z_im²) / ((1 + r_af z_re)² + (r_af z_im)²).
  // Nothing when some lane falls outside that case (the complex sum above takes it). The lanes'
  // loop has no branch and no library call, so it runs on all lanes at once (SIMD).
  template <typename BaseIndex>
  std::optional<SampledSpectrum<N>> propagating_reflectance(float cos_theta, const BaseIndex& base) const {
    if (cos_theta < 0) return std::nullopt;
    const float c = std::min(cos_theta, 1.f), s2 = 1 - c * c;
    constexpr bool metal = !std::is_floating_point_v<std::remove_cvref_t<std::invoke_result_t<BaseIndex, int>>>;
    std::array<float, N> n_re, n_im;
    for (int i = 0; i < N; ++i) {
      const auto b = base(i);
      if constexpr (metal)
        n_re[i] = b.real(), n_im[i] = b.imag();
      else
        n_re[i] = b, n_im[i] = 0;
    }
    // A dielectric base must also let the light in (q_b real), as the real sum needs. (An int
    // reduction in a loop of its own, which GCC runs on all lanes at once; folded into the loop
    // above, it left both scalar.)
    int propagates = 1;
    for (int i = 0; i < N; ++i) propagates &= int(ior[i] * ior[i] > s2) & int(metal || n_re[i] * n_re[i] > s2);
    if (!propagates) return std::nullopt;
    SampledSpectrum<N> R;
    for (int i = 0; i < N; ++i) {
      const float n2f = ior[i] * ior[i], q_f = std::sqrt(n2f - s2);
      // n_b² and q_b = √(n_b² − s²), the principal root from the larger of its parts.
      const float n2b_re = n_re[i] * n_re[i] - n_im[i] * n_im[i], n2b_im = 2 * n_re[i] * n_im[i];
      const float x = n2b_re - s2, big = std::sqrt((std::sqrt(x * x + n2b_im * n2b_im) + std::abs(x)) / 2);
      const float small = n2b_im / (2 * big + 1e-30f);  // big = 0 only where n2b_im = 0
      // n, k ≥ 0, so both parts are ≥ 0: the larger is the real part where x ≥ 0.
      const float qb_re = x >= 0 ? big : small, qb_im = x >= 0 ? small : big;
      const float af_s = (c - q_f) / (c + q_f), af_p = (n2f * c - q_f) / (n2f * c + q_f);
      // r_fb = (a − b) / (a + b) = (a − b)(a + b)* / |a + b|², s: a = q_f, b = q_b; p: a = n_b² q_f, b = n_f² q_b.
      const auto ratio = [](float a_re, float a_im, float b_re, float b_im) {
        const float d_re = a_re - b_re, d_im = a_im - b_im, s_re = a_re + b_re, s_im = a_im + b_im;
        const float den = s_re * s_re + s_im * s_im;
        return std::array<float, 2>{(d_re * s_re + d_im * s_im) / den, (d_im * s_re - d_re * s_im) / den};
      };
      const auto fb_s = ratio(q_f, 0, qb_re, qb_im);
      const auto fb_p = ratio(n2b_re * q_f, n2b_im * q_f, n2f * qb_re, n2f * qb_im);
      const SinCos phi = sin_cos(k[i] * q_f);
      // A vanishing denominator (grazing) gives 1: min(1, x/0) is 1 for x/0 = inf or NaN.
      const auto airy = [](float r1, float z_re, float z_im) {
        const float den = sqr(1 + r1 * z_re) + sqr(r1 * z_im);
        return std::min(1.f, (sqr(r1 + z_re) + sqr(z_im)) / den);
      };
      const auto filmed = [&](float r1, const std::array<float, 2>& r2) {
        return airy(r1, r2[0] * phi.cos - r2[1] * phi.sin, r2[0] * phi.sin + r2[1] * phi.cos);
      };
      const float bare = (airy(af_s, fb_s[0], fb_s[1]) + airy(af_p, fb_p[0], fb_p[1])) / 2;
      R[i] = bare + weight * ((filmed(af_s, fb_s) + filmed(af_p, fb_p)) / 2 - bare);
    }
    return R;
  }
};

}  // namespace prism
