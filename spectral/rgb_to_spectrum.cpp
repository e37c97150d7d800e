#include "spectral/rgb_to_spectrum.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include "core/base/data_path.h"
#include "core/base/error.h"

namespace prism {

RgbToSpectrumTable::RgbToSpectrumTable(int resolution, std::vector<float> z_nodes, std::vector<float> coefficients)
    : res_(resolution), z_nodes_(std::move(z_nodes)), coeffs_(std::move(coefficients)) {
  if (res_ < 2 || int(z_nodes_.size()) != res_ || coeffs_.size() != size_t(3) * res_ * res_ * res_ * 3)
    fail("RGB-to-spectrum table of resolution {} has inconsistent sizes", res_);
}

RgbToSpectrumTable RgbToSpectrumTable::load(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8];
  uint32_t res = 0;
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || !in.read(reinterpret_cast<char*>(&res), 4) ||
      res < 2 || res > 1024)
    fail("{}: not a Prism RGB-to-spectrum table", file.string());
  std::vector<float> z(res), coeffs(size_t(3) * res * res * res * 3);
  if (!in.read(reinterpret_cast<char*>(z.data()), std::streamsize(z.size() * 4)) ||
      !in.read(reinterpret_cast<char*>(coeffs.data()), std::streamsize(coeffs.size() * 4)))
    fail("{}: truncated RGB-to-spectrum table", file.string());
  return RgbToSpectrumTable(int(res), std::move(z), std::move(coeffs));
}

void RgbToSpectrumTable::save(const std::filesystem::path& file) const {
  std::ofstream out(file, std::ios::binary);
  const uint32_t res = uint32_t(res_);
  out.write(kMagic, 8);
  out.write(reinterpret_cast<const char*>(&res), 4);
  out.write(reinterpret_cast<const char*>(z_nodes_.data()), std::streamsize(z_nodes_.size() * 4));
  out.write(reinterpret_cast<const char*>(coeffs_.data()), std::streamsize(coeffs_.size() * 4));
  if (!out) fail("{}: cannot write", file.string());
}

const RgbToSpectrumTable& RgbToSpectrumTable::srgb() {
  static const RgbToSpectrumTable table = load(data_file("spectra/srgb_sigmoid.coeff"));
  return table;
}

std::array<float, 3> RgbToSpectrumTable::coefficients(int l, int zi, int yi, int xi) const {
  const size_t base = ((((size_t(l) * res_ + zi) * res_ + yi) * res_) + xi) * 3;
  return {coeffs_[base], coeffs_[base + 1], coeffs_[base + 2]};
}

RgbSigmoidPolynomial RgbToSpectrumTable::operator()(Rgb rgb) const {
  // The table covers [0, 1]^3: anything else (NaN included, read as 0) is clamped into it, so
  // no input can index outside the table.
  for (int c = 0; c < 3; ++c) rgb[c] = std::isnan(rgb[c]) ? 0.f : std::clamp(rgb[c], 0.f, 1.f);
  // Grey: s(c2) = v exactly for c2 = (v − 1/2) / sqrt(v (1 − v)) (v = 1 gives +∞ → s = 1).
  if (rgb.r == rgb.g && rgb.g == rgb.b) {
    const float v = rgb.r;
    return {0, 0, (v - 0.5f) / std::sqrt(v * (1 - v))};
  }
  const int l = rgb.r > rgb.g ? (rgb.r > rgb.b ? 0 : 2) : (rgb.g > rgb.b ? 1 : 2);
  const float z = rgb[l];
  const float x = rgb[(l + 1) % 3] * float(res_ - 1) / z;
  const float y = rgb[(l + 2) % 3] * float(res_ - 1) / z;

  const int xi = std::min(int(x), res_ - 2), yi = std::min(int(y), res_ - 2);
  const int zi = int(
      std::clamp<ptrdiff_t>(std::upper_bound(z_nodes_.begin(), z_nodes_.end(), z) - z_nodes_.begin() - 1, 0, res_ - 2));
  const float dx = x - float(xi), dy = y - float(yi);
  const float dz = std::clamp((z - z_nodes_[zi]) / (z_nodes_[zi + 1] - z_nodes_[zi]), 0.f, 1.f);

  // Trilinear interpolation of the three coefficients.
  float c[3] = {0, 0, 0};
  for (int k = 0; k < 8; ++k) {
    const int ox = k & 1, oy = (k >> 1) & 1, oz = k >> 2;
    const float w = (ox ? dx : 1 - dx) * (oy ? dy : 1 - dy) * (oz ? dz : 1 - dz);
    const auto coeff = coefficients(l, zi + oz, yi + oy, xi + ox);
    for (int i = 0; i < 3; ++i) c[i] += w * coeff[i];
  }
  return {c[0], c[1], c[2]};
}

}  // namespace prism
