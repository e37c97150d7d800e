#include "core/render/photon_grid.h"

#include <cmath>

namespace prism {

PhotonGrid::PhotonGrid(std::vector<Vec3f> points, float radius)
    : points_(std::move(points)),
      radius_(radius),
      radius2_(radius * radius),
      inv_cell_(1.f / (2.f * radius)),
      buckets_(uint32_t(std::max<size_t>(points_.size(), 1))) {
  const auto cell_bucket = [&](const Vec3f& p) {
    const Vec3f c = p * inv_cell_;
    return bucket(cell(c.x), cell(c.y), cell(c.z));
  };
  begin_.assign(size_t(buckets_) + 1, 0);
  for (const Vec3f& p : points_) ++begin_[cell_bucket(p) + 1];
  for (uint32_t b = 0; b < buckets_; ++b) begin_[b + 1] += begin_[b];
  order_.resize(points_.size());
  std::vector<uint32_t> next(begin_.begin(), begin_.end() - 1);
  for (uint32_t i = 0; i < uint32_t(points_.size()); ++i) order_[next[cell_bucket(points_[i])]++] = i;
}

}  // namespace prism
