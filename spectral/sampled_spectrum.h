#pragma once
// SampledSpectrum<N>: spectral quantities (radiance, throughput, reflectance) at the N
// wavelengths a path carries (see SampledWavelengths). Plain per-lane arithmetic.

#include <algorithm>
#include <array>
#include <cmath>

namespace prism {

// Default wavelengths per path (hero + 7 stratified companions; Wilkie et al. 2014). 8 instead of 4
// cuts the colour noise for little more time per sample, a better error per second
// (docs/performance.md, "Sampling choices").
inline constexpr int kDefaultWavelengths = 8;

template <int N>
class SampledSpectrum {
 public:
  static constexpr int size = N;
  constexpr SampledSpectrum() = default;
  constexpr explicit SampledSpectrum(float c) { v_.fill(c); }
  constexpr explicit SampledSpectrum(const std::array<float, N>& v) : v_(v) {}

  constexpr float operator[](int i) const { return v_[i]; }
  constexpr float& operator[](int i) { return v_[i]; }
  constexpr const std::array<float, N>& lanes() const { return v_; }

#define PRISM_LANEWISE(op)                                                \
  constexpr SampledSpectrum& operator op##=(const SampledSpectrum& b) {   \
    for (int i = 0; i < N; ++i) v_[i] op## = b.v_[i];                     \
    return *this;                                                         \
  }                                                                       \
  constexpr SampledSpectrum operator op(const SampledSpectrum& b) const { \
    SampledSpectrum r = *this;                                            \
    r op## = b;                                                           \
    return r;                                                             \
  }                                                                       \
  constexpr SampledSpectrum& operator op##=(float s) {                    \
    for (int i = 0; i < N; ++i) v_[i] op## = s;                           \
    return *this;                                                         \
  }                                                                       \
  constexpr SampledSpectrum operator op(float s) const {                  \
    SampledSpectrum r = *this;                                            \
    r op## = s;                                                           \
    return r;                                                             \
  }
  PRISM_LANEWISE(+)
  PRISM_LANEWISE(-)
  PRISM_LANEWISE(*)
  PRISM_LANEWISE(/)
#undef PRISM_LANEWISE

  friend constexpr SampledSpectrum operator*(float s, const SampledSpectrum& a) { return a * s; }

  constexpr bool is_zero() const {
    return std::all_of(v_.begin(), v_.end(), [](float x) { return x == 0.f; });
  }
  bool is_finite() const {
    return std::all_of(v_.begin(), v_.end(), [](float x) { return std::isfinite(x); });
  }
  constexpr float max() const { return *std::max_element(v_.begin(), v_.end()); }
  constexpr float min() const { return *std::min_element(v_.begin(), v_.end()); }
  constexpr float average() const {
    float s = 0;
    for (float x : v_) s += x;
    return s / N;
  }

 private:
  std::array<float, N> v_{};
};

// a / b per lane, 0 where b = 0 (a terminated wavelength has pdf 0 and contributes nothing).
template <int N>
constexpr SampledSpectrum<N> safe_div(const SampledSpectrum<N>& a, const SampledSpectrum<N>& b) {
  SampledSpectrum<N> r;
  for (int i = 0; i < N; ++i) r[i] = b[i] != 0.f ? a[i] / b[i] : 0.f;
  return r;
}

// exp per lane; large negative arguments underflow to exactly 0, never NaN.
template <int N>
SampledSpectrum<N> exp(const SampledSpectrum<N>& a) {
  SampledSpectrum<N> r;
  for (int i = 0; i < N; ++i) r[i] = std::exp(a[i]);
  return r;
}

}  // namespace prism
