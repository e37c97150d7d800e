#pragma once
// Bounding volume hierarchy over primitives given by their bounds, with 8-wide nodes whose eight
// child boxes one SIMD slab test checks at once (Wald, Benthin & Boulos 2008, "Getting rid of
// packets"; Dammertz et al. 2008, "Shallow bounding volume hierarchies"). Built by binned SAH
// (Wald 2007), each node's children by splitting its largest child until there are eight, as
// Embree does (Wald et al. 2014). Leaves are runs of blocks of a fixed number of primitive slots,
// so that a leaf's primitives can be tested together too. Traversal visits children nearest first.

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "accel/simd.h"
#include "core/base/bounds.h"
#include "core/base/frustum.h"
#include "core/base/huge_page_allocator.h"
#include "core/base/ray.h"

namespace prism {

struct alignas(64) BvhNode {
  static constexpr int kWidth = 8;
  // The children's boxes, lane by lane: lo x, y, z, then hi x, y, z. Unused lanes hold an empty
  // box (lo = +∞, hi = −∞), which no ray enters.
  float planes[6][kWidth];
  uint32_t child[kWidth];
};

// A child reference: an inner node's index, or a leaf: a run of blocks, or one primitive that the
// BVH's owner handles itself ("solo", such as an instance in Accel's world tree).
namespace bvh_ref {
inline constexpr uint32_t kLeaf = 1u << 31;
inline constexpr int kCountShift = 27;
inline constexpr uint32_t kSolo = 15;  // this block count marks a solo leaf
inline constexpr uint32_t kMaxLeafBlocks = kSolo - 1;
inline constexpr uint32_t kMaxIndex = (1u << kCountShift) - 1;
constexpr uint32_t leaf(uint32_t first_block, uint32_t blocks) {
  return kLeaf | (blocks - 1) << kCountShift | first_block;
}
constexpr uint32_t solo(uint32_t index) { return kLeaf | (kSolo - 1) << kCountShift | index; }
constexpr bool is_leaf(uint32_t ref) { return ref & kLeaf; }
constexpr uint32_t block_count(uint32_t ref) { return ((ref & ~kLeaf) >> kCountShift) + 1; }
constexpr bool is_solo(uint32_t ref) { return block_count(ref) == kSolo; }
constexpr uint32_t index(uint32_t ref) { return ref & kMaxIndex; }  // first block, or the solo primitive
}  // namespace bvh_ref

struct BvhBuildOptions {
  int block_size = 1;                // primitive slots per leaf block (the SIMD width of the leaf test)
  float traversal_cost = 1.f;        // SAH: cost of visiting a node, relative to testing one block
  uint32_t first_solo = 0xFFFFFFFF;  // primitives numbered from here on get a solo leaf each
};

// Per-ray constants of the slab test.
struct BvhRay {
  simd::f8 o[3], inv_near[3], inv_far[3];
  // Per axis, the byte offsets in BvhNode::planes of the rows the ray enters by (rows[0..2]) and
  // leaves by (rows[3..5]): kRows' entry for the signs of the direction.
  const size_t* rows;

  explicit BvhRay(const Ray& ray) {
    // The near distance is rounded down and the far one up, by more than the four roundings of
    // (p − o)·(1/d)·c, so that no box the ray touches is ever missed (pbrt-v4 §6.8.2).
    constexpr float kDown = 1.f - 2.f * gamma(5), kUp = 1.f + 2.f * gamma(5);
    // The three axes at once (one division; the per-ray set-up is a good part of a short ray's cost).
    const simd::f4 inv = 1.f / simd::f4{ray.d.x, ray.d.y, ray.d.z, 1.f}, down = inv * kDown, up = inv * kUp;
    for (int a = 0; a < 3; ++a) {
      o[a] = simd::broadcast(ray.o[a]);
      inv_near[a] = simd::broadcast(down[a]);
      inv_far[a] = simd::broadcast(up[a]);
    }
    rows = kRows[simd::bits(inv < 0.f)].data();
  }

 private:
  static constexpr size_t kRow = sizeof(BvhNode::planes[0]);
  // kRows[s]: entry and exit rows for direction signs s (bit a set: d[a] < 0, entering by hi).
  static constexpr auto kRows = [] {
    std::array<std::array<size_t, 6>, 8> rows{};
    for (int s = 0; s < 8; ++s)
      for (int a = 0; a < 3; ++a) {
        const bool negative = s >> a & 1;
        rows[s][a] = (negative ? a + 3 : a) * kRow;
        rows[s][a + 3] = (negative ? a : a + 3) * kRow;
      }
    return rows;
  }();
};

// Per-region constants of the box test (Bvh::any_leaf_meets), in float: each plane's normal in
// every lane, the rows of a box's corner furthest inside it, and the bound on n·x beyond which a
// point is outside, the region's margin for `extent` (everything tested) included.
struct BvhFrustum {
  int count;
  simd::f8 n[5][3], limit[5];
  size_t rows[5][3];

  BvhFrustum(const Frustum& f, const Bounds3f& extent) : count(f.count) {
    const double margin = f.margin(extent);
    for (int i = 0; i < count; ++i) {
      const Vec3d& normal = f.planes[i].n;
      for (int a = 0; a < 3; ++a) {
        n[i][a] = simd::broadcast(float(normal[a]));
        rows[i][a] = size_t(normal[a] > 0 ? a : a + 3) * sizeof(BvhNode::planes[0]);
      }
      limit[i] = simd::broadcast(float(dot(normal, f.origin) + f.planes[i].d + margin));
    }
  }
  // Bit c: child c's box is not wholly outside a plane. (Unused children's empty boxes give +∞ or NaN.)
  uint32_t boxes(const BvhNode& node) const {
    const char* planes = reinterpret_cast<const char*>(node.planes);
    uint32_t mask = 0xFF;
    for (int i = 0; i < count; ++i) {
      const auto row = [&](int a) { return simd::load(reinterpret_cast<const float*>(planes + rows[i][a])); };
      mask &= simd::bits(n[i][0] * row(0) + n[i][1] * row(1) + n[i][2] * row(2) <= limit[i]);
    }
    return mask;
  }
};

class Bvh {
 public:
  static constexpr uint32_t kEmptySlot = 0xFFFFFFFF;

  Bvh() = default;
  // Builds over the primitives whose bounds are not empty. `slots` receives them in the order
  // the leaves list them: block after block of options.block_size slots, unused ones kEmptySlot.
  // Solo primitives are not in `slots`: their leaves name them (minus options.first_solo).
  static Bvh build(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options, std::vector<uint32_t>& slots);

  bool empty() const { return root_ == kNoRoot; }
  Bounds3f bounds() const { return bounds_; }
  size_t memory_bytes() const { return nodes_.size() * sizeof(BvhNode); }

  // Visits the leaves a ray may hit, nearest first: calls leaf(first_block, block_count), or
  // solo(index) for a solo leaf, which tests the leaf's primitives, lowers tmax to any closer hit
  // and returns whether it hit. Boxes entered beyond tmax + slack are skipped, `slack` being what
  // a primitive test may round its t below the exact one's (so that a primitive whose rounded t is
  // the least is found even when its box starts beyond the first hit: faces that coincide). With
  // AnyHit, returns at the first hit. `blocks` (the leaves' blocks) is only prefetched. Defined in
  // bvh_traverse.h, which only the tracing code includes (so that changing it recompiles one file).
  template <bool AnyHit, typename Block, typename Leaf, typename Solo>
  bool traverse(const Ray& ray, float& tmax, float slack, const Block* blocks, Leaf&& leaf, Solo&& solo) const;
  // Whether any leaf whose box may meet the region says its primitives may: leaf(first_block,
  // block_count) or solo(index). Also in bvh_traverse.h.
  template <typename Leaf, typename Solo>
  bool any_leaf_meets(const BvhFrustum& region, Leaf&& leaf, Solo&& solo) const;

 private:
  friend class BvhBuilder;
  static constexpr uint32_t kNoRoot = 0xFFFFFFFF;
  // Deep enough for the builder's depth limit (it switches to median splits), 7 entries a level.
  static constexpr int kStackSize = 7 * 64;

  std::vector<BvhNode, HugePageAllocator<BvhNode>> nodes_;
  uint32_t root_ = kNoRoot;
  Bounds3f bounds_;
};

}  // namespace prism
