#pragma once
// Watertight ray-triangle intersection (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)): vertices are moved into a ray-aligned frame (translate to the
// origin, permute so the ray's largest axis is z, shear so the ray is +z), where the 2D edge
// functions of a shared edge are computed identically for both triangles. Rays through an edge
// or vertex therefore hit at least one of the triangles sharing it; none slip through.
// One implementation, eight triangles at a time: the BVH's leaves store triangles in blocks.

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "accel/simd.h"
#include "base/ray.h"

namespace prism {

// Per-ray constants of the watertight test, computed once per traversal.
struct WatertightRay {
  int kx, ky, kz;
  float ox, oy, oz;  // the origin in the permuted axes
  float sx, sy, sz;

  explicit WatertightRay(const Ray& ray) {
    kz = max_dimension(abs(ray.d));
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    if (ray.d[kz] < 0) std::swap(kx, ky);  // keep the winding of the sheared triangle
    sx = ray.d[kx] / ray.d[kz];
    sy = ray.d[ky] / ray.d[kz];
    sz = 1.f / ray.d[kz];
    ox = ray.o[kx], oy = ray.o[ky], oz = ray.o[kz];
  }
};

struct TriangleHit {
  float t;
  float b0, b1, b2;  // barycentric weights of v0, v1, v2
};

// Eight triangles, stored lane by lane. Unused lanes hold NaN vertices, which never hit.
struct alignas(32) TriangleBlock {
  static constexpr int kLanes = 8;
  simd::f8 v[3][3];     // v[vertex][axis]
  uint32_t id[kLanes];  // the owner's number for each triangle

  TriangleBlock() {
    for (auto& vertex : v)
      for (auto& axis : vertex) axis = simd::broadcast(std::numeric_limits<float>::quiet_NaN());
    for (uint32_t& i : id) i = 0;
  }
  void set(int lane, const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, uint32_t triangle_id) {
    const Vec3f* vs[3] = {&v0, &v1, &v2};
    for (int k = 0; k < 3; ++k)
      for (int axis = 0; axis < 3; ++axis) v[k][axis][lane] = (*vs[k])[axis];
    id[lane] = triangle_id;
  }
};

// The lanes of a block that a ray hits with 0 < t <= tmax (either face), and how. (t = tmax is
// let through: the caller breaks ties with the closest hit so far by triangle number.)
struct BlockHits {
  uint32_t mask = 0;  // bit i: lane i hits
  simd::f8 t, u, v, w, inv_det;

  TriangleHit lane(int i) const { return {t[i], u[i] * inv_det[i], v[i] * inv_det[i], w[i] * inv_det[i]}; }
};

// The edge functions of the lanes in `lanes` recomputed in double, where the products are exact:
// for rays exactly on an edge in float (rare). Out of line, so that the common path stays small.
[[gnu::cold, gnu::noinline]] inline void exact_edge_functions(uint32_t lanes, const simd::f8& ax, const simd::f8& ay,
                                                              const simd::f8& bx, const simd::f8& by,
                                                              const simd::f8& cx, const simd::f8& cy, simd::f8& u,
                                                              simd::f8& v, simd::f8& w) {
  const auto edge_function = [](double px, double py, double qx, double qy) { return float(px * qy - py * qx); };
  for (; lanes; lanes &= lanes - 1) {
    const int i = std::countr_zero(lanes);
    u[i] = edge_function(cx[i], cy[i], bx[i], by[i]);
    v[i] = edge_function(ax[i], ay[i], cx[i], cy[i]);
    w[i] = edge_function(bx[i], by[i], ax[i], ay[i]);
  }
}

inline BlockHits intersect_triangles(const WatertightRay& r, const TriangleBlock& tri, float tmax) {
  using simd::f8, simd::i8;
  // Vertices relative to the origin, in the permuted axes.
  const f8 ox = simd::broadcast(r.ox), oy = simd::broadcast(r.oy), oz = simd::broadcast(r.oz);
  const f8 a_x = tri.v[0][r.kx] - ox, a_y = tri.v[0][r.ky] - oy, a_z = tri.v[0][r.kz] - oz;
  const f8 b_x = tri.v[1][r.kx] - ox, b_y = tri.v[1][r.ky] - oy, b_z = tri.v[1][r.kz] - oz;
  const f8 c_x = tri.v[2][r.kx] - ox, c_y = tri.v[2][r.ky] - oy, c_z = tri.v[2][r.kz] - oz;
  // Sheared into the ray's frame.
  const f8 ax = a_x - r.sx * a_z, ay = a_y - r.sy * a_z;
  const f8 bx = b_x - r.sx * b_z, by = b_y - r.sy * b_z;
  const f8 cx = c_x - r.sx * c_z, cy = c_y - r.sy * c_z;

  // Scaled barycentrics: 2D edge functions of the edges opposite v0, v1, v2.
  f8 u = cx * by - cy * bx;
  f8 v = ax * cy - ay * cx;
  f8 w = bx * ay - by * ax;
  const i8 on_edge = (u == 0.f) | (v == 0.f) | (w == 0.f);
  if (const uint32_t edge = simd::bits(on_edge)) exact_edge_functions(edge, ax, ay, bx, by, cx, cy, u, v, w);
  const i8 outside = ((u < 0.f) | (v < 0.f) | (w < 0.f)) & ((u > 0.f) | (v > 0.f) | (w > 0.f));
  const f8 det = u + v + w;

  // Scaled distance T = det · t.
  const f8 az = r.sz * a_z, bz = r.sz * b_z, cz = r.sz * c_z;
  const f8 t_scaled = u * az + v * bz + w * cz;
  BlockHits hits;
  hits.inv_det = 1.f / det;
  hits.t = t_scaled * hits.inv_det;
  hits.u = u, hits.v = v, hits.w = w;
  const i8 candidates = ~outside & (det != 0.f) & (hits.t > 0.f) & (hits.t <= tmax);
  if (!simd::bits(candidates)) return hits;  // most blocks a ray reaches: no need for the bound

  // t must exceed its own rounding-error bound δt, or a ray leaving a surface point could hit
  // that surface again at a tiny t: a point exactly on an axis-aligned plane has no error to be
  // offset by (pbrt-v4 §6.8.4, from the error of each step above). The shear's share of the
  // error is |s|·|z| rather than pbrt's |z| (which takes |s| ≤ 1): otherwise the bound of a ray
  // grazing a small triangle exceeds t itself, and true hits are lost.
  const auto magnitude = [](f8 x) { return x < 0.f ? -x : x; };
  const auto largest = [&](f8 p, f8 q, f8 s) {
    const f8 m = magnitude(p) > magnitude(q) ? magnitude(p) : magnitude(q);
    return m > magnitude(s) ? m : magnitude(s);
  };
  const f8 max_x = largest(ax, bx, cx), max_y = largest(ay, by, cy), max_z = largest(az, bz, cz);
  const f8 delta_x = gamma(5) * (max_x + 2 * std::abs(r.sx) * max_z);
  const f8 delta_y = gamma(5) * (max_y + 2 * std::abs(r.sy) * max_z);
  const f8 delta_z = gamma(3) * max_z;
  const f8 delta_e = 2 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const f8 max_e = largest(u, v, w);
  const f8 delta_t = 3 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * magnitude(hits.inv_det);
  hits.mask = simd::bits(candidates & (hits.t > delta_t));
  return hits;
}

// Unit normal of triangle (v0, v1, v2) by the right-hand rule (counter-clockwise = front),
// computed in double so that tiny or sliver triangles still get one; (0, 0, 0) if degenerate.
inline Vec3f triangle_normal(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2) {
  const Vec3d n = cross(Vec3d(v1 - v0), Vec3d(v2 - v0));
  const double len = length(n);
  return len > 0 ? Vec3f(n / len) : Vec3f(0, 0, 0);
}

// Area of the triangle, in double for the same reason.
inline float triangle_area(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2) {
  return float(0.5 * length(cross(Vec3d(v1 - v0), Vec3d(v2 - v0))));
}

}  // namespace prism
