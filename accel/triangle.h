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
#include "core/base/ray.h"

namespace prism {

// Per-ray constants of the watertight test, computed once per traversal.
struct WatertightRay {
  int kx, ky, kz;
  float ox, oy, oz;  // the origin in the permuted axes
  float sx, sy, sz;

  // Without a branch on the direction (a choice of the largest axis and Vec3::operator[], mispredicted
  // about every other time for random directions): the axes are picked by arithmetic on the
  // comparisons, the coordinates read from arrays.
  explicit WatertightRay(const Ray& ray) {
    const float d[3] = {ray.d.x, ray.d.y, ray.d.z}, o[3] = {ray.o.x, ray.o.y, ray.o.z};
    const float ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    // The largest axis of |d|: x if ax > ay and ax > az, else y if ay > az (and ax <= ay), else z.
    const int x_largest = (ax > ay) & (ax > az), y_largest = !(ax > ay) & (ay > az);
    kz = 2 - 2 * x_largest - y_largest;
    // The other two axes in cyclic order, swapped when d[kz] < 0 to keep the sheared triangle's winding.
    constexpr int kAxes[3][2][2] = {{{1, 2}, {2, 1}}, {{2, 0}, {0, 2}}, {{0, 1}, {1, 0}}};
    const int negative = d[kz] < 0;
    kx = kAxes[kz][negative][0];
    ky = kAxes[kz][negative][1];
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1.f / d[kz];
    ox = o[kx], oy = o[ky], oz = o[kz];
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

// A block's vertices relative to the ray's origin, in its permuted axes, and sheared so that the
// ray runs along +z (the z coordinates are not yet scaled by sz).
struct ShearedBlock {
  simd::f8 ax, ay, a_z, bx, by, b_z, cx, cy, c_z;

  ShearedBlock(const WatertightRay& r, const TriangleBlock& tri) {
    const simd::f8 ox = simd::broadcast(r.ox), oy = simd::broadcast(r.oy), oz = simd::broadcast(r.oz);
    a_z = tri.v[0][r.kz] - oz, b_z = tri.v[1][r.kz] - oz, c_z = tri.v[2][r.kz] - oz;
    ax = (tri.v[0][r.kx] - ox) - r.sx * a_z, ay = (tri.v[0][r.ky] - oy) - r.sy * a_z;
    bx = (tri.v[1][r.kx] - ox) - r.sx * b_z, by = (tri.v[1][r.ky] - oy) - r.sy * b_z;
    cx = (tri.v[2][r.kx] - ox) - r.sx * c_z, cy = (tri.v[2][r.ky] - oy) - r.sy * c_z;
  }
};

// Scaled barycentrics: the 2D edge functions of the edges opposite v0, v1, v2.
struct EdgeFunctions {
  simd::f8 u, v, w;
};

// The edge functions of the lanes in `lanes` recomputed in double, where the products are exact:
// for rays exactly on an edge in float (rare). Out of line, and given the block rather than its
// sheared vertices (it shears them again, identically), so that the common path keeps those in
// registers.
[[gnu::cold, gnu::noinline]] inline EdgeFunctions exact_edge_functions(uint32_t lanes, const WatertightRay& r,
                                                                       const TriangleBlock& tri, EdgeFunctions e) {
  const ShearedBlock s(r, tri);
  const auto edge_function = [](double px, double py, double qx, double qy) { return float(px * qy - py * qx); };
  for (; lanes; lanes &= lanes - 1) {
    const int i = std::countr_zero(lanes);
    e.u[i] = edge_function(s.cx[i], s.cy[i], s.bx[i], s.by[i]);
    e.v[i] = edge_function(s.ax[i], s.ay[i], s.cx[i], s.cy[i]);
    e.w[i] = edge_function(s.bx[i], s.by[i], s.ax[i], s.ay[i]);
  }
  return e;
}

[[gnu::always_inline]] inline BlockHits intersect_triangles(const WatertightRay& r, const TriangleBlock& tri,
                                                            float tmax) {
  using simd::f8, simd::i8;
  const ShearedBlock sheared(r, tri);
  const f8 &ax = sheared.ax, &ay = sheared.ay, &bx = sheared.bx, &by = sheared.by, &cx = sheared.cx, &cy = sheared.cy;
  EdgeFunctions e{cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax};
  const i8 on_edge = (e.u == 0.f) | (e.v == 0.f) | (e.w == 0.f);
  if (const uint32_t edge = simd::bits(on_edge)) e = exact_edge_functions(edge, r, tri, e);
  const f8 &u = e.u, &v = e.v, &w = e.w;
  // Outside: edge functions of both signs (a lane with NaN vertices fails the t test below).
  const i8 outside = (simd::min_ignore_nan(u, simd::min_ignore_nan(v, w)) < 0.f) &
                     (simd::max_ignore_nan(u, simd::max_ignore_nan(v, w)) > 0.f);
  const f8 det = u + v + w;

  // Scaled distance T = det · t.
  const f8 az = r.sz * sheared.a_z, bz = r.sz * sheared.b_z, cz = r.sz * sheared.c_z;
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
  using simd::abs;
  const auto largest = [](f8 p, f8 q, f8 s) {
    const f8 m = abs(p) > abs(q) ? abs(p) : abs(q);
    return m > abs(s) ? m : abs(s);
  };
  const f8 max_x = largest(ax, bx, cx), max_y = largest(ay, by, cy), max_z = largest(az, bz, cz);
  const f8 delta_x = gamma(5) * (max_x + 2 * std::abs(r.sx) * max_z);
  const f8 delta_y = gamma(5) * (max_y + 2 * std::abs(r.sy) * max_z);
  const f8 delta_z = gamma(3) * max_z;
  const f8 delta_e = 2 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const f8 max_e = largest(u, v, w);
  const f8 delta_t = 3 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * abs(hits.inv_det);
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
