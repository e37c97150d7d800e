#pragma once
// Fixed-radius neighbours among points (the photons of vertex merging): a uniform grid of cells
// of side 2r, hashed into as many buckets as there are points (Teschner et al. 2003, "Optimized
// Spatial Hashing"), the points ordered by bucket with a counting sort. A query visits the
// 2 × 2 × 2 cells a ball of radius r can overlap, each bucket once.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/vec.h"

namespace prism {

class PhotonGrid {
 public:
  PhotonGrid() = default;
  PhotonGrid(std::vector<Vec3f> points, float radius);

  float radius() const { return radius_; }

  // Calls f(i) for every point i within the radius of p, in an order fixed by the points alone.
  template <typename F>
  void for_each_near(const Vec3f& p, F&& f) const {
    if (order_.empty()) return;
    const Vec3f c = p * inv_cell_ - Vec3f(0.5f, 0.5f, 0.5f);
    const int x0 = cell(c.x), y0 = cell(c.y), z0 = cell(c.z);
    std::array<uint32_t, 8> seen;
    int count = 0;
    for (int i = 0; i < 8; ++i) {
      const uint32_t b = bucket(x0 + (i & 1), y0 + (i >> 1 & 1), z0 + (i >> 2));
      bool again = false;
      for (int k = 0; k < count; ++k) again |= seen[k] == b;
      if (again) continue;
      seen[count++] = b;
      for (uint32_t j = begin_[b]; j < begin_[b + 1]; ++j)
        if (length_squared(points_[order_[j]] - p) <= radius2_) f(order_[j]);
    }
  }

 private:
  // The cell coordinate of c (in cells), clamped so that far-away points cannot overflow (and NaN,
  // which fails every comparison, taken as the lowest cell).
  static int cell(float c) { return c >= -2e9f ? int(std::min(std::floor(c), 2e9f)) : -2000000000; }
  uint32_t bucket(int x, int y, int z) const {
    return ((uint32_t(x) * 73856093u) ^ (uint32_t(y) * 19349663u) ^ (uint32_t(z) * 83492791u)) % buckets_;
  }

  std::vector<Vec3f> points_;
  float radius_ = 0, radius2_ = 0, inv_cell_ = 0;
  uint32_t buckets_ = 0;
  std::vector<uint32_t> begin_, order_;  // bucket b holds order_[begin_[b], begin_[b + 1])
};

}  // namespace prism
