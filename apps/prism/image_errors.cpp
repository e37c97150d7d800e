#include "apps/prism/image_errors.h"

#include <algorithm>
#include <cmath>

namespace prism {

ImageErrors image_errors(const std::vector<float>& image, const std::vector<float>& reference) {
  double se = 0, rel = 0, sum = 0, ref_sum = 0;
  for (size_t i = 0; i < image.size(); ++i) {
    const double d = double(image[i]) - reference[i];
    se += d * d;
    rel += d * d / (double(reference[i]) * reference[i] + 0.01);
    sum += image[i];
    ref_sum += reference[i];
  }
  const double n = double(image.size());
  return {std::sqrt(se / n), rel / n, (sum - ref_sum) / n, ref_sum / n};
}

std::vector<float> display_encoded(const std::vector<float>& linear) {
  std::vector<float> encoded(linear.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    const float v = std::min(std::max(0.f, linear[i]), 1.f);  // NaN → 0
    encoded[i] = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
  }
  return encoded;
}

}  // namespace prism
