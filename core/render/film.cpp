#include "core/render/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prism {

Film::Film(int width, int height, uint32_t aovs, SpectralBins bins)
    : width_(width),
      height_(height),
      aovs_(aovs),
      bins_(std::move(bins)),
      sum_(pixel_count() * 3, 0),
      sq_(pixel_count() * 3, 0),
      count_(pixel_count(), 0),
      second_sum_(pixel_count() * 3, 0),
      second_count_(pixel_count(), 0),
      aov_(aovs & (kAovAlbedo | kAovNormal | kAovDepth) ? pixel_count() * kAovFields : 0, 0),
      spectral_(pixel_count() * bins_.count(), 0),
      splat_(aovs & kFilmSplats ? pixel_count() * 3 : 0, 0) {}

uint64_t Film::bytes_per_pixel(uint32_t aovs, const SpectralBins& bins) {
  const uint64_t fixed = 3 + 3 + 3 + (aovs & (kAovAlbedo | kAovNormal | kAovDepth) ? kAovFields : 0) + bins.count() +
                         (aovs & kFilmSplats ? 3 : 0);
  return fixed * sizeof(Fixed) + 2 * sizeof(uint32_t);
}

Film::FixedXyz Film::to_fixed_xyz(const Xyz& xyz) {
  const bool valid = fixed_in_range(xyz.x) && fixed_in_range(xyz.y) && fixed_in_range(xyz.z);
  const double v[3] = {valid ? xyz.x : 0.f, valid ? xyz.y : 0.f, valid ? xyz.z : 0.f};
  FixedXyz f;
  for (int c = 0; c < 3; ++c) f.value[c] = to_fixed(v[c]), f.square[c] = to_fixed(v[c] * v[c], kFixedSquareBits);
  f.valid = valid;
  return f;
}

bool Film::add_repeated(size_t p, const FixedXyz& xyz, uint32_t n, int replicate) {
  for (int c = 0; c < 3; ++c) {
    sum_[p * 3 + c] += n * xyz.value[c];
    sq_[p * 3 + c] += n * xyz.square[c];
    if (replicate != 0) second_sum_[p * 3 + c] += n * xyz.value[c];
  }
  (replicate == 0 ? count_ : second_count_)[p] += n;
  return xyz.valid;
}

bool Film::add(size_t p, const FilmSample& s, int replicate) {
  const bool valid = add_repeated(p, to_fixed_xyz(s.xyz), 1, replicate);
  if (!aov_.empty() && valid) {
    Fixed* a = &aov_[p * kAovFields];
    const float values[6] = {s.albedo.x, s.albedo.y, s.albedo.z, s.normal.x, s.normal.y, s.normal.z};
    if (std::all_of(values, values + 6, [](float v) { return fixed_in_range(v); }))
      for (int i = 0; i < 6; ++i) a[i] += to_fixed(values[i]);
    if (s.hit && fixed_in_range(s.depth)) {
      a[6] += to_fixed(s.depth);
      a[7] += to_fixed(1.0);
    }
  }
  return valid;
}

void Film::add_spectral(size_t p, float lambda, double weighted_radiance) {
  const int bin = bins_.find(lambda);
  if (bin >= 0 && fixed_in_range(weighted_radiance)) spectral_[p * bins_.count() + bin] += to_fixed(weighted_radiance);
}

void Film::merge(const Film& other) {
  const auto add = [](auto& into, const auto& from) {
    for (size_t i = 0; i < into.size(); ++i) into[i] += from[i];
  };
  add(sum_, other.sum_), add(sq_, other.sq_), add(count_, other.count_), add(second_sum_, other.second_sum_),
      add(second_count_, other.second_count_), add(aov_, other.aov_), add(spectral_, other.spectral_),
      add(splat_, other.splat_);
}

void Film::add_splats(const std::vector<Fixed>& xyz_sums) {
  for (size_t i = 0; i < splat_.size(); ++i) splat_[i] += xyz_sums[i];
}

double Film::mean(size_t p, int c) const {
  return to_double(sum_[p * 3 + c] + (splat_.empty() ? 0 : splat_[p * 3 + c])) / all_samples(p);
}

double Film::replicate_mean(size_t p, int c, int replicate) const {
  const double second = to_double(second_sum_[p * 3 + c]);
  if (replicate == 1) return second_count_[p] > 0 ? second / second_count_[p] : 0.0;
  return count_[p] > 0 ? (to_double(sum_[p * 3 + c]) - second) / count_[p] : 0.0;
}

// s²/n with s² = (Σy² − (Σy)²/n) / (n − 1), the unbiased sample variance, from the exact sums.
double Film::variance_of_mean(size_t p, int c) const {
  const uint32_t n = count_[p] + second_count_[p];
  if (n < 2) return 0.0;
  const double sy = to_double(sum_[p * 3 + c]), sy2 = to_double(sq_[p * 3 + c], kFixedSquareBits);
  return std::max(0.0, (sy2 - sy * sy / n) / (double(n - 1) * n));
}

// Per-pixel means of `fields` consecutive sums per pixel, each divided by the pixel's count.
std::vector<float> Film::means(const std::vector<Fixed>& sums, int fields, const std::vector<double>& scale) const {
  std::vector<float> out(sums.size());
  for (size_t p = 0; p < pixel_count(); ++p)
    for (int f = 0; f < fields; ++f)
      out[p * fields + f] = float(to_double(sums[p * fields + f]) / all_samples(p) * (scale.empty() ? 1.0 : scale[f]));
  return out;
}

std::vector<float> Film::xyz_image() const {
  if (splat_.empty()) return means(sum_, 3);
  std::vector<Fixed> total = sum_;
  for (size_t i = 0; i < total.size(); ++i) total[i] += splat_[i];
  return means(total, 3);
}

std::vector<float> Film::albedo_image() const {
  std::vector<float> out(pixel_count() * 3);
  for (size_t p = 0; p < pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = float(to_double(aov_[p * kAovFields + c]) / all_samples(p));
  return out;
}

std::vector<float> Film::normal_image() const {
  std::vector<float> out(pixel_count() * 3);
  for (size_t p = 0; p < pixel_count(); ++p) {
    const double a[3] = {to_double(aov_[p * kAovFields + 3]), to_double(aov_[p * kAovFields + 4]),
                         to_double(aov_[p * kAovFields + 5])};
    const double length = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = length > 0 ? float(a[c] / length) : 0.f;
  }
  return out;
}

std::vector<float> Film::depth_image() const {
  std::vector<float> out(pixel_count());
  for (size_t p = 0; p < pixel_count(); ++p) {
    const double a[2] = {to_double(aov_[p * kAovFields + 6]), to_double(aov_[p * kAovFields + 7])};
    out[p] = a[1] > 0 ? float(a[0] / a[1]) : std::numeric_limits<float>::infinity();
  }
  return out;
}

std::vector<float> Film::spectral_image() const {
  // Each lane's estimate L(λ)/p(λ) integrates L over the whole range; the part in a bin,
  // divided by the bin's width, is the bin's mean spectral radiance.
  std::vector<double> inv_width(bins_.count());
  for (int i = 0; i < bins_.count(); ++i) inv_width[i] = 1.0 / bins_.width(i);
  return means(spectral_, bins_.count(), inv_width);
}

}  // namespace prism
