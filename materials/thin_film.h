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

#include <array>
#include <cmath>
#include <complex>
#include <optional>

#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace prism {

// A film over a surface: KHR_materials_iridescence's factor (a blend weight on the reflectance),
// thickness in nanometres and index.
struct ThinFilm {
  float weight = 0, thickness_nm = 0, ior = 1.3f;
};

// The film's two interfaces for light arriving from the ambient at cos θ_a: everything of Airy's
// sum but the wavelength. Complex arithmetic is written out where the library's would call its
// slow, NaN-guarding routines (division, square root).
struct FilmInterfaces {
  using C = std::complex<double>;
  C r_af_s, r_af_p, r_fb_s, r_fb_p;  // amplitude reflection coefficients, s and p
  C q_f;                             // n_f cos θ_f: the phase is e^{i k q_f}, k = 4π d / λ

  FilmInterfaces(double cos_theta, double n_ambient, double n_film, C n_base) {
    const double c = std::min(std::abs(cos_theta), 1.0);
    const double s2 = n_ambient * n_ambient * (1 - c * c);  // (n_a sin θ_a)², conserved across layers
    const C n2a(n_ambient * n_ambient), n2f(n_film * n_film), n2b = n_base * n_base;
    const C q_a(n_ambient * c), q_b = s2 == 0 ? n_base : root(n2b - s2);
    q_f = s2 == 0 ? C(n_film) : root(n2f - s2);
    r_af_s = ratio(q_a, q_f), r_af_p = ratio(n2f * q_a, n2a * q_f);
    r_fb_s = ratio(q_f, q_b), r_fb_p = ratio(n2b * q_f, n2f * q_b);
  }

  // Unpolarised reflectance for the phase constant k = 4π d / λ (k = 0: the bare interface).
  double reflectance(double k) const {
    C phase(1);
    if (k != 0) {
      const double a = k * q_f.real();
      phase = C(std::cos(a), std::sin(a));
      if (q_f.imag() != 0) phase *= std::exp(-k * q_f.imag());  // evanescent in the film
    }
    return (airy(r_af_s, r_fb_s * phase) + airy(r_af_p, r_fb_p * phase)) / 2;
  }

 private:
  // |r_1 + z|² / |1 + r_1 z|², z = r_2 e^{2iβ}; a vanishing denominator is the grazing limit, 1.
  static double airy(C r1, C z) {
    const double den = std::norm(1.0 + r1 * z);
    return den == 0 ? 1.0 : std::min(1.0, std::norm(r1 + z) / den);
  }
  // (a − b) / (a + b) as (a − b)(a + b)* / |a + b|².
  static C ratio(C a, C b) {
    const double den = std::norm(a + b);
    return den == 0 ? C(1) : (a - b) * std::conj(a + b) / den;
  }
  // The principal square root, from the larger of its parts (no cancellation).
  static C root(C x) {
    if (x.imag() == 0) return x.real() >= 0 ? C(std::sqrt(x.real()), 0) : C(0, std::sqrt(-x.real()));
    const double m = std::sqrt(std::norm(x));
    if (x.real() >= 0) {
      const double re = std::sqrt((m + x.real()) / 2);
      return {re, x.imag() / (2 * re)};
    }
    const double im = std::copysign(std::sqrt((m - x.real()) / 2), x.imag());
    return {x.imag() / (2 * im), im};
  }
};

// Unpolarised reflectance of a film (thickness d_nm, index n_film) between an ambient of index
// n_ambient and a base of complex index n_base, for light of vacuum wavelength lambda_nm
// arriving from the ambient at cos θ = cos_theta (its absolute value is used).
inline double thin_film_reflectance(double cos_theta, double lambda_nm, double d_nm, double n_ambient, double n_film,
                                    std::complex<double> n_base) {
  return FilmInterfaces(cos_theta, n_ambient, n_film, n_base)
      .reflectance(4 * 3.14159265358979323846 * d_nm / lambda_nm);
}

// A ThinFilm for one path's wavelengths, in the units of the front medium (index n_front): the
// film's relative index n_film / n_front and the phase constants k = 4π d n_front / λ.
template <int N>
struct FilmLanes {
  float weight;
  SampledSpectrum<N> ior;
  std::array<double, N> k;

  FilmLanes(const ThinFilm& film, const SampledWavelengths<N>& wavelengths, const SampledSpectrum<N>& n_front)
      : weight(film.weight) {
    for (int i = 0; i < N; ++i)
      ior[i] = film.ior / n_front[i],
      k[i] = 4 * 3.14159265358979323846 * film.thickness_nm * n_front[i] / wavelengths[i];
  }

  // Each lane's reflectance: the bare base's blended by the weight with the filmed one, for the
  // base's relative index base(i) (complex for a metal). cos_theta < 0: light from inside a
  // dielectric base. Lanes of the same indices share the interfaces' coefficients.
  template <typename BaseIndex>
  SampledSpectrum<N> reflectance(float cos_theta, const BaseIndex& base) const {
    SampledSpectrum<N> R;
    std::complex<double> n_base;
    float n_film = 0;
    double bare = 0;
    std::optional<FilmInterfaces> f;
    for (int i = 0; i < N; ++i) {
      const std::complex<double> b = base(i);
      if (!f || b != n_base || ior[i] != n_film) {
        n_base = b, n_film = ior[i];
        f = cos_theta >= 0 ? FilmInterfaces(cos_theta, 1, n_film, b) : FilmInterfaces(cos_theta, b.real(), n_film, 1);
        bare = f->reflectance(0);
      }
      R[i] = float(bare + weight * (f->reflectance(k[i]) - bare));
    }
    return R;
  }
};

}  // namespace prism
