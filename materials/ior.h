#pragma once
// Index-of-refraction models n(λ) for dielectrics, λ in nm:
//   constant           n
//   Cauchy             n = A + B / λ²                       (λ in µm; Cauchy 1836)
//   Sellmeier          n² = 1 + A + Σ Bᵢ λ² / (λ² − Cᵢ)     (λ in µm, Cᵢ in µm²; Sellmeier 1871)
//   Abbe               n = n_d + (n_d − 1)/V_d · (523655/λ² − 1.5168)   (λ in nm; exactly the
//                      form of KHR_materials_dispersion: a Cauchy law through n_d with the
//                      glass's Abbe number V_d = (n_d − 1)/(n_F − n_C))
//   tabulated          measured n(λ), linear between points
// A model is dispersive when n varies with λ; a path meeting one keeps only its hero wavelength.

#include <variant>
#include <vector>

#include "core/base/math.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/spectrum.h"

namespace prism {

struct ConstantIor {
  float n;
  float operator()(float) const { return n; }
};

struct CauchyIor {
  float a, b;  // b in µm²
  float operator()(float lambda_nm) const {
    const float l = lambda_nm * 1e-3f;
    return a + b / (l * l);
  }
};

struct SellmeierIor {
  float a = 0;
  std::vector<float> b, c;  // c in µm²
  float operator()(float lambda_nm) const {
    const double l2 = double(lambda_nm) * lambda_nm * 1e-6;
    double n2 = 1 + a;
    for (size_t i = 0; i < b.size(); ++i) n2 += b[i] * l2 / (l2 - c[i]);
    return float(std::sqrt(std::max(n2, 0.0)));
  }
};

struct AbbeIor {
  float nd, vd;  // refractive index at 587.56 nm (He d line), Abbe number
  float operator()(float lambda_nm) const {
    return nd + (nd - 1) / vd * (523655.f / (lambda_nm * lambda_nm) - 1.5168f);
  }
};

struct TabulatedIor {
  TabulatedSpectrum n;
  float operator()(float lambda_nm) const { return n(lambda_nm); }
};

using IorModel = std::variant<ConstantIor, CauchyIor, SellmeierIor, AbbeIor, TabulatedIor>;

inline float ior(const IorModel& model, float lambda_nm) {
  return std::visit([lambda_nm](const auto& m) { return m(lambda_nm); }, model);
}

// Whether n differs anywhere over the visible range.
bool is_dispersive(const IorModel& model);

// Abbe number V_d = (n_d − 1) / (n_F − n_C) at the Fraunhofer d, F and C lines.
float abbe_number(const IorModel& model);

// Each lane's relative index η'_λ whose exact normal-incidence reflectance is that of η times c_λ
// (at most 1): KHR_materials_specular's coloured F0, on η's side of 1. The index η ≥ 1 of
// reflectance F0 = ((η − 1)/(η + 1))² is (1 + √F0)/(1 − √F0) (F0 = 1: η → ∞). Two loops over the
// lanes, each run on all lanes at once (in one, GCC turns the clamp's constant ends into branches
// and leaves the lanes one by one). The clamp's max with 0 repeats the one inside it, but GCC keeps
// the loop vector code only with it.
template <int N>
SampledSpectrum<N> ior_with_scaled_f0(float eta, const SampledSpectrum<N>& c) {
  const float f0 = sqr((eta - 1) / (eta + 1));
  SampledSpectrum<N> root, scaled;
  for (int i = 0; i < N; ++i) root[i] = std::sqrt(std::min(std::max(f0 * std::max(c[i], 0.f), 0.f), 0.9999f));
  for (int i = 0; i < N; ++i) {
    const float s = (1 + root[i]) / (1 - root[i]);
    scaled[i] = eta < 1 ? 1 / s : s;
  }
  return scaled;
}

}  // namespace prism
