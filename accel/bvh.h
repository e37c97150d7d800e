#pragma once
// Bounding volume hierarchy over any primitives given by their bounds: built by binned SAH
// (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"), stored as flat
// depth-first nodes (left child follows its parent), traversed front to back.

#include <cstdint>
#include <span>
#include <vector>

#include "base/bounds.h"
#include "base/ray.h"

namespace prism {

struct BvhNode {
  Bounds3f bounds;
  uint32_t index;  // leaf: first entry in prim_order(); interior: the second child's node
  uint16_t count;  // primitives in a leaf; 0 for interior nodes
  uint16_t axis;   // interior: split axis (children ordered by it)
};

class Bvh {
 public:
  Bvh() = default;
  static Bvh build(std::span<const Bounds3f> prim_bounds, int max_leaf_size = 4);

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  // Primitive indices in leaf order; leaf nodes point into this array.
  const std::vector<uint32_t>& prim_order() const { return prim_order_; }
  Bounds3f bounds() const { return nodes_.empty() ? Bounds3f{} : nodes_[0].bounds; }

  // Visits the leaves a ray may hit, nearest first. For each primitive slot i in a leaf,
  // calls hit(i, tmax), which returns true if it hit the primitive (and then lowers tmax).
  // With AnyHit, returns at the first hit. Returns whether anything was hit.
  template <bool AnyHit, typename Hit>
  bool traverse(const Ray& ray, float& tmax, Hit&& hit) const;

 private:
  std::vector<BvhNode> nodes_;
  std::vector<uint32_t> prim_order_;
};

// Slab test; the far distance is widened by 2γ₃ so rounding never loses a box the ray grazes
// (pbrt-v4 §6.8.2). NaNs from 0·∞ (ray in a slab plane) drop out of the min/max.
inline bool intersect_box(const Bounds3f& b, const Vec3f& o, const Vec3f& inv_d, float tmax) {
  float t0 = 0.f, t1 = tmax;
  for (int i = 0; i < 3; ++i) {
    float tn = (b.lo[i] - o[i]) * inv_d[i];
    float tf = (b.hi[i] - o[i]) * inv_d[i];
    if (tn > tf) std::swap(tn, tf);
    tf *= 1.f + 2.f * gamma(3);
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
    if (t0 > t1) return false;
  }
  return true;
}

template <bool AnyHit, typename Hit>
bool Bvh::traverse(const Ray& ray, float& tmax, Hit&& hit) const {
  if (nodes_.empty()) return false;
  const Vec3f inv_d(1.f / ray.d.x, 1.f / ray.d.y, 1.f / ray.d.z);
  const bool negative[3] = {inv_d.x < 0, inv_d.y < 0, inv_d.z < 0};
  uint32_t stack[64];
  int top = 0;
  uint32_t current = 0;
  bool found = false;
  while (true) {
    const BvhNode& node = nodes_[current];
    if (intersect_box(node.bounds, ray.o, inv_d, tmax)) {
      if (node.count > 0) {
        for (uint32_t i = node.index; i < node.index + node.count; ++i) {
          if (hit(i, tmax)) {
            found = true;
            if constexpr (AnyHit) return true;
          }
        }
      } else {
        // Visit the child on the ray's side of the split first.
        if (negative[node.axis]) {
          stack[top++] = current + 1;
          current = node.index;
        } else {
          stack[top++] = node.index;
          current = current + 1;
        }
        continue;
      }
    }
    if (top == 0) break;
    current = stack[--top];
  }
  return found;
}

}  // namespace prism
