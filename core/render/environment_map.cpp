#include "core/render/environment_map.h"

#include <algorithm>
#include <cctype>

#include "core/base/checksum.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/render/image_output.h"
#include "spectral/cie.h"

namespace prism {

EnvironmentMapDesc load_environment_map(const std::filesystem::path& file, float rotation_degrees, float scale) {
  const std::string name = file.string();
  if (!std::isfinite(rotation_degrees)) fail("{}: the rotation must be a finite number of degrees", name);
  if (!(scale >= 0 && std::isfinite(scale)))
    fail("{}: the scale must be finite and non-negative (got {})", name, scale);
  if (!std::filesystem::is_regular_file(file)) fail("{}: no such file", name);
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".exr" && ext != ".hdr") fail("{}: environment maps must be .exr or .hdr files", name);
  RgbImage image = ext == ".exr" ? read_exr(file) : read_hdr(file);
  if (image.width < 1 || image.height < 1) fail("{}: the image is empty", name);
  size_t negative = 0;
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    if (!std::isfinite(image.rgb[i]))
      fail("{}: pixel ({}, {}) is not finite", name, i / 3 % image.width, i / 3 / image.width);
    if (image.rgb[i] < 0) ++negative, image.rgb[i] = 0;
  }
  const float brightest = *std::max_element(image.rgb.begin(), image.rgb.end());
  if (brightest > kMaxEmission)
    fail("{}: a value of {:g} exceeds {:g}, the brightest radiance Prism accepts", name, brightest, kMaxEmission);
  if (double(brightest) * scale > kMaxEmission)
    fail("{}: --env-scale {:g} makes its brightest value {:g}, over the {:g} Prism accepts", name, scale,
         double(brightest) * scale, kMaxEmission);
  if (negative > 0) log::warn("{}: {} negative values (outside Rec.709) set to 0", name, negative);
  Checksum hash;
  hash.add(&image.width, sizeof image.width), hash.add(&image.height, sizeof image.height);
  hash.add(image.rgb.data(), image.rgb.size() * sizeof(float));
  return {name, std::move(image), radians(rotation_degrees), scale, hash.h, std::nullopt};
}

EnvironmentMap::EnvironmentMap(const EnvironmentMapDesc& desc)
    : image_(desc.image),
      white_(desc.white ? &*desc.white : &cie().d65),
      scale_(desc.scale),
      cos_rotation_(std::cos(desc.rotation)),
      sin_rotation_(std::sin(desc.rotation)) {
  const int w = image_.width, h = image_.height;
  if (w < 1 || h < 1 || image_.rgb.size() != size_t(w) * h * 3) fail("{}: malformed environment image", desc.file);
  std::vector<float> lum(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) lum[size_t(y) * w + x] = luminance(image_.pixel(x, y));
  // Sampling weight of a texel: the bilinear luminance averaged over its centre and four corners
  // (each corner the mean of four texels), so that every direction the lookup makes bright has
  // a non-zero pdf; times sin θ, the solid angle of a lat-long texel per unit of (u, v).
  const auto at = [&](int x, int y) { return lum[size_t(std::clamp(y, 0, h - 1)) * w + (x + w) % w]; };
  // corners[y·w + x]: the grid point at the top left of texel (x, y); columns wrap, so w per row.
  std::vector<float> corners(size_t(w) * (h + 1));
  for (int y = 0; y <= h; ++y)
    for (int x = 0; x < w; ++x)
      corners[size_t(y) * w + x] = (at(x - 1, y - 1) + at(x, y - 1) + at(x - 1, y) + at(x, y)) / 4;
  const auto corner = [&](int x, int y) { return corners[size_t(y) * w + x % w]; };
  std::vector<float> weights(size_t(w) * h);
  double integral = 0;
  for (int y = 0; y < h; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(h));
    for (int x = 0; x < w; ++x) {
      const float mean = (at(x, y) + corner(x, y) + corner(x + 1, y) + corner(x, y + 1) + corner(x + 1, y + 1)) / 5;
      weights[size_t(y) * w + x] = mean * sin_theta;
      integral += double(at(x, y)) * sin_theta;
    }
  }
  distribution_ = PiecewiseConstant2D(weights, w, h);
  // Midpoint rule for ∫∫ Y sin θ dθ dφ, each texel spanning Δθ = π / h and Δφ = 2π / w.
  luminance_integral_ = float(integral * scale_ * (2 * kPi / w) * (kPi / h));
}

Vec2f EnvironmentMap::uv(const Vec3f& w) const {
  // Into the image's frame: rotate by −rotation about +Y.
  const Vec3f d(w.x * cos_rotation_ - w.z * sin_rotation_, w.y, w.x * sin_rotation_ + w.z * cos_rotation_);
  float phi = std::atan2(-d.z, -d.x);
  if (phi < 0) phi += 2 * kPi;
  return {phi * kInv2Pi, safe_acos(d.y) * kInvPi};
}

Vec3f EnvironmentMap::direction(Vec2f uv) const {
  const float theta = kPi * uv.y, phi = 2 * kPi * uv.x;
  const float sin_theta = std::sin(theta);
  const Vec3f d(-sin_theta * std::cos(phi), std::cos(theta), -sin_theta * std::sin(phi));
  return {d.x * cos_rotation_ + d.z * sin_rotation_, d.y, -d.x * sin_rotation_ + d.z * cos_rotation_};
}

Rgb EnvironmentMap::bilinear(Vec2f uv) const {
  const int w = image_.width, h = image_.height;
  const float x = uv.x * float(w) - 0.5f, y = uv.y * float(h) - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  // Columns wrap around in azimuth; rows clamp at the poles.
  const int xa = ((int(x0) % w) + w) % w, xb = (xa + 1) % w;
  const int ya = std::clamp(int(y0), 0, h - 1), yb = std::clamp(int(y0) + 1, 0, h - 1);
  Rgb c;
  for (int k = 0; k < 3; ++k) {
    const auto at = [&](int px, int py) { return image_.rgb[(size_t(py) * w + px) * 3 + k]; };
    c[k] = (1 - fy) * ((1 - fx) * at(xa, ya) + fx * at(xb, ya)) + fy * ((1 - fx) * at(xa, yb) + fx * at(xb, yb));
  }
  return c;
}

Rgb EnvironmentMap::radiance(const Vec3f& w) const { return bilinear(uv(w)) * scale_; }

// p(u, v) du dv = pdf(ω) dω with dω = sin θ dθ dφ = 2π² sin θ du dv.
std::optional<EnvironmentMap::DirectionSample> EnvironmentMap::sample(Vec2f u) const {
  const auto s = distribution_.sample(u);
  const float sin_theta = std::sin(kPi * s.p.y);
  if (!(s.pdf > 0) || sin_theta <= 0) return std::nullopt;
  return DirectionSample{direction(s.p), s.pdf / (2 * kPi * kPi * sin_theta)};
}

float EnvironmentMap::pdf(const Vec3f& w) const {
  const Vec2f p = uv(w);
  const float sin_theta = std::sin(kPi * p.y);
  return sin_theta > 0 ? distribution_.pdf(p) / (2 * kPi * kPi * sin_theta) : 0.f;
}

}  // namespace prism
