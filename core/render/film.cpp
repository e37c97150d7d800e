#include "render/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prism {

Film::Film(int width, int height, uint32_t aovs, SpectralBins bins)
    : width_(width),
      height_(height),
      aovs_(aovs),
      bins_(std::move(bins)),
      sum_(pixel_count() * 3, 0.0),
      mean_(pixel_count() * 3, 0.0),
      m2_(pixel_count() * 3, 0.0),
      count_(pixel_count(), 0),
      aov_(aovs & (kAovAlbedo | kAovNormal | kAovDepth) ? pixel_count() * kAovFields : 0, 0.0),
      spectral_(pixel_count() * bins_.count(), 0.0) {}

void Film::add(size_t p, const FilmSample& s) {
  const bool finite = std::isfinite(s.xyz.x) && std::isfinite(s.xyz.y) && std::isfinite(s.xyz.z);
  const Xyz xyz = finite ? s.xyz : Xyz{0, 0, 0};
  double* sum = &sum_[p * 3];
  sum[0] += xyz.x;
  sum[1] += xyz.y;
  sum[2] += xyz.z;
  // Welford's update of the mean and of the sum of squared deviations.
  const uint32_t n = ++count_[p];
  const double x[3] = {xyz.x, xyz.y, xyz.z};
  for (int c = 0; c < 3; ++c) {
    const double delta = x[c] - mean_[p * 3 + c];
    mean_[p * 3 + c] += delta / n;
    m2_[p * 3 + c] += delta * (x[c] - mean_[p * 3 + c]);
  }
  if (!aov_.empty()) {
    double* a = &aov_[p * kAovFields];
    a[0] += s.albedo.x;
    a[1] += s.albedo.y;
    a[2] += s.albedo.z;
    a[3] += s.normal.x;
    a[4] += s.normal.y;
    a[5] += s.normal.z;
    if (s.hit) {
      a[6] += s.depth;
      a[7] += 1;
    }
  }
}

void Film::add_spectral(size_t p, float lambda, double weighted_radiance) {
  const int bin = bins_.find(lambda);
  if (bin >= 0 && std::isfinite(weighted_radiance)) spectral_[p * bins_.count() + bin] += weighted_radiance;
}

namespace {

// Per-pixel means of `fields` consecutive sums per pixel, each divided by the pixel's count.
std::vector<float> means(const std::vector<double>& sums, const std::vector<uint32_t>& count, int fields,
                         const std::vector<double>& scale = {}) {
  std::vector<float> out(sums.size());
  for (size_t p = 0; p < count.size(); ++p)
    for (int f = 0; f < fields; ++f) {
      const double n = std::max<uint32_t>(count[p], 1);
      out[p * fields + f] = float(sums[p * fields + f] / n * (scale.empty() ? 1.0 : scale[f]));
    }
  return out;
}

}  // namespace

std::vector<float> Film::xyz_image() const { return means(sum_, count_, 3); }

std::vector<float> Film::albedo_image() const {
  std::vector<float> out(pixel_count() * 3);
  for (size_t p = 0; p < pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = float(aov_[p * kAovFields + c] / std::max<uint32_t>(count_[p], 1));
  return out;
}

std::vector<float> Film::normal_image() const {
  std::vector<float> out(pixel_count() * 3);
  for (size_t p = 0; p < pixel_count(); ++p) {
    const double* a = &aov_[p * kAovFields + 3];
    const double length = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = length > 0 ? float(a[c] / length) : 0.f;
  }
  return out;
}

std::vector<float> Film::depth_image() const {
  std::vector<float> out(pixel_count());
  for (size_t p = 0; p < pixel_count(); ++p) {
    const double* a = &aov_[p * kAovFields + 6];
    out[p] = a[1] > 0 ? float(a[0] / a[1]) : std::numeric_limits<float>::infinity();
  }
  return out;
}

std::vector<float> Film::spectral_image() const {
  // Each lane's estimate L(λ)/p(λ) integrates L over the whole range; the part in a bin,
  // divided by the bin's width, is the bin's mean spectral radiance.
  std::vector<double> inv_width(bins_.count());
  for (int i = 0; i < bins_.count(); ++i) inv_width[i] = 1.0 / bins_.width(i);
  return means(spectral_, count_, bins_.count(), inv_width);
}

double Film::estimated_rel_rmse() const {
  double variance = 0, y = 0;
  for (size_t p = 0; p < pixel_count(); ++p) {
    variance += variance_of_mean(p);
    y += mean_y(p);
  }
  return y > 0 ? std::sqrt(variance / pixel_count()) / (y / pixel_count()) : 0.0;
}

double Film::pixel_rel_rmse_quantile(double q) const {
  std::vector<double> e;
  for (size_t p = 0; p < pixel_count(); ++p)
    if (mean_y(p) > 0) e.push_back(std::sqrt(variance_of_mean(p)) / mean_y(p));
  if (e.empty()) return 0.0;
  const size_t k = std::min(e.size() - 1, size_t(q * double(e.size())));
  std::nth_element(e.begin(), e.begin() + k, e.end());
  return e[k];
}

}  // namespace prism
