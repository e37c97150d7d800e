// Building the 8-wide BVH: binned SAH (Wald 2007, "On fast Construction of SAH-based Bounding
// Volume Hierarchies") over primitive references, in parallel over subtrees (oneTBB), then laid
// out depth first, so that a node's first child follows it and the tree's memory order does not
// depend on which thread built what.

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <type_traits>

#include "accel/bvh.h"
#include "core/base/error.h"

namespace prism {

namespace {

using simd::f4;
using simd::i4;

constexpr int kBins = 32;
// Below this depth the SAH decides; deeper nodes split at the object median, which bounds the
// depth (and so the traversal stack) even for pathological inputs.
constexpr int kSahDepth = 40;
constexpr uint32_t kParallelPrims = 4096;  // a subtree this large is built as its own task
constexpr uint32_t kParallelBinning = 1 << 16;

// A box in SIMD form; lane 3 is unused.
struct Box {
  f4 lo = f4{} + kInfinity, hi = f4{} - kInfinity;
  void extend(const Box& b) { lo = b.lo < lo ? b.lo : lo, hi = b.hi > hi ? b.hi : hi; }
  void extend(f4 p) { lo = p < lo ? p : lo, hi = p > hi ? p : hi; }
  // Half the surface area, the SAH's measure (only ratios matter).
  float half_area() const {
    if (!(lo[0] <= hi[0])) return 0.f;
    const f4 d = hi - lo;
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
  }
};

struct PrimRef {
  f4 lo, hi;  // the primitive's box; lane 3 of lo holds its index
  uint32_t prim() const { return std::bit_cast<uint32_t>(lo[3]); }
  // Twice the centroid (binning only compares); lane 3 cleared of the index bits.
  f4 centroid2() const { return f4(i4(lo) & i4{-1, -1, -1, 0}) + hi; }
};

// Primitives [begin, end) of the reference array with their box and their centroids' box.
struct Range {
  uint32_t begin, end;
  Box bounds, centroids;
  uint32_t solos = 0;  // how many of them need a leaf of their own
  uint32_t size() const { return end - begin; }
  // Whether it must be split further: a solo primitive shares no leaf.
  bool must_split() const { return solos > 0 && size() > 1; }
};

// Maps a centroid to its bin on each axis.
struct BinMap {
  f4 offset, scale;
  explicit BinMap(const Box& centroids) : offset(centroids.lo) {
    const f4 extent = centroids.hi - centroids.lo;
    scale = extent > 0.f ? (kBins * 0.99999f) / extent : f4{};
  }
  i4 bins(f4 c2) const {
    const i4 b = __builtin_convertvector((c2 - offset) * scale, i4);
    return b < 0 ? i4{} : (b > kBins - 1 ? i4{} + (kBins - 1) : b);
  }
};

struct Bins {
  Box box[3][kBins];
  uint32_t count[3][kBins] = {};

  void add(const BinMap& map, const PrimRef& r) {
    const i4 b = map.bins(r.centroid2());
    const Box pb{r.lo, r.hi};
    for (int a = 0; a < 3; ++a) {
      box[a][b[a]].extend(pb);
      ++count[a][b[a]];
    }
  }
  void merge(const Bins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < kBins; ++b) box[a][b].extend(o.box[a][b]), count[a][b] += o.count[a][b];
  }
};

struct Split {
  int axis = -1;  // -1: no SAH split; split at the object median
  int bin = 0;    // bins [0, bin] go left
  float cost = kInfinity;
};

}  // namespace

class BvhBuilder {
 public:
  BvhBuilder(std::vector<PrimRef>& refs, const BvhBuildOptions& options)
      : refs_(refs), options_(options), nodes_(new TempNode[std::max<size_t>(refs.size(), 1)]) {}

  Bvh run(Range root, std::vector<uint32_t>& slots) {
    uint64_t root_ref = build(root, 0);
    // A tree that is one leaf (a small scene) still gets a node above it, whose box rays that
    // miss the whole scene fail first, instead of testing every triangle.
    if (root_ref & kTempLeaf && root.size() > 0) {
      const uint32_t index = node_count_.fetch_add(1);
      TempNode& node = nodes_[index];
      node.count = 1;
      node.lo[0] = root.bounds.lo, node.hi[0] = root.bounds.hi;
      node.child[0] = root_ref;
      root_ref = index;
    }
    Bvh bvh;
    bvh.bounds_ = to_bounds(root.bounds);
    bvh.nodes_.reserve(node_count_);
    slots.clear();
    slots.reserve(refs_.size() + refs_.size() / 2);
    bvh.root_ = emit(root_ref, bvh, slots);
    return bvh;
  }

 private:
  // A node as built: eight boxes and children, a leaf being a range of references. (Plain
  // vectors, without Box's initialisers, so that allocating room for the largest possible tree
  // touches no memory.)
  struct TempNode {
    f4 lo[8], hi[8];
    uint64_t child[8];
    int count;
  };
  static_assert(std::is_trivially_default_constructible_v<TempNode>);
  static constexpr uint64_t kTempLeaf = uint64_t(1) << 63;
  static uint64_t temp_leaf(const Range& r) { return kTempLeaf | uint64_t(r.begin) << 24 | r.size(); }

  uint32_t blocks(uint32_t n) const { return (n + options_.block_size - 1) / options_.block_size; }
  uint32_t max_leaf() const { return bvh_ref::kMaxLeafBlocks * options_.block_size; }
  static Bounds3f to_bounds(const Box& b) { return {{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}}; }

  Bins bin(const Range& r, const BinMap& map) const {
    if (r.size() < kParallelBinning) {
      Bins bins;
      for (uint32_t i = r.begin; i < r.end; ++i) bins.add(map, refs_[i]);
      return bins;
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(r.begin, r.end, kParallelBinning / 4), Bins{},
        [&](const tbb::blocked_range<uint32_t>& sub, Bins bins) {
          for (uint32_t i = sub.begin(); i < sub.end(); ++i) bins.add(map, refs_[i]);
          return bins;
        },
        [](Bins a, const Bins& b) {
          a.merge(b);
          return a;
        });
  }

  // The binned split of least SAH cost, Σ area(side) · blocks(side), over all three axes.
  Split find_split(const Range& r) const {
    const BinMap map(r.centroids);
    const Bins bins = bin(r, map);
    Split best;
    for (int a = 0; a < 3; ++a) {
      if (map.scale[a] == 0.f) continue;
      float right_area[kBins];
      uint32_t right_count[kBins];
      Box acc;
      uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bins.box[a][b]);
        n += bins.count[a][b];
        right_area[b] = acc.half_area();
        right_count[b] = n;
      }
      acc = Box{};
      n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.extend(bins.box[a][b]);
        n += bins.count[a][b];
        if (n == 0 || right_count[b + 1] == 0) continue;
        const float cost = acc.half_area() * float(blocks(n)) + right_area[b + 1] * float(blocks(right_count[b + 1]));
        if (cost < best.cost) best = {a, b, cost};
      }
    }
    return best;
  }

  // Splits r in two: by the SAH split if there is one, else at the median along the widest
  // centroid axis (coincident centroids: at the middle of the range).
  std::pair<Range, Range> partition(const Range& r, const Split& split) {
    PrimRef* first = refs_.data() + r.begin;
    PrimRef* last = refs_.data() + r.end;
    PrimRef* mid;
    if (split.axis >= 0) {
      const BinMap map(r.centroids);
      mid = std::partition(first, last,
                           [&](const PrimRef& p) { return map.bins(p.centroid2())[split.axis] <= split.bin; });
    } else {
      mid = first + r.size() / 2;
      const f4 extent = r.centroids.hi - r.centroids.lo;
      const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0 : (extent[1] >= extent[2] ? 1 : 2);
      std::nth_element(first, mid, last,
                       [&](const PrimRef& p, const PrimRef& q) { return p.centroid2()[axis] < q.centroid2()[axis]; });
    }
    const auto measure = [&](PrimRef* b, PrimRef* e) {
      Range side{uint32_t(b - refs_.data()), uint32_t(e - refs_.data()), {}, {}};
      for (PrimRef* p = b; p != e; ++p) {
        side.bounds.extend(Box{p->lo, p->hi});
        side.centroids.extend(p->centroid2());
        side.solos += p->prim() >= options_.first_solo;
      }
      return side;
    };
    return {measure(first, mid), measure(mid, last)};
  }

  // Builds the subtree over r; returns its reference (a leaf or a TempNode index).
  uint64_t build(const Range& r, int depth) {
    const uint32_t n = r.size();
    if (n <= uint32_t(options_.block_size) && !r.must_split()) return temp_leaf(r);
    Split split = depth < kSahDepth ? find_split(r) : Split{};
    // SAH, per unit of this box's area: a leaf tests every block; a node costs a visit plus the
    // children's blocks, weighted by the chance that a ray through this box enters each child.
    const float leaf_cost = float(blocks(n));
    const float split_cost = options_.traversal_cost + split.cost / std::max(r.bounds.half_area(), 1e-30f);
    if (n <= max_leaf() && leaf_cost <= split_cost && !r.must_split()) return temp_leaf(r);

    // Open the node's largest child until it has eight, or none has more than a block (or solos).
    Range child[8] = {r};
    int count = 1;
    while (count < 8) {
      int best = -1;
      float best_key = -1.f;
      for (int c = 0; c < count; ++c) {
        if (child[c].size() <= uint32_t(options_.block_size) && !child[c].must_split()) continue;
        // Deep nodes open the child with the most primitives, so the depth stays logarithmic.
        const float key = depth < kSahDepth ? child[c].bounds.half_area() : float(child[c].size());
        if (key > best_key) best = c, best_key = key;
      }
      if (best < 0) break;
      if (count > 1) split = depth < kSahDepth ? find_split(child[best]) : Split{};
      std::tie(child[best], child[count]) = partition(child[best], split);
      ++count;
    }

    const uint32_t index = node_count_.fetch_add(1);
    TempNode& node = nodes_[index];
    node.count = count;
    for (int c = 0; c < count; ++c) node.lo[c] = child[c].bounds.lo, node.hi[c] = child[c].bounds.hi;
    const auto build_child = [&](int c) { node.child[c] = build(child[c], depth + 1); };
    if (n >= kParallelPrims) {
      tbb::parallel_for(0, count, build_child);
    } else {
      for (int c = 0; c < count; ++c) build_child(c);
    }
    return index;
  }

  // Writes the subtree depth first into bvh; returns its final reference.
  uint32_t emit(uint64_t ref, Bvh& bvh, std::vector<uint32_t>& slots) {
    if (ref & kTempLeaf) {
      const uint32_t begin = uint32_t(ref >> 24), n = uint32_t(ref & 0xFFFFFF);
      const uint32_t prim = refs_[begin].prim();
      if (prim >= options_.first_solo) return bvh_ref::solo(prim - options_.first_solo);
      const uint32_t first_block = uint32_t(slots.size()) / options_.block_size;
      if (first_block + blocks(n) > bvh_ref::kMaxIndex) fail("BVH: more than {} leaf blocks", bvh_ref::kMaxIndex);
      for (uint32_t i = 0; i < n; ++i) slots.push_back(refs_[begin + i].prim());
      slots.resize(size_t(first_block + blocks(n)) * options_.block_size, Bvh::kEmptySlot);
      return bvh_ref::leaf(first_block, blocks(n));
    }
    const TempNode& temp = nodes_[ref];
    const uint32_t index = uint32_t(bvh.nodes_.size());
    bvh.nodes_.emplace_back();
    for (int c = 0; c < 8; ++c) {
      const Box box = c < temp.count ? Box{temp.lo[c], temp.hi[c]} : Box{};
      for (int a = 0; a < 3; ++a) {
        bvh.nodes_[index].planes[a][c] = box.lo[a];
        bvh.nodes_[index].planes[a + 3][c] = box.hi[a];
      }
      bvh.nodes_[index].child[c] = 0;
    }
    for (int c = 0; c < temp.count; ++c) {
      const uint32_t child = emit(temp.child[c], bvh, slots);
      bvh.nodes_[index].child[c] = child;  // by index: the children's emplace_back may reallocate
    }
    return index;
  }

  std::vector<PrimRef>& refs_;
  BvhBuildOptions options_;
  std::unique_ptr<TempNode[]> nodes_;  // uninitialised: only the nodes built are touched
  std::atomic<uint32_t> node_count_{0};
};

Bvh Bvh::build(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options, std::vector<uint32_t>& slots) {
  std::vector<PrimRef> refs;
  refs.reserve(prim_bounds.size());
  Range root{0, 0, {}, {}};
  for (uint32_t i = 0; i < prim_bounds.size(); ++i) {
    const Bounds3f& b = prim_bounds[i];
    if (b.empty()) continue;
    PrimRef r{{b.lo.x, b.lo.y, b.lo.z, std::bit_cast<float>(i)}, {b.hi.x, b.hi.y, b.hi.z, 0.f}};
    refs.push_back(r);
    root.bounds.extend(Box{r.lo, r.hi});
    root.centroids.extend(r.centroid2());
    root.solos += i >= options.first_solo;
  }
  root.end = uint32_t(refs.size());
  slots.clear();
  if (refs.empty()) return Bvh{};
  return BvhBuilder(refs, options).run(root, slots);
}

}  // namespace prism
