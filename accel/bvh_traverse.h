#pragma once
// The BVH's traversals (declared in bvh.h). A ray's: a stack of entered boxes, children visited
// nearest first, boxes beyond the closest hit so far skipped. A region's: every box it may meet,
// until a leaf whose primitives it may meet.

#include "accel/bvh.h"

namespace prism {

template <bool AnyHit, typename Block, typename Leaf, typename Solo>
bool Bvh::traverse(const Ray& r, float& tmax, float slack, const Block* blocks, Leaf&& leaf, Solo&& solo) const {
  using simd::f8;
  if (root_ == kNoRoot) return false;
  const BvhRay ray(r);  // built here, so the compiler keeps it in registers
  const auto prefetch = [](const void* p, size_t bytes) {
    for (size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(static_cast<const char*>(p) + offset);
    __builtin_prefetch(static_cast<const char*>(p) + bytes - 1);
  };
  struct Entry {
    uint32_t ref;
    float t;  // where the ray enters the box
  };
  Entry stack[kStackSize];
  int top = 0;
  uint32_t ref = root_;
  bool found = false;
  while (true) {
    if (bvh_ref::is_leaf(ref)) {
      const uint32_t i = bvh_ref::index(ref);
      if (bvh_ref::is_solo(ref) ? solo(i) : leaf(i, bvh_ref::block_count(ref))) {
        found = true;
        if constexpr (AnyHit) return true;
      }
    } else {
      const BvhNode& node = nodes_[ref];
      const char* planes = reinterpret_cast<const char*>(node.planes);
      const auto slab = [&](size_t offset, int a, const f8& inv) {
        return (simd::load(reinterpret_cast<const float*>(planes + offset)) - ray.o[a]) * inv;
      };
      const f8 t_enter =
          simd::max_ignore_nan(slab(ray.rows[0], 0, ray.inv_near[0]),
                               simd::max_ignore_nan(slab(ray.rows[1], 1, ray.inv_near[1]),
                                                    simd::max_ignore_nan(slab(ray.rows[2], 2, ray.inv_near[2]), f8{})));
      const f8 t_leave = simd::min_ignore_nan(
          slab(ray.rows[3], 0, ray.inv_far[0]),
          simd::min_ignore_nan(
              slab(ray.rows[4], 1, ray.inv_far[1]),
              simd::min_ignore_nan(slab(ray.rows[5], 2, ray.inv_far[2]), simd::broadcast(tmax + slack))));
      uint32_t mask = simd::bits(t_enter <= t_leave);
      if (mask) {
        int i = std::countr_zero(mask);
        if (!(mask & (mask - 1))) {  // one child: straight down
          ref = node.child[i];
          continue;
        }
        // Several: fetch them all now, so that memory works while the nearest is traversed.
        for (uint32_t m = mask; m; m &= m - 1) {
          const uint32_t c = node.child[std::countr_zero(m)];
          if (!bvh_ref::is_leaf(c))
            prefetch(&nodes_[c], sizeof(BvhNode));
          else if (!bvh_ref::is_solo(c))
            prefetch(&blocks[bvh_ref::index(c)], sizeof(Block));
        }
        if constexpr (AnyHit) {  // any hit will do: no order, no distances to keep
          ref = node.child[i];
          for (mask &= mask - 1; mask; mask &= mask - 1) stack[top++].ref = node.child[std::countr_zero(mask)];
          continue;
        }
        alignas(32) float t[8];
        simd::store(t, t_enter);
        mask &= mask - 1;
        int j = std::countr_zero(mask);
        mask &= mask - 1;
        if (!mask) {  // two children: the nearer now, the other later
          if (t[j] < t[i]) std::swap(i, j);
          stack[top++] = {node.child[j], t[j]};
          ref = node.child[i];
          continue;
        }
        // More: push all, sort them far to near (insertion sort: at most eight), take the nearest.
        Entry* pushed = stack + top;
        int n = 0;
        for (uint32_t m = mask | 1u << i | 1u << j; m; m &= m - 1) {
          const int c = std::countr_zero(m);
          const Entry e{node.child[c], t[c]};
          int k = n++;
          for (; k > 0 && pushed[k - 1].t < e.t; --k) pushed[k] = pushed[k - 1];
          pushed[k] = e;
        }
        top += n - 1;
        ref = pushed[n - 1].ref;
        continue;
      }
    }
    // Next: the nearest box still pending that starts before tmax (+ slack).
    if constexpr (AnyHit) {
      if (top == 0) return false;
      ref = stack[--top].ref;
      continue;
    }
    do {
      if (top == 0) return found;
      --top;
    } while (stack[top].t > tmax + slack);
    ref = stack[top].ref;
  }
}

template <typename Leaf, typename Solo>
bool Bvh::any_leaf_meets(const BvhFrustum& region, Leaf&& leaf, Solo&& solo) const {
  if (root_ == kNoRoot) return false;
  uint32_t stack[kStackSize + BvhNode::kWidth];
  int top = 0;
  stack[top++] = root_;
  while (top > 0) {
    const uint32_t ref = stack[--top];
    if (bvh_ref::is_leaf(ref)) {
      const uint32_t i = bvh_ref::index(ref);
      if (bvh_ref::is_solo(ref) ? solo(i) : leaf(i, bvh_ref::block_count(ref))) return true;
      continue;
    }
    const BvhNode& node = nodes_[ref];
    for (uint32_t mask = region.boxes(node); mask; mask &= mask - 1) stack[top++] = node.child[std::countr_zero(mask)];
  }
  return false;
}

}  // namespace prism
