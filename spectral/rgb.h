#pragma once
// Linear RGB triples and images in some named colour space (glTF colours are linear Rec.709 / sRGB).

#include <algorithm>
#include <vector>

namespace prism {

struct Rgb {
  float r = 0, g = 0, b = 0;
  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr float max() const { return std::max(r, std::max(g, b)); }
  constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
  constexpr Rgb operator/(float s) const { return {r / s, g / s, b / s}; }
  constexpr bool operator==(const Rgb&) const = default;
};

// The largest emitted radiance (or intensity) per channel Prism accepts: brighter emitters in a
// file are clamped to it with a warning, brighter command-line values refused. The film sums any
// finite sample exactly (core/render/fixed_point.h); this leaves a light sample's geometric factors
// and the wavelengths' weights a margin of 10^8 below the largest float before an estimate
// overflows (and is counted invalid).
inline constexpr float kMaxEmission = 1e30f;

// Luminance of linear Rec.709 RGB (ITU-R BT.709 weights).
constexpr float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// An image of linear RGB triples, interleaved, top row first.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;

  Rgb pixel(int x, int y) const {
    const float* p = &rgb[(size_t(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

// CIE 1931 tristimulus values.
struct Xyz {
  float x = 0, y = 0, z = 0;
  constexpr Xyz operator+(const Xyz& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Xyz operator*(float s) const { return {x * s, y * s, z * s}; }
};

}  // namespace prism
