#pragma once
// Watertight ray-triangle intersection (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)): vertices are moved into a ray-aligned frame (translate to the
// origin, permute so the ray's largest axis is z, shear so the ray is +z), where the 2D edge
// functions of a shared edge are computed identically for both triangles. Rays through an edge
// or vertex therefore hit at least one of the triangles sharing it; none slip through.

#include <cmath>

#include "base/ray.h"

namespace prism {

// Per-ray constants of the watertight test, computed once per traversal.
struct WatertightRay {
  Vec3f o;
  int kx, ky, kz;
  float sx, sy, sz;

  explicit WatertightRay(const Ray& ray) : o(ray.o) {
    kz = max_dimension(abs(ray.d));
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    if (ray.d[kz] < 0) std::swap(kx, ky);  // keep the winding of the sheared triangle
    sx = ray.d[kx] / ray.d[kz];
    sy = ray.d[ky] / ray.d[kz];
    sz = 1.f / ray.d[kz];
  }
};

struct TriangleHit {
  float t;
  float b0, b1, b2;  // barycentric weights of v0, v1, v2
};

// Returns true and fills hit for an intersection with 0 < t < tmax (either face).
inline bool intersect_triangle(const WatertightRay& r, const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, float tmax,
                               TriangleHit& hit) {
  const Vec3f a = v0 - r.o, b = v1 - r.o, c = v2 - r.o;
  const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];

  // Scaled barycentrics: 2D edge functions of the edges opposite v0, v1, v2.
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  if (u == 0.f || v == 0.f || w == 0.f) {  // exactly on an edge in float: decide in double
    u = float(double(cx) * by - double(cy) * bx);
    v = float(double(ax) * cy - double(ay) * cx);
    w = float(double(bx) * ay - double(by) * ax);
  }
  if ((u < 0.f || v < 0.f || w < 0.f) && (u > 0.f || v > 0.f || w > 0.f)) return false;
  const float det = u + v + w;
  if (det == 0.f) return false;

  // Scaled distance T = det · t, compared with det · tmax without dividing.
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float t_scaled = u * az + v * bz + w * cz;
  if (det < 0.f && (t_scaled >= 0.f || t_scaled < tmax * det)) return false;
  if (det > 0.f && (t_scaled <= 0.f || t_scaled > tmax * det)) return false;

  const float inv_det = 1.f / det;
  hit = {t_scaled * inv_det, u * inv_det, v * inv_det, w * inv_det};

  // t must exceed the bound on its own rounding error (pbrt-v4 §6.8.7): a ray spawned on the
  // triangle's plane (an axis-aligned face at coordinate 0 has a zero error bound there, so no
  // offset) otherwise re-hits it at t = 0 ± rounding whenever its largest axis is not the normal.
  const float max_x = max_component(abs(Vec3f(ax, bx, cx))), max_y = max_component(abs(Vec3f(ay, by, cy)));
  const float max_z = max_component(abs(Vec3f(az, bz, cz)));
  const float delta_x = gamma(5) * (max_x + max_z), delta_y = gamma(5) * (max_y + max_z), delta_z = gamma(3) * max_z;
  const float delta_e = 2 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const float max_e = max_component(abs(Vec3f(u, v, w)));
  const float delta_t = 3 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * std::abs(inv_det);
  return hit.t > delta_t && hit.t < tmax;
}

}  // namespace prism

namespace prism {

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
