#include "accel/closed_surface.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/base/bounds.h"

namespace prism {

namespace {

// One id per distinct position (−0 and +0 alike): the vertices sorted by their coordinates' bits.
std::vector<uint32_t> position_ids(std::span<const Vec3f> positions) {
  const auto key = [&](uint32_t v) {
    const Vec3f p = positions[v];
    return std::array<uint32_t, 3>{std::bit_cast<uint32_t>(p.x + 0.f), std::bit_cast<uint32_t>(p.y + 0.f),
                                   std::bit_cast<uint32_t>(p.z + 0.f)};
  };
  std::vector<uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::ranges::sort(order, [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<uint32_t> id(positions.size());
  uint32_t next = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && key(order[i]) != key(order[i - 1])) ++next;
    id[order[i]] = next;
  }
  return id;
}

// The connected parts of the triangles, as a forest with path halving (Tarjan 1975).
struct Parts {
  std::vector<uint32_t> parent;
  explicit Parts(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t root(uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  }
  void join(uint32_t a, uint32_t b) { parent[root(a)] = root(b); }
};

}  // namespace

int enclosed_side(std::span<const Vec3f> positions, std::span<const uint32_t> indices) {
  const size_t triangles = indices.size() / 3;
  if (triangles > kClosedCheckTriangles) return 0;
  const std::vector<uint32_t> id = position_ids(positions);
  // Each edge of each triangle, its ends in increasing order and whether the triangle crosses it
  // that way.
  struct Edge {
    uint32_t lo, hi, triangle;
    bool forward;
  };
  std::vector<Edge> edges;
  edges.reserve(3 * triangles);
  std::vector<uint8_t> counted(triangles, 0);
  for (uint32_t t = 0; t < triangles; ++t) {
    const uint32_t v[3] = {id[indices[3 * t]], id[indices[3 * t + 1]], id[indices[3 * t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    counted[t] = 1;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  }
  if (edges.empty()) return 0;
  std::ranges::sort(edges, [](const Edge& a, const Edge& b) { return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi; });
  const auto same = [&](size_t i, size_t j) { return edges[i].lo == edges[j].lo && edges[i].hi == edges[j].hi; };
  Parts parts(triangles);
  for (size_t i = 0; i < edges.size(); i += 2) {
    if (i + 1 == edges.size() || !same(i, i + 1) || (i + 2 < edges.size() && same(i, i + 2))) return 0;
    if (edges[i].forward == edges[i + 1].forward) return 0;  // both cross it the same way: wound inconsistently
    parts.join(edges[i].triangle, edges[i + 1].triangle);
  }
  // Each part's signed volume, Σ a · (b × c) / 6 from a point near the mesh (divergence theorem), in
  // double; and Σ |a · (b × c)| / 6, the scale its rounding and a flat part's cancellation are judged by.
  Bounds3f box;
  for (const Vec3f& p : positions) box.extend(p);
  const Vec3d origin(box.centroid());
  std::vector<double> volume(triangles, 0.0), scale(triangles, 0.0);
  for (uint32_t t = 0; t < triangles; ++t) {
    if (!counted[t]) continue;
    const Vec3d a = Vec3d(positions[indices[3 * t]]) - origin, b = Vec3d(positions[indices[3 * t + 1]]) - origin,
                c = Vec3d(positions[indices[3 * t + 2]]) - origin;
    const double v = dot(a, cross(b, c)) / 6;
    if (!std::isfinite(v)) return 0;
    const uint32_t r = parts.root(t);
    volume[r] += v, scale[r] += std::abs(v);
  }
  int side = 0;
  for (uint32_t t = 0; t < triangles; ++t) {
    if (!counted[t] || parts.root(t) != t) continue;
    if (!(std::abs(volume[t]) > 1e-6 * scale[t])) return 0;  // encloses no volume (two faces back to back)
    const int part_side = volume[t] > 0 ? -1 : 1;
    if (side != 0 && part_side != side) return 0;
    side = part_side;
  }
  return side;
}

}  // namespace prism
