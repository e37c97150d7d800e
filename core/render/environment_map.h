#pragma once
// An equirectangular (latitude-longitude) environment image: its radiance in any direction and
// its importance sampling.
//
// Mapping (glTF's +Y up): the direction at polar angle θ from +Y and azimuth φ is
//   d(θ, φ) = (−sin θ cos φ, cos θ, −sin θ sin φ),  at image coordinates u = φ / 2π, v = θ / π,
// u left to right and v from the top row (+Y) to the bottom row (−Y). The image centre looks
// along +X, u = 1/4 along −Z (where a glTF camera looks by default) and u = 3/4 along +Z; it is
// how Blender shows an equirectangular world after its glTF importer's change of axes. The
// rotation then turns the environment about +Y, right-handed (−Z towards −X for a positive angle).

#include <filesystem>
#include <optional>

#include "core/base/distribution.h"
#include "core/scene/scene.h"

namespace prism {

// Reads an .exr (RGB channels) or .hdr (Radiance RGBE) file; fails naming the file if it is
// missing, unreadable, of another kind, or holds non-finite values. Negative values (colours
// outside Rec.709) are clamped to 0.
EnvironmentMapDesc load_environment_map(const std::filesystem::path& file, float rotation_degrees, float scale);

// Refers to the description's image (which may be large), so the description must outlive it.
class EnvironmentMap {
 public:
  explicit EnvironmentMap(const EnvironmentMapDesc& desc);
  explicit EnvironmentMap(EnvironmentMapDesc&&) = delete;

  // Linear Rec.709 radiance arriving from direction w (bilinear between texel centres).
  Rgb radiance(const Vec3f& w) const;

  struct DirectionSample {
    Vec3f w;
    float pdf;  // solid-angle density
  };
  // Directions in proportion to the texels' luminance (see the constructor).
  std::optional<DirectionSample> sample(Vec2f u) const;
  float pdf(const Vec3f& w) const;

  // ∫ Y(L(ω)) dω over the sphere: the luminance the map sends towards a point.
  float luminance_integral() const { return luminance_integral_; }
  // The spectrum of the map's white (RGB 1, 1, 1) at luminance 1: the scene's (--env-spectrum), or D65.
  const DenselySampledSpectrum* white() const { return white_; }

  Vec2f uv(const Vec3f& w) const;
  Vec3f direction(Vec2f uv) const;

 private:
  Rgb bilinear(Vec2f uv) const;

  const RgbImage& image_;
  const DenselySampledSpectrum* white_;
  float scale_, cos_rotation_, sin_rotation_;
  PiecewiseConstant2D distribution_;
  float luminance_integral_ = 0;
};

}  // namespace prism
