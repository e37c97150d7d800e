#include "accel/bvh.h"

#include <algorithm>
#include <array>

namespace prism {

namespace {

constexpr int kBins = 16;
constexpr float kTraversalCost = 1.f;  // SAH: cost of a box test relative to a primitive test

struct BuildItem {
  Bounds3f bounds;
  Vec3f centroid;
  uint32_t prim;
};

struct Split {
  int axis = -1;
  int bin = 0;  // primitives in bins [0, bin] go left
  float cost = kInfinity;
};

int bin_of(float c, float lo, float scale) { return std::clamp(int((c - lo) * scale), 0, kBins - 1); }

// Best binned-SAH split of items over the centroid bounds (all three axes tried).
Split find_split(std::span<const BuildItem> items, const Bounds3f& centroid_bounds) {
  Split best;
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = centroid_bounds.lo[axis], extent = centroid_bounds.hi[axis] - lo;
    if (!(extent > 0.f)) continue;
    const float scale = kBins / extent;
    std::array<Bounds3f, kBins> bin_bounds;
    std::array<int, kBins> bin_count{};
    for (const BuildItem& it : items) {
      const int b = bin_of(it.centroid[axis], lo, scale);
      bin_bounds[b].extend(it.bounds);
      ++bin_count[b];
    }
    // Sweep from the right to get the area and count of every right-hand side, then from the left.
    std::array<float, kBins> right_area{};
    std::array<int, kBins> right_count{};
    Bounds3f acc;
    int n = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.extend(bin_bounds[b]);
      n += bin_count[b];
      right_area[b] = acc.surface_area();
      right_count[b] = n;
    }
    acc = Bounds3f{};
    n = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      acc.extend(bin_bounds[b]);
      n += bin_count[b];
      if (n == 0 || right_count[b + 1] == 0) continue;
      const float cost = acc.surface_area() * float(n) + right_area[b + 1] * float(right_count[b + 1]);
      if (cost < best.cost) best = {axis, b, cost};
    }
  }
  return best;
}

class Builder {
 public:
  Builder(std::vector<BuildItem>& items, int max_leaf) : items_(items), max_leaf_(max_leaf) {}

  uint32_t build(uint32_t begin, uint32_t end) {
    const uint32_t node_index = uint32_t(nodes.size());
    nodes.push_back({});
    Bounds3f bounds, centroid_bounds;
    for (uint32_t i = begin; i < end; ++i) {
      bounds.extend(items_[i].bounds);
      centroid_bounds.extend(items_[i].centroid);
    }
    const uint32_t count = end - begin;
    Split split = count > 1 ? find_split({items_.data() + begin, count}, centroid_bounds) : Split{};
    // SAH leaf test: the split's cost, relative to this node's area, against testing every primitive.
    const float split_cost = kTraversalCost + split.cost / std::max(bounds.surface_area(), 1e-30f);
    if (count <= uint32_t(max_leaf_) && float(count) <= split_cost) {
      nodes[node_index] = {bounds, begin, uint16_t(count), 0};
      return node_index;
    }
    uint32_t mid = begin + count / 2;  // coincident centroids: no split is better than another
    if (split.axis >= 0) {
      const float lo = centroid_bounds.lo[split.axis];
      const float scale = kBins / (centroid_bounds.hi[split.axis] - lo);
      auto* mid_ptr = std::partition(items_.data() + begin, items_.data() + end, [&](const BuildItem& it) {
        return bin_of(it.centroid[split.axis], lo, scale) <= split.bin;
      });
      mid = uint32_t(mid_ptr - items_.data());
    } else {
      split.axis = 0;
    }
    build(begin, mid);
    const uint32_t right = build(mid, end);
    nodes[node_index] = {bounds, right, 0, uint16_t(split.axis)};
    return node_index;
  }

  std::vector<BvhNode> nodes;

 private:
  std::vector<BuildItem>& items_;
  int max_leaf_;
};

}  // namespace

Bvh Bvh::build(std::span<const Bounds3f> prim_bounds, int max_leaf_size) {
  Bvh bvh;
  if (prim_bounds.empty()) return bvh;
  std::vector<BuildItem> items;
  items.reserve(prim_bounds.size());
  for (uint32_t i = 0; i < prim_bounds.size(); ++i)
    if (!prim_bounds[i].empty()) items.push_back({prim_bounds[i], prim_bounds[i].centroid(), i});
  if (items.empty()) return bvh;
  Builder builder(items, max_leaf_size);
  builder.nodes.reserve(2 * items.size());
  builder.build(0, uint32_t(items.size()));
  bvh.nodes_ = std::move(builder.nodes);
  bvh.prim_order_.reserve(items.size());
  for (const BuildItem& it : items) bvh.prim_order_.push_back(it.prim);
  return bvh;
}

}  // namespace prism
