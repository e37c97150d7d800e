#include "core/render/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prism {

namespace {
// The channel pairs of the products kept: XY, XZ, YZ.
constexpr std::pair<int, int> kCrossPairs[3] = {{0, 1}, {0, 2}, {1, 2}};
}  // namespace

Film::Film(int width, int height, uint32_t aovs, SpectralBins bins)
    : width_(width),
      height_(height),
      aovs_(aovs),
      bins_(std::move(bins)),
      sum_(pixel_count() * 3, 0),
      sq_(pixel_count() * 3, 0),
      cross_(pixel_count() * 3, 0),
      count_(pixel_count(), 0),
      second_sum_(pixel_count() * 3, 0),
      second_count_(pixel_count(), 0),
      aov_(aovs & (kAovAlbedo | kAovNormal | kAovDepth) ? pixel_count() * kAovFields : 0, 0),
      spectral_(pixel_count() * bins_.count(), 0),
      splat_(aovs & kFilmSplats ? pixel_count() * 3 : 0, 0),
      wide_(pixel_count()) {}

uint64_t Film::field_bytes_per_pixel(uint32_t aovs, const SpectralBins& bins) {
  const uint64_t fixed = 3 + 3 + 3 + 3 + (aovs & (kAovAlbedo | kAovNormal | kAovDepth) ? kAovFields : 0) +
                         bins.count() + (aovs & kFilmSplats ? 3 : 0);
  return fixed * sizeof(Fixed) + 2 * sizeof(uint32_t);
}

uint64_t Film::bytes_per_pixel(uint32_t aovs, const SpectralBins& bins) {
  return field_bytes_per_pixel(aovs, bins) + sizeof(std::unique_ptr<WideSums>);
}

Film::WideSums& Film::wide(size_t p) {
  if (!wide_[p]) {
    wide_[p] = std::make_unique<WideSums>();
    wide_[p]->spectral.resize(bins_.count());
  }
  return *wide_[p];
}

Film::FixedXyz Film::to_fixed_xyz(const Xyz& xyz) {
  const bool valid = std::isfinite(xyz.x) && std::isfinite(xyz.y) && std::isfinite(xyz.z);
  const double v[3] = {valid ? xyz.x : 0.f, valid ? xyz.y : 0.f, valid ? xyz.z : 0.f};
  FixedXyz f;
  f.has_wide = false;
  for (int c = 0; c < 3; ++c) {
    const bool fixed = fixed_in_range(v[c]);
    const double in_range = fixed ? v[c] : 0.0;
    f.value[c] = to_fixed(in_range), f.square[c] = to_fixed(in_range * in_range, kFixedSquareBits);
    f.wide[c] = fixed ? 0.0 : v[c];
    f.has_wide |= !fixed;
  }
  // The products XY, XZ, YZ: fixed-point while both channels are (the product stays below 2^62).
  for (int k = 0; k < 3; ++k) {
    const auto [a, b] = kCrossPairs[k];
    f.cross[k] = f.wide[a] == 0 && f.wide[b] == 0 ? to_fixed(v[a] * v[b], kFixedSquareBits) : Fixed(0);
  }
  f.valid = valid;
  return f;
}

bool Film::add_repeated(size_t p, const FixedXyz& xyz, uint32_t n, int replicate) {
  for (int c = 0; c < 3; ++c) {
    sum_[p * 3 + c] += n * xyz.value[c];
    sq_[p * 3 + c] += n * xyz.square[c];
    cross_[p * 3 + c] += n * xyz.cross[c];
    if (replicate != 0) second_sum_[p * 3 + c] += n * xyz.value[c];
  }
  if (xyz.has_wide) {
    WideSums& w = wide(p);
    const double v[3] = {xyz.wide[0] != 0 ? xyz.wide[0] : to_double(xyz.value[0]),
                         xyz.wide[1] != 0 ? xyz.wide[1] : to_double(xyz.value[1]),
                         xyz.wide[2] != 0 ? xyz.wide[2] : to_double(xyz.value[2])};
    for (int c = 0; c < 3; ++c)
      if (xyz.wide[c] != 0) {
        w.sum[c].add(xyz.wide[c], n);
        w.sq[c].add(xyz.wide[c] * xyz.wide[c], n);
        if (replicate != 0) w.second_sum[c].add(xyz.wide[c], n);
      }
    for (int k = 0; k < 3; ++k)  // a product with a wide channel is summed wide (rounded to an integer)
      if (const auto [a, b] = kCrossPairs[k]; xyz.wide[a] != 0 || xyz.wide[b] != 0) w.cross[k].add(v[a] * v[b], n);
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
  if (bin < 0 || !std::isfinite(weighted_radiance)) return;
  if (fixed_in_range(weighted_radiance))
    spectral_[p * bins_.count() + bin] += to_fixed(weighted_radiance);
  else
    wide(p).spectral[bin].add(weighted_radiance);
}

void Film::merge(const Film& other) {
  const auto add = [](auto& into, const auto& from) {
    for (size_t i = 0; i < into.size(); ++i) into[i] += from[i];
  };
  add(sum_, other.sum_), add(sq_, other.sq_), add(cross_, other.cross_), add(count_, other.count_),
      add(second_sum_, other.second_sum_), add(second_count_, other.second_count_), add(aov_, other.aov_),
      add(spectral_, other.spectral_), add(splat_, other.splat_);
  other.visit_wide([&](size_t p, const WideSums& from) {
    WideSums& into = wide(p);
    for (int c = 0; c < 3; ++c)
      into.sum[c] += from.sum[c], into.sq[c] += from.sq[c], into.cross[c] += from.cross[c],
          into.second_sum[c] += from.second_sum[c], into.splat[c] += from.splat[c];
    for (size_t b = 0; b < into.spectral.size(); ++b) into.spectral[b] += from.spectral[b];
  });
}

void Film::add_splats(const SplatBuffer& splats) {
  const std::vector<Fixed>& sums = splats.sums();
  for (size_t i = 0; i < splat_.size(); ++i) splat_[i] += sums[i];
  for (const SplatBuffer::WideSplat& s : splats.wide()) {
    WideSums& w = wide(s.pixel);
    const float v[3] = {s.xyz.x, s.xyz.y, s.xyz.z};
    for (int c = 0; c < 3; ++c) w.splat[c].add(v[c]);
  }
}

double Film::mean(size_t p, int c) const {
  const double wide = wide_value(p, [c](const WideSums& w) { return w.sum[c]; }) +
                      wide_value(p, [c](const WideSums& w) { return w.splat[c]; });
  return (to_double(sum_[p * 3 + c] + (splat_.empty() ? 0 : splat_[p * 3 + c])) + wide) / all_samples(p);
}

double Film::replicate_mean(size_t p, int c, int replicate) const {
  const double second =
      to_double(second_sum_[p * 3 + c]) + wide_value(p, [c](const WideSums& w) { return w.second_sum[c]; });
  if (replicate == 1) return second_count_[p] > 0 ? second / second_count_[p] : 0.0;
  const double all = to_double(sum_[p * 3 + c]) + wide_value(p, [c](const WideSums& w) { return w.sum[c]; });
  return count_[p] > 0 ? (all - second) / count_[p] : 0.0;
}

// s²/n of w · (X, Y, Z): Σ(w·v)² = Σᵢ wᵢ² Σvᵢ² + 2 Σᵢ<ⱼ wᵢwⱼ Σvᵢvⱼ, from the squares and products.
double Film::variance_of_mean(size_t p, const std::array<double, 3>& w) const {
  const uint32_t n = count_[p] + second_count_[p];
  if (n < 2) return 0.0;
  double sy = 0, sy2 = 0;
  for (int c = 0; c < 3; ++c) {
    sy += w[c] * (to_double(sum_[p * 3 + c]) + wide_value(p, [c](const WideSums& s) { return s.sum[c]; }));
    sy2 += w[c] * w[c] *
           (to_double(sq_[p * 3 + c], kFixedSquareBits) + wide_value(p, [c](const WideSums& s) { return s.sq[c]; }));
  }
  for (int k = 0; k < 3; ++k) {
    const auto [a, b] = kCrossPairs[k];
    sy2 +=
        2 * w[a] * w[b] *
        (to_double(cross_[p * 3 + k], kFixedSquareBits) + wide_value(p, [k](const WideSums& s) { return s.cross[k]; }));
  }
  return std::max(0.0, (sy2 - sy * sy / n) / (double(n - 1) * n));
}

// s²/n with s² = (Σy² − (Σy)²/n) / (n − 1), the unbiased sample variance, from the exact sums.
double Film::variance_of_mean(size_t p, int c) const {
  const uint32_t n = count_[p] + second_count_[p];
  if (n < 2) return 0.0;
  const double sy = to_double(sum_[p * 3 + c]) + wide_value(p, [c](const WideSums&w) { return w.sum[c]; }),
               sy2 = to_double(sq_[p * 3 + c], kFixedSquareBits) +
                     wide_value(p, [c](const WideSums&w) { return w.sq[c]; });
  return std::max(0.0, (sy2 - sy * sy / n) / (double(n - 1) * n));
}

std::vector<float> Film::xyz_image() const {
  std::vector<float> out(pixel_count() * 3);
  for (size_t p = 0; p < pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = float(mean(p, c));
  return out;
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
  const int bins = bins_.count();
  std::vector<float> out(spectral_.size());
  for (size_t p = 0; p < pixel_count(); ++p)
    for (int b = 0; b < bins; ++b) {
      const double sum =
          to_double(spectral_[p * bins + b]) + wide_value(p, [b](const WideSums& w) { return w.spectral[b]; });
      out[p * bins + b] = float(sum / all_samples(p) * (1.0 / bins_.width(b)));
    }
  return out;
}

}  // namespace prism
