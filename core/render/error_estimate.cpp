#include "core/render/error_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace prism {

ErrorEstimate::ErrorEstimate(const Film& film, const OutputChannels& output) : film_(film), output_(output) {
  std::array<double, 3> spread{}, iid{}, output_spread{}, output_iid{};
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const uint32_t na = film.samples(p), nb = film.second_replicate_samples(p);
    if (na == 0 || nb == 0) continue;
    ++replicated_pixels_;
    std::array<double, 3> difference;
    for (int c = 0; c < 3; ++c) {
      difference[c] = film.replicate_mean(p, c, 0) - film.replicate_mean(p, c, 1);
      spread[c] += sqr(difference[c]);
      // s²(1/n_A + 1/n_B), with s²/n = variance_of_mean over all n = n_A + n_B samples.
      iid[c] += film.variance_of_mean(p, c) * double(na + nb) * (1.0 / na + 1.0 / nb);
    }
    for (int k = 0; k < 3; ++k) {
      const auto& m = output[k];
      output_spread[k] += sqr(m[0] * difference[0] + m[1] * difference[1] + m[2] * difference[2]);
      output_iid[k] += film.variance_of_mean(p, m) * double(na + nb) * (1.0 / na + 1.0 / nb);
    }
  }
  for (int c = 0; c < 3; ++c) {
    if (iid[c] > 0) calibration_[c] = spread[c] / iid[c];
    if (output_iid[c] > 0) output_calibration_[c] = output_spread[c] / output_iid[c];
  }
}

double ErrorEstimate::output_rel_rmse() const {
  double variance = 0, sum = 0;
  for (size_t p = 0; p < film_.pixel_count(); ++p) {
    const double xyz[3] = {film_.mean(p, 0), film_.mean(p, 1), film_.mean(p, 2)};
    for (int k = 0; k < 3; ++k) {
      variance += output_variance_of_mean(p, k);
      sum += output_[k][0] * xyz[0] + output_[k][1] * xyz[1] + output_[k][2] * xyz[2];
    }
  }
  const double n = 3.0 * double(film_.pixel_count());
  return sum > 0 ? std::sqrt(variance / n) / (sum / n) : 0.0;
}

double ErrorEstimate::rel_rmse() const {
  double variance = 0, y = 0;
  for (size_t p = 0; p < film_.pixel_count(); ++p) {
    variance += variance_of_mean(p, 1);
    y += film_.mean_y(p);
  }
  return y > 0 ? std::sqrt(variance / film_.pixel_count()) / (y / film_.pixel_count()) : 0.0;
}

double ErrorEstimate::pixel_rel_rmse_quantile(double q) const {
  std::vector<double> e;
  for (size_t p = 0; p < film_.pixel_count(); ++p)
    if (film_.mean_y(p) > 0) e.push_back(std::sqrt(variance_of_mean(p, 1)) / film_.mean_y(p));
  if (e.empty()) return 0.0;
  const size_t k = std::min(e.size() - 1, size_t(q * double(e.size())));
  std::nth_element(e.begin(), e.begin() + k, e.end());
  return e[k];
}

}  // namespace prism
