#include "core/render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace prism {

int adaptive_min_samples(double threshold) { return std::max(16, int(std::ceil(4.0 / std::sqrt(threshold)))); }

double adaptive_error(const Film& film, size_t p, const std::array<double, 3>& image_mean,
                      const OutputChannels& channels) {
  const double xyz[3] = {film.mean(p, 0), film.mean(p, 1), film.mean(p, 2)};
  std::array<double, 3> value, image;
  for (int k = 0; k < 3; ++k) {
    const auto& m = channels[k];
    value[k] = m[0] * xyz[0] + m[1] * xyz[1] + m[2] * xyz[2];
    image[k] = m[0] * image_mean[0] + m[1] * image_mean[1] + m[2] * image_mean[2];
  }
  const double magnitude = (std::abs(value[0]) + std::abs(value[1]) + std::abs(value[2])) / 3,
               image_magnitude = (std::abs(image[0]) + std::abs(image[1]) + std::abs(image[2])) / 3;
  double error = 0;
  for (int k = 0; k < 3; ++k) {
    const double variance = film.variance_of_mean(p, channels[k]);
    if (variance <= 0) continue;
    const double scale = value[k] > 0 && image[k] > 0 ? value[k] * image[k] : magnitude * image_magnitude;
    error = std::max(error, scale > 0 ? std::sqrt(variance / scale) : HUGE_VAL);
  }
  return error;
}

void find_unconverged(const Film& film, double threshold, std::vector<uint8_t>& active,
                      const OutputChannels& channels) {
  const size_t pixels = film.pixel_count();
  std::array<double, 3> image_mean{};
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) image_mean[c] += film.mean(p, c);
  for (double& m : image_mean) m /= double(pixels);
  const int min_samples = adaptive_min_samples(threshold);
  std::vector<uint8_t> noisy(pixels);
  for (size_t p = 0; p < pixels; ++p)
    noisy[p] = film.samples(p) < uint32_t(min_samples) || adaptive_error(film, p, image_mean, channels) > threshold;
  const int w = film.width(), h = film.height();
  active.assign(pixels, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t any = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && nx < w && ny >= 0 && ny < h) any |= noisy[size_t(ny) * w + nx];
        }
      active[size_t(y) * w + x] = any;
    }
}

}  // namespace prism
