#pragma once
// Small fixed-size vectors: Vec2<T>, Vec3<T> with the usual arithmetic. Points, directions and
// normals share one type; the functions that use them say which they expect.

#include <cmath>
#include <cstddef>

#include "core/base/math.h"

namespace prism {

template <typename T>
struct Vec2 {
  T x = 0, y = 0;
  constexpr Vec2() = default;
  constexpr Vec2(T x_, T y_) : x(x_), y(y_) {}
  constexpr T operator[](int i) const { return i == 0 ? x : y; }
  constexpr T& operator[](int i) { return i == 0 ? x : y; }
  constexpr Vec2 operator+(Vec2 b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2 operator-(Vec2 b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2 operator*(T s) const { return {x * s, y * s}; }
  constexpr bool operator==(const Vec2&) const = default;
};

template <typename T>
struct Vec3 {
  T x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <typename U>
  constexpr explicit Vec3(const Vec3<U>& v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}

  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3 operator-(const Vec3& b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3 operator*(const Vec3& b) const { return {x * b.x, y * b.y, z * b.z}; }
  constexpr Vec3 operator/(const Vec3& b) const { return {x / b.x, y / b.y, z / b.z}; }
  constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& b) {
    x -= b.x;
    y -= b.y;
    z -= b.z;
    return *this;
  }
  constexpr Vec3& operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3&) const = default;
};

template <typename T>
constexpr Vec3<T> operator*(T s, const Vec3<T>& v) {
  return v * s;
}

using Vec2f = Vec2<float>;
using Vec2i = Vec2<int>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

template <typename T>
constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr T abs_dot(const Vec3<T>& a, const Vec3<T>& b) {
  return std::abs(dot(a, b));
}

// Cross product; each component is evaluated as a difference of products in double so that
// nearly parallel float inputs do not lose the result to cancellation (pbrt-v4 §3.3.2).
inline Vec3f cross(const Vec3f& a, const Vec3f& b) {
  const auto dop = [](float p, float q, float r, float s) { return float(double(p) * q - double(r) * s); };
  return {dop(a.y, b.z, a.z, b.y), dop(a.z, b.x, a.x, b.z), dop(a.x, b.y, a.y, b.x)};
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <typename T>
constexpr T length_squared(const Vec3<T>& v) {
  return dot(v, v);
}
template <typename T>
T length(const Vec3<T>& v) {
  return std::sqrt(dot(v, v));
}
// Always inlined: its body is smaller than a call, and GCC's per-file inlining budget, spent by the
// BSDFs, had left it out of line in their evaluations.
template <typename T>
[[gnu::always_inline]] inline Vec3<T> normalize(const Vec3<T>& v) {
  return v / length(v);
}
template <typename T>
T distance(const Vec3<T>& a, const Vec3<T>& b) {
  return length(a - b);
}

template <typename T>
constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T>
Vec3<T> abs(const Vec3<T>& v) {
  return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}

// n flipped, if needed, to lie in the hemisphere of v.
template <typename T>
constexpr Vec3<T> face_forward(const Vec3<T>& n, const Vec3<T>& v) {
  return dot(n, v) < 0 ? -n : n;
}

inline bool is_finite(const Vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace prism
