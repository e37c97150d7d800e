#include "core/render/error_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace prism {

ErrorEstimate::ErrorEstimate(const Film& film) : film_(film) {
  std::array<double, 3> spread{}, iid{};
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const uint32_t na = film.samples(p), nb = film.second_replicate_samples(p);
    if (na == 0 || nb == 0) continue;
    ++replicated_pixels_;
    for (int c = 0; c < 3; ++c) {
      spread[c] += sqr(film.replicate_mean(p, c, 0) - film.replicate_mean(p, c, 1));
      // s²(1/n_A + 1/n_B), with s²/n = variance_of_mean over all n = n_A + n_B samples.
      iid[c] += film.variance_of_mean(p, c) * double(na + nb) * (1.0 / na + 1.0 / nb);
    }
  }
  for (int c = 0; c < 3; ++c)
    if (iid[c] > 0) calibration_[c] = spread[c] / iid[c];
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
