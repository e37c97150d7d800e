#pragma once
// Watertight ray-triangle intersection (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)): vertices are moved into a ray-aligned frame (translate to the
// origin, permute so the ray's largest axis is z, shear so the ray is +z), where the 2D edge
// functions of a shared edge are computed identically for both triangles. Rays through an edge
// or vertex therefore hit at least one of the triangles sharing it; none slip through.
// One implementation, four or eight triangles at a time: the BVH's leaves store triangles in blocks.

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

  // Without branches where a select does (a ray's axes and signs are unpredictable from one ray
  // to the next): the components are read from arrays, not through Vec3's operator[].
  explicit WatertightRay(const Ray& ray) {
    const float d[3] = {ray.d.x, ray.d.y, ray.d.z}, o[3] = {ray.o.x, ray.o.y, ray.o.z};
    kz = max_dimension(abs(ray.d));
    const int next = kz == 2 ? 0 : kz + 1, after = next == 2 ? 0 : next + 1;
    const bool flip = d[kz] < 0;  // swap x and y: keep the winding of the sheared triangle
    kx = flip ? after : next;
    ky = flip ? next : after;
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

// Four triangles, stored lane by lane (160 bytes, two and a half cache lines). Unused lanes hold
// NaN vertices, which never hit. A leaf is a run of blocks, tested two at a time as eight lanes
// (Lanes = simd::f8) and an odd last one alone (simd::f4): a leaf of up to four triangles, the
// most common kind, costs the ray half the memory of an eight-triangle block.
struct alignas(16) TriangleBlock {
  static constexpr int kLanes = 4;
  simd::f4 v[3][3];     // v[vertex][axis]
  uint32_t id[kLanes];  // the owner's number for each triangle

  TriangleBlock() {
    for (auto& vertex : v)
      for (auto& axis : vertex) axis = simd::broadcast<simd::f4>(std::numeric_limits<float>::quiet_NaN());
    for (uint32_t& i : id) i = 0;
  }
  void set(int lane, const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, uint32_t triangle_id) {
    const Vec3f* vs[3] = {&v0, &v1, &v2};
    for (int k = 0; k < 3; ++k)
      for (int axis = 0; axis < 3; ++axis) v[k][axis][lane] = (*vs[k])[axis];
    id[lane] = triangle_id;
  }
};

// The vertex coordinates of the lanes tested together: one block's (simd::f4), or two
// consecutive blocks' side by side (simd::f8). Lane i is triangle i % 4 of block i / 4.
template <typename Lanes>
[[gnu::always_inline]] inline Lanes coordinate(const TriangleBlock* tri, int vertex, int axis) {
  if constexpr (sizeof(Lanes) == sizeof(simd::f4))
    return tri[0].v[vertex][axis];
  else
    return simd::join(tri[0].v[vertex][axis], tri[1].v[vertex][axis]);
}
inline uint32_t lane_id(const TriangleBlock* tri, int lane) {
  return tri[lane / TriangleBlock::kLanes].id[lane % TriangleBlock::kLanes];
}

// The lanes that a ray hits with 0 < t <= tmax (either face), and how. (t = tmax is let through:
// the caller breaks ties with the closest hit so far by triangle number.)
template <typename Lanes>
struct BlockHits {
  uint32_t mask = 0;  // bit i: lane i hits
  Lanes t, u, v, w, inv_det;

  TriangleHit lane(int i) const { return {t[i], u[i] * inv_det[i], v[i] * inv_det[i], w[i] * inv_det[i]}; }
};

// The lanes' vertices relative to the ray's origin, in its permuted axes, and sheared so that
// the ray runs along +z (the z coordinates are not yet scaled by sz).
template <typename Lanes>
struct ShearedBlock {
  Lanes ax, ay, a_z, bx, by, b_z, cx, cy, c_z;

  [[gnu::always_inline]] ShearedBlock(const WatertightRay& r, const TriangleBlock* tri) {
    using simd::broadcast;
    const Lanes ox = broadcast<Lanes>(r.ox), oy = broadcast<Lanes>(r.oy), oz = broadcast<Lanes>(r.oz);
    const auto v = [&](int vertex, int axis) { return coordinate<Lanes>(tri, vertex, axis); };
    a_z = v(0, r.kz) - oz, b_z = v(1, r.kz) - oz, c_z = v(2, r.kz) - oz;
    ax = (v(0, r.kx) - ox) - r.sx * a_z, ay = (v(0, r.ky) - oy) - r.sy * a_z;
    bx = (v(1, r.kx) - ox) - r.sx * b_z, by = (v(1, r.ky) - oy) - r.sy * b_z;
    cx = (v(2, r.kx) - ox) - r.sx * c_z, cy = (v(2, r.ky) - oy) - r.sy * c_z;
  }
};

// Scaled barycentrics: the 2D edge functions of the edges opposite v0, v1, v2.
template <typename Lanes>
struct EdgeFunctions {
  Lanes u, v, w;
};

// The edge functions of the lanes in `lanes` recomputed in double, where the products are exact:
// for rays exactly on an edge in float (rare). Out of line, and given the blocks rather than their
// sheared vertices (it shears them again, identically), so that the common path keeps those in
// registers.
template <typename Lanes>
[[gnu::cold, gnu::noinline]] EdgeFunctions<Lanes> exact_edge_functions(uint32_t lanes, const WatertightRay& r,
                                                                       const TriangleBlock* tri,
                                                                       EdgeFunctions<Lanes> e) {
  const ShearedBlock<Lanes> s(r, tri);
  const auto edge_function = [](double px, double py, double qx, double qy) { return float(px * qy - py * qx); };
  for (; lanes; lanes &= lanes - 1) {
    const int i = std::countr_zero(lanes);
    e.u[i] = edge_function(s.cx[i], s.cy[i], s.bx[i], s.by[i]);
    e.v[i] = edge_function(s.ax[i], s.ay[i], s.cx[i], s.cy[i]);
    e.w[i] = edge_function(s.bx[i], s.by[i], s.ax[i], s.ay[i]);
  }
  return e;
}

// Tests the triangles of tri[0] (Lanes = simd::f4) or of tri[0] and tri[1] (simd::f8).
template <typename Lanes>
[[gnu::always_inline]] inline BlockHits<Lanes> intersect_triangles(const WatertightRay& r, const TriangleBlock* tri,
                                                                   float tmax) {
  using Mask = decltype(Lanes{} < Lanes{});
  const ShearedBlock<Lanes> sheared(r, tri);
  const Lanes &ax = sheared.ax, &ay = sheared.ay, &bx = sheared.bx, &by = sheared.by, &cx = sheared.cx,
              &cy = sheared.cy;
  EdgeFunctions<Lanes> e{cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax};
  const Mask on_edge = (e.u == 0.f) | (e.v == 0.f) | (e.w == 0.f);
  if (const uint32_t edge = simd::bits(on_edge)) e = exact_edge_functions(edge, r, tri, e);
  const Lanes &u = e.u, &v = e.v, &w = e.w;
  // Outside: edge functions of both signs (a lane with NaN vertices fails the t test below).
  const Mask outside = (simd::min_ignore_nan(u, simd::min_ignore_nan(v, w)) < 0.f) &
                       (simd::max_ignore_nan(u, simd::max_ignore_nan(v, w)) > 0.f);
  const Lanes det = u + v + w;

  // Scaled distance T = det · t.
  const Lanes az = r.sz * sheared.a_z, bz = r.sz * sheared.b_z, cz = r.sz * sheared.c_z;
  const Lanes t_scaled = u * az + v * bz + w * cz;
  BlockHits<Lanes> hits;
  hits.inv_det = 1.f / det;
  hits.t = t_scaled * hits.inv_det;
  hits.u = u, hits.v = v, hits.w = w;
  const Mask candidates = ~outside & (det != 0.f) & (hits.t > 0.f) & (hits.t <= tmax);
  if (!simd::bits(candidates)) return hits;  // most blocks a ray reaches: no need for the bound

  // t must exceed its own rounding-error bound δt, or a ray leaving a surface point could hit
  // that surface again at a tiny t: a point exactly on an axis-aligned plane has no error to be
  // offset by (pbrt-v4 §6.8.4, from the error of each step above). The shear's share of the
  // error is |s|·|z| rather than pbrt's |z| (which takes |s| ≤ 1): otherwise the bound of a ray
  // grazing a small triangle exceeds t itself, and true hits are lost.
  using simd::abs;
  const auto largest = [](Lanes p, Lanes q, Lanes s) {
    const Lanes m = abs(p) > abs(q) ? abs(p) : abs(q);
    return m > abs(s) ? m : abs(s);
  };
  const Lanes max_x = largest(ax, bx, cx), max_y = largest(ay, by, cy), max_z = largest(az, bz, cz);
  const Lanes delta_x = gamma(5) * (max_x + 2 * std::abs(r.sx) * max_z);
  const Lanes delta_y = gamma(5) * (max_y + 2 * std::abs(r.sy) * max_z);
  const Lanes delta_z = gamma(3) * max_z;
  const Lanes delta_e = 2 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const Lanes max_e = largest(u, v, w);
  const Lanes delta_t = 3 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * abs(hits.inv_det);
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
