#pragma once
// Splitting triangles whose box fits them badly into several boxes before the BVH is built
// (Karras & Aila 2013, "Fast Parallel Construction of High-Quality Bounding Volume Hierarchies",
// §4.3): a long diagonal triangle's one box overlaps much empty space and many neighbours; its
// pieces' boxes, each the exact bounds of the triangle clipped to a slab, do not. The leaves then
// reference the whole triangle from each piece that reaches them, so a triangle may sit in
// several leaves (the closest hit is still decided by (t, id)).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "base/bounds.h"

namespace prism {

// The BVH's input: boxes, and the primitive each box belongs to.
struct PrimitiveBoxes {
  std::vector<Bounds3f> bounds;
  std::vector<uint32_t> prims;
};

// One box per hittable triangle, plus up to `budget` × their count further boxes, given to the
// triangles by how much box area splitting would save. Unhittable triangles get none.
PrimitiveBoxes split_triangles(std::span<const std::array<Vec3f, 3>> triangles, float budget);

}  // namespace prism
