#pragma once
// Spectral distributions, as a closed set of kinds (std::variant):
//   ConstantSpectrum            c for every λ
//   TabulatedSpectrum           piecewise-linear through measured (λ, value) points
//   DenselySampledSpectrum      one value per nm (the CIE tables)
//   BlackbodySpectrum           Planck's law, normalised to peak 1
//   RgbAlbedoSpectrum           reflectance from RGB in [0,1]: bounded to [0,1]
//   RgbUnboundedSpectrum        any non-negative RGB (e.g. absorption, scale × bounded shape)
//   RgbIlluminantSpectrum       emission from RGB: unbounded shape × the colour space's white (D65)
//   RgbAbsorptionSpectrum       absorption coefficient whose transmittance over a distance is an RGB colour

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <variant>
#include <vector>

#include "spectral/rgb.h"
#include "spectral/rgb_to_spectrum.h"
#include "spectral/wavelengths.h"

namespace prism {

struct ConstantSpectrum {
  float c = 0;
  float operator()(float) const { return c; }
};

// Where each of a path's wavelengths falls on a table of 1-nm rows from λ = first (rows ≥ 2 of
// them): the row below it, the fraction towards the next, and inside = 1 within the table's span,
// 0 outside it (and for NaN). All lanes at once (SIMD): no branches.
template <int N>
struct RowPlaces {
  std::array<int, N> row;
  std::array<float, N> fraction, inside;
};
template <int N>
RowPlaces<N> locate_rows(const SampledWavelengths<N>& lambda, float first, int rows) {
  RowPlaces<N> p;
  const float top = float(rows - 1);
  for (int i = 0; i < N; ++i) {
    const float x = lambda[i] - first;
    p.inside[i] = ((x >= 0.f) & (x <= top)) ? 1.f : 0.f;
    const float xc = std::min(std::max(0.f, x), top);  // x where inside; NaN to 0
    p.row[i] = std::min(int(xc), rows - 2);
    p.fraction[i] = xc - float(p.row[i]);
  }
  return p;
}

// Linear interpolation between samples. Beyond the first / last sample the end value holds by
// default (measured optical constants that end short of 360 or 830 nm are extended flat), or the
// spectrum is 0 there (Outside::zero: emission and reflectance tables, which stop where the light does).
class TabulatedSpectrum {
 public:
  enum class Outside { hold, zero };
  TabulatedSpectrum(std::vector<float> lambdas, std::vector<float> values, Outside outside = Outside::hold);
  float operator()(float lambda) const;
  const std::vector<float>& lambdas() const { return lambdas_; }
  const std::vector<float>& values() const { return values_; }
  Outside outside() const { return outside_; }

 private:
  std::vector<float> lambdas_, values_;
  Outside outside_;
};

// Values at every integer nm from lambda_min; linear in between; 0 outside.
class DenselySampledSpectrum {
 public:
  DenselySampledSpectrum() = default;
  DenselySampledSpectrum(int lambda_min, std::vector<float> values)
      : lambda_min_(lambda_min), values_(std::move(values)) {}
  float operator()(float lambda) const {
    const float x = lambda - float(lambda_min_);
    if (!(x >= 0.f) || x > float(values_.size() - 1)) return 0.f;
    const int i = std::min(int(x), int(values_.size()) - 2);
    const float t = x - float(i);
    return (1.f - t) * values_[i] + t * values_[i + 1];
  }
  // The same at all of a path's wavelengths (a constant environment's radiance, once per path):
  // the lanes' rows found at once (locate_rows), then a pair of loads per lane.
  template <int N>
  SampledSpectrum<N> operator()(const SampledWavelengths<N>& lambda) const {
    const RowPlaces<N> p = locate_rows(lambda, float(lambda_min_), int(values_.size()));
    std::array<float, N> a, b;
    for (int i = 0; i < N; ++i) a[i] = values_[p.row[i]], b[i] = values_[p.row[i] + 1];
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) r[i] = p.inside[i] * ((1.f - p.fraction[i]) * a[i] + p.fraction[i] * b[i]);
    return r;
  }
  int lambda_min() const { return lambda_min_; }
  const std::vector<float>& values() const { return values_; }

 private:
  int lambda_min_ = 0;
  std::vector<float> values_;
};

// Planck's law B(λ, T) = 2hc² / (λ⁵ (exp(hc / (λ k T)) − 1)), divided by its value at Wien's
// peak λ_max = b / T so that the maximum is 1.
class BlackbodySpectrum {
 public:
  explicit BlackbodySpectrum(float kelvin);
  float operator()(float lambda) const { return planck(lambda, kelvin_) * normalization_; }
  static float planck(float lambda_nm, float kelvin);

 private:
  float kelvin_, normalization_;
};

struct RgbAlbedoSpectrum {
  explicit RgbAlbedoSpectrum(Rgb rgb);  // each channel clamped to [0, 1]
  float operator()(float lambda) const { return rsp(lambda); }
  template <int N>
  SampledSpectrum<N> operator()(const SampledWavelengths<N>& lambda) const {
    return rsp(lambda);
  }
  RgbSigmoidPolynomial rsp;
};

// scale · s(λ) with scale = 2·max(rgb), so the sigmoid shape fits RGB / scale (max 1/2) with
// room on both sides and stays smooth (pbrt-v4 §4.6.6).
struct RgbUnboundedSpectrum {
  explicit RgbUnboundedSpectrum(Rgb rgb);
  float operator()(float lambda) const { return scale * rsp(lambda); }
  template <int N>
  SampledSpectrum<N> operator()(const SampledWavelengths<N>& lambda) const {
    return scale * rsp(lambda);
  }
  float scale = 0;
  RgbSigmoidPolynomial rsp;
};

struct RgbIlluminantSpectrum {
  explicit RgbIlluminantSpectrum(Rgb rgb);  // over D65
  // Over another white of luminance 1 (which must outlive the spectrum).
  RgbIlluminantSpectrum(Rgb rgb, const DenselySampledSpectrum* white) : shape(rgb), illuminant(white) {}
  float operator()(float lambda) const;
  // All lanes at once; out of line (spectrum.cpp, N = 1, 4, 8; other widths go lane by lane in
  // sample()): inlined into every light sample's caller, it took GCC's inlining budget from the
  // BSDFs' small helpers there.
  template <int N>
  requires(N == 1 || N == 4 || N == 8) SampledSpectrum<N>
  operator()(const SampledWavelengths<N>& lambda) const;
  RgbUnboundedSpectrum shape;
  const DenselySampledSpectrum* illuminant;  // D65 with luminance Y = 1, or another white
};

// σ_a(λ) = −ln T(λ) / d, T the reflectance-like upsampling of `transmittance` (RgbAlbedoSpectrum):
// a medium whose Beer–Lambert transmittance exp(−σ_a d) over the distance d is exactly T(λ), so
// white light turns into that colour up to the upsampling's round trip (KHR_materials_volume's
// attenuationColor at attenuationDistance). Smooth and non-negative since T is; T ≥ 1e-30.
struct RgbAbsorptionSpectrum {
  RgbAbsorptionSpectrum(Rgb transmittance, float distance);
  float operator()(float lambda) const { return sigma_a(transmittance(lambda)); }
  template <int N>
  SampledSpectrum<N> operator()(const SampledWavelengths<N>& lambda) const {
    SampledSpectrum<N> r = transmittance(lambda);
    for (int i = 0; i < N; ++i) r[i] = sigma_a(r[i]);
    return r;
  }
  float sigma_a(float t) const { return -std::log(std::max(t, 1e-30f)) * inv_distance; }
  RgbAlbedoSpectrum transmittance;
  float inv_distance;
};

using Spectrum = std::variant<ConstantSpectrum, TabulatedSpectrum, DenselySampledSpectrum, BlackbodySpectrum,
                              RgbAlbedoSpectrum, RgbUnboundedSpectrum, RgbIlluminantSpectrum, RgbAbsorptionSpectrum>;

inline float evaluate(const Spectrum& s, float lambda) {
  return std::visit([lambda](const auto& kind) { return kind(lambda); }, s);
}

// s at each nm of the visible range, linear in between: for spectra evaluated very often.
DenselySampledSpectrum densely_sampled(const Spectrum& s);

// s at a path's wavelengths: all lanes at once where the kind offers it (the RGB sigmoids).
template <int N>
SampledSpectrum<N> sample(const Spectrum& s, const SampledWavelengths<N>& lambda) {
  return std::visit(
      [&lambda](const auto& kind) {
        if constexpr (requires { kind(lambda); }) {
          return kind(lambda);
        } else {
          SampledSpectrum<N> r;
          for (int i = 0; i < N; ++i) r[i] = kind(lambda[i]);
          return r;
        }
      },
      s);
}

}  // namespace prism
