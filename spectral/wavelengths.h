#pragma once
// SampledWavelengths<N>: the wavelengths one camera path carries, with their sampling pdfs.
// Hero wavelength sampling (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling"): the N
// wavelengths sit at the CDF values (s + k)/N, k = 0..N-1, so they are stratified over the pdf;
// u.y picks which of them is the hero (lane 0), so the hero alone is distributed as the pdf.
// Only s = u.x sets the N values, so a sampler that stratifies u.x over a pixel's M samples
// stratifies the pixel's M·N wavelengths (a single number u with companions u + i/N would
// stratify only frac(N·u), which a (0,2)-sequence's top bits do not).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/base/vec.h"
#include "spectral/sampled_spectrum.h"

namespace prism {

inline constexpr float kLambdaMin = 360.f;  // nm; the range of the CIE 1931 tables Prism ships
inline constexpr float kLambdaMax = 830.f;

// Visible-importance pdf p(λ) ∝ sech²(a(λ − μ)), a = 0.0072 nm⁻¹, μ = 538 nm, normalised on
// [360, 830] nm (Radziszewski et al. 2009, "An Improved Technique for Full Spectral Rendering";
// the fit pbrt-v4 uses). Its CDF is affine in tanh(a(λ − μ)), so sampling is closed form.
namespace visible_pdf {
inline constexpr double kA = 0.0072, kMu = 538.0;
inline const double kTanhMin = std::tanh(kA * (kLambdaMin - kMu));
inline const double kTanhMax = std::tanh(kA * (kLambdaMax - kMu));
}  // namespace visible_pdf

// p(λ) through t = tanh(a(λ − μ)): sech² = 1 − t², so sampling gets the pdf without a cosh.
inline float visible_pdf_of_tanh(float t) {
  using namespace visible_pdf;
  return float(kA / (kTanhMax - kTanhMin)) * (1.f - t * t);
}

inline float visible_wavelengths_pdf(float lambda) {
  using namespace visible_pdf;
  if (lambda < kLambdaMin || lambda > kLambdaMax) return 0.f;
  return visible_pdf_of_tanh(std::tanh(float(kA) * (lambda - float(kMu))));
}

// atanh t = ½ ln((1 + t)/(1 − t)) for |t| < 1, inline and branch-free so that the loop over a
// path's wavelengths vectorises (glibc's atanhf is slow, and logf is a call per lane). ln x with
// x = m·2^k, m ∈ [√½, √2) from the bits (the reduction of musl's logf), and
// ln m = 2 atanh z = 2(z + z³/3 + … + z¹¹/11), z = (m − 1)/(m + 1) ∈ ±0.172, whose remainder is
// below 1e-11: as exact as float arithmetic (about an ulp).
inline float atanh_by_series(float t) {
  const uint32_t bits = std::bit_cast<uint32_t>((1.f + t) / (1.f - t)) + (0x3f800000u - 0x3f3504f3u);
  const float k = float(int(bits >> 23) - 0x7f);
  const float m = std::bit_cast<float>((bits & 0x007fffffu) + 0x3f3504f3u);
  const float z = (m - 1.f) / (m + 1.f), z2 = z * z;
  const float series = z2 * (1.f / 3 + z2 * (1.f / 5 + z2 * (1.f / 7 + z2 * (1.f / 9 + z2 * (1.f / 11)))));
  return 0.5f * k * 0.693147182f + (z + z * series);
}

// The inverse CDF at u, and p(λ) there.
inline float sample_visible_wavelengths(float u, float& pdf) {
  using namespace visible_pdf;
  const float t = float(kTanhMin) + u * float(kTanhMax - kTanhMin);
  pdf = visible_pdf_of_tanh(t);
  return std::clamp(float(kMu) + atanh_by_series(t) / float(kA), kLambdaMin, kLambdaMax);
}

enum class WavelengthSampling { visible, uniform };

template <int N>
class SampledWavelengths {
 public:
  static SampledWavelengths sample(Vec2f u, WavelengthSampling mode = WavelengthSampling::visible) {
    SampledWavelengths w;
    const int hero = std::min(int(u.y * N), N - 1);
    for (int i = 0; i < N; ++i) {
      const float ui = (u.x + float((hero + i) % N)) / N;
      if (mode == WavelengthSampling::visible) {
        w.lambda_[i] = sample_visible_wavelengths(ui, w.pdf_[i]);
      } else {
        w.lambda_[i] = kLambdaMin + ui * (kLambdaMax - kLambdaMin);
        w.pdf_[i] = 1.f / (kLambdaMax - kLambdaMin);
      }
    }
    return w;
  }

  float operator[](int i) const { return lambda_[i]; }

  // Lane i alone, as a one-wavelength path (for tracing wavelengths separately).
  SampledWavelengths<1> lane(int i) const {
    SampledWavelengths<1> w;
    w.lambda_[0] = lambda_[i];
    w.pdf_[0] = pdf_[i];
    return w;
  }
  const SampledSpectrum<N>& pdf() const { return pdf_; }

  // At an interface whose index of refraction varies with λ, only the hero wavelength (lane 0)
  // can follow the refracted direction. The companions are dropped (pdf 0) and the hero's pdf
  // divided by N, so that the lane average used by the film stays an unbiased estimator
  // (pbrt-v4 §4.5.4, TerminateSecondary). BDPT and VCM do this; the path tracer keeps every lane
  // by spectral MIS where the interface is rough (materials/dispersive_bsdf.h).
  void terminate_secondary() {
    if (secondary_terminated()) return;
    for (int i = 1; i < N; ++i) pdf_[i] = 0.f;
    pdf_[0] /= N;
  }
  bool secondary_terminated() const {
    for (int i = 1; i < N; ++i)
      if (pdf_[i] != 0.f) return false;
    return true;
  }

 private:
  template <int>
  friend class SampledWavelengths;
  SampledSpectrum<N> lambda_, pdf_;
};

// A contribution that only the hero wavelength could make (its path met a dispersive interface),
// as an estimate over all lanes of wavelengths whose secondaries are still alive: N times its hero
// lane, as terminate_secondary's pdf gives it. Estimators that keep such contributions apart from
// those every lane could make stay unbiased lane by lane and lose only the former's colour.
template <int N>
SampledSpectrum<N> hero_lane(const SampledSpectrum<N>& c) {
  SampledSpectrum<N> h(0.f);
  h[0] = c[0] * float(N);
  return h;
}

}  // namespace prism
