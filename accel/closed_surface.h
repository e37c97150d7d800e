#pragma once
// Whether a triangle mesh is closed, the boundary of a volume: then a ray that leaves one of its
// triangles into that volume meets the mesh again before it leaves the volume, and so before it
// leaves the mesh's bounds (a shadow ray from inside a closed object to a light outside it is
// blocked without being traced; World::meets_own_surface).

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/base/vec.h"

namespace prism {

// The side of the triangles' front normals, n = (v1 − v0) × (v2 − v0) (counter-clockwise winding),
// on which the enclosed volume lies: −1 if the normals point out of it, +1 if they point in, and 0
// if the mesh is not closed. Closed means:
// - every edge is shared by exactly two triangles that cross it in opposite directions, vertices
//   being compared by position (the split vertices of a texture seam join; a T-junction does not);
// - every connected part encloses a volume (a sheet's two faces back to back enclose none), and
//   all parts have their normals on the same side of it.
// Triangles with two vertices at one position are left out: their edges cancel each other.
// Meshes of more than kClosedCheckTriangles triangles are not checked (0): the check sorts their
// edges, about 75 bytes of memory a triangle while it runs.
inline constexpr size_t kClosedCheckTriangles = size_t(1) << 20;
int enclosed_side(std::span<const Vec3f> positions, std::span<const uint32_t> indices);

}  // namespace prism
