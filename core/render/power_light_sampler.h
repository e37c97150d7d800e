#pragma once
// Chooses a light for next-event estimation with probability proportional to its power.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "materials/bsdf_sample.h"

namespace prism {

class PowerLightSampler {
 public:
  PowerLightSampler() = default;
  // Lights of zero power are never chosen; if all have zero power, all are equally likely.
  explicit PowerLightSampler(const std::vector<float>& powers) {
    double total = 0;
    for (float p : powers) total += std::max(p, 0.f);
    const bool uniform = !(total > 0);
    double acc = 0;
    cdf_.reserve(powers.size());
    pmf_.reserve(powers.size());
    for (float p : powers) {
      const double w = uniform ? 1.0 / double(powers.size()) : std::max(p, 0.f) / total;
      pmf_.push_back(float(w));
      acc += w;
      cdf_.push_back(float(acc));
    }
    if (!cdf_.empty()) cdf_.back() = 1.f;
  }

  bool empty() const { return pmf_.empty(); }
  float pmf(uint32_t light) const { return pmf_[light]; }

  // The light whose CDF interval holds u ∈ [0, 1).
  uint32_t sample(float u) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    uint32_t i = uint32_t(std::min<ptrdiff_t>(it - cdf_.begin(), ptrdiff_t(cdf_.size()) - 1));
    while (pmf_[i] == 0.f && i > 0) --i;  // float ties at the boundary of a zero-power light
    return i;
  }
  // As sample(u), and u made uniform over [0, 1) again within the chosen light's interval.
  uint32_t sample_reusing(float& u) const {
    const uint32_t i = sample(u);
    u = within_lobe(u, i == 0 ? 0.f : cdf_[i - 1], pmf_[i]);
    return i;
  }

 private:
  std::vector<float> cdf_, pmf_;
};

}  // namespace prism
