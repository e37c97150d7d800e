#pragma once
// Scalar helpers used everywhere: constants, clamping, safe inverse trig, a vectorisable sin/cos,
// float error bounds.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace prism {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
inline constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;

template <typename T>
constexpr T sqr(T x) {
  return x * x;
}

template <typename T>
constexpr T lerp(float t, T a, T b) {
  return (1 - t) * a + t * b;
}

template <typename T, typename U, typename V>
constexpr T clamp(T x, U lo, V hi) {
  return x < lo ? T(lo) : (x > hi ? T(hi) : x);
}

inline float safe_sqrt(float x) { return std::sqrt(std::max(0.f, x)); }
inline double safe_sqrt(double x) { return std::sqrt(std::max(0., x)); }
inline float safe_acos(float x) { return std::acos(clamp(x, -1.f, 1.f)); }

inline float radians(float degrees) { return degrees * (kPi / 180.f); }
inline float degrees(float radians) { return radians * (180.f / kPi); }

// gamma(n) = n·ε / (1 − n·ε): bound on the relative error of n chained float operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1; pbrt-v4 §6.8.1).
constexpr float gamma(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

// The next representable float above / below v (for conservative rounding).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.f) return v;
  if (v == -0.f) v = 0.f;
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = v >= 0 ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.f) return v;
  if (v == 0.f) v = -0.f;
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = v > 0 ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

// sin x and cos x in plain arithmetic (no library call, so loops over a path's lanes vectorise),
// for |x| up to ~10⁴: x less the nearest multiple q of π/2 (Cody & Waite's reduction, π/2 split
// into three floats whose products with q are exact, as in Cephes' sinf), r ∈ [−π/4, π/4], then
// the Taylor polynomials of sin r to r⁷ and cos r to r⁸, turned to x's quadrant q mod 4. Within
// 4·10⁻⁷ of sin and cos over that range (tests/base/test_base.cpp).
struct SinCos {
  float sin, cos;
};
inline SinCos sin_cos(float x) {
  const float t = x * 0.636619772f + 0.5f;  // 2/π; q = ⌊t⌋ by truncation, which vectorises
  int n = int(t);
  n -= float(n) > t;
  const float q = float(n);
  const float r = ((x - q * 1.5703125f) - q * 4.837512969970703125e-4f) - q * 7.54978995489188216e-8f, r2 = r * r;
  const float s = r + r * r2 * (-1.f / 6 + r2 * (1.f / 120 + r2 * (-1.f / 5040)));
  const float c = 1 + r2 * (-0.5f + r2 * (1.f / 24 + r2 * (-1.f / 720 + r2 * (1.f / 40320))));
  const float sin_r = n & 1 ? c : s, cos_r = n & 1 ? s : c;  // the quadrant's swap of sin and cos
  return {n & 2 ? -sin_r : sin_r, (n + 1) & 2 ? -cos_r : cos_r};
}

// Balance heuristic (Veach 1997, §9.2.2): weight of a sample from f among f and g.
inline float balance_heuristic(float pdf_f, float pdf_g) {
  if (std::isinf(pdf_f)) return 1.f;
  return pdf_f + pdf_g > 0.f ? pdf_f / (pdf_f + pdf_g) : 0.f;
}

}  // namespace prism
