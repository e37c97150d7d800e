#pragma once
// Thin-film interference (KHR_materials_iridescence), exact per wavelength: a film of thickness
// d and real index n_f between an ambient medium n_a and a base of complex index n_b, summed over
// all its internal reflections with their phase — Airy's formula (Born & Wolf, "Principles of
// Optics", §7.6.1), for s and p polarisation, averaged for unpolarised light:
//   r = (r_af + r_fb e^{2iβ}) / (1 + r_af r_fb e^{2iβ}),  β = 2π d q_f / λ,
//   q_j = n_j cos θ_j = √(n_j² − n_a² sin²θ_a)  (complex beyond a critical angle or in a metal),
//   r_ij⊥ = (q_i − q_j) / (q_i + q_j),  r_ij∥ = (n_j² q_i − n_i² q_j) / (n_j² q_i + n_i² q_j).
// d = 0 and n_f = n_a reduce it to the bare interface's Fresnel reflectance.
// Where this departs from the extension's reference (Belcour & Barla 2017, "A Practical
// Extension to Microfacet Theory for the Modeling of Varying Iridescence"): they integrate this
// same sum against the CIE matching functions to get RGB (with a Gaussian fit of the spectra and
// F0-derived base indices); a spectral renderer evaluates it at each sampled wavelength, against
// the base's actual index (or measured n, k), so nothing is fitted and no colour is lost.

#include <complex>

#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace prism {

// A film over a surface: KHR_materials_iridescence's factor (a blend weight on the reflectance),
// thickness in nanometres and index.
struct ThinFilm {
  float weight = 0, thickness_nm = 0, ior = 1.3f;
};

// Unpolarised reflectance of a film (thickness d_nm, index n_film) between an ambient of index
// n_ambient and a base of complex index n_base, for light of vacuum wavelength lambda_nm
// arriving from the ambient at cos θ = cos_theta (its absolute value is used).
inline double thin_film_reflectance(double cos_theta, double lambda_nm, double d_nm, double n_ambient, double n_film,
                                    std::complex<double> n_base) {
  // Complex arithmetic written out where the library's would call the (slow, NaN-guarding)
  // complex division: x / y = x ȳ / |y|².
  using C = std::complex<double>;
  const double c = std::min(std::abs(cos_theta), 1.0);
  const double s2 = n_ambient * n_ambient * (1 - c * c);  // (n_a sin θ_a)², conserved across layers
  const auto root = [](C x) {  // principal square root; real arguments without the library call
    if (x.imag() == 0) return x.real() >= 0 ? C(std::sqrt(x.real()), 0) : C(0, std::sqrt(-x.real()));
    return std::sqrt(x);
  };
  const C qa(n_ambient * c), qf = root(C(n_film * n_film - s2)), qb = root(n_base * n_base - s2);
  const C n2a(n_ambient * n_ambient), n2f(n_film * n_film), n2b = n_base * n_base;
  const double k = 4 * 3.14159265358979323846 * d_nm / lambda_nm;  // e^{2iβ} = e^{i k q_f}
  const C phase = std::exp(-k * qf.imag()) * C(std::cos(k * qf.real()), std::sin(k * qf.real()));
  const auto airy = [&](C r_af, C r_fb) {
    const double den = std::norm(1.0 + r_af * r_fb * phase);
    return den == 0 ? 1.0 : std::min(1.0, std::norm(r_af + r_fb * phase) / den);
  };
  const auto ratio = [](C a, C b) {
    const double den = std::norm(a + b);
    return den == 0 ? C(1) : (a - b) * std::conj(a + b) / den;
  };
  const double Rs = airy(ratio(qa, qf), ratio(qf, qb));
  const double Rp = airy(ratio(n2f * qa, n2a * qf), ratio(n2b * qf, n2f * qb));
  return (Rs + Rp) / 2;
}

}  // namespace prism

namespace prism {

// A ThinFilm for one path's wavelengths, in the units of the front medium (index n_front): the
// film's relative index n_film / n_front and the wavelengths in that medium, λ / n_front.
template <int N>
struct FilmLanes {
  float weight, thickness_nm;
  SampledSpectrum<N> ior, lambda;

  FilmLanes(const ThinFilm& film, const SampledWavelengths<N>& wavelengths, const SampledSpectrum<N>& n_front)
      : weight(film.weight), thickness_nm(film.thickness_nm) {
    for (int i = 0; i < N; ++i) ior[i] = film.ior / n_front[i], lambda[i] = wavelengths[i] / n_front[i];
  }

  // Lane i's reflectance `bare` of the base alone, blended by the weight with the filmed one;
  // base = the base's relative index. cos_theta < 0: light from inside a dielectric base.
  float reflectance(int i, float cos_theta, std::complex<double> base, float bare) const {
    const double r = cos_theta >= 0 ? thin_film_reflectance(cos_theta, lambda[i], thickness_nm, 1, ior[i], base)
                                    : thin_film_reflectance(cos_theta, lambda[i], thickness_nm, base.real(), ior[i], 1);
    return bare + weight * (float(r) - bare);
  }
};

}  // namespace prism
