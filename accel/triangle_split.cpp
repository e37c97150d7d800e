#include "accel/triangle_split.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include <algorithm>
#include <cmath>

#include "accel/triangle.h"
#include "base/math.h"

namespace prism {

namespace {

using Triangle = std::array<Vec3f, 3>;

// Half the surface area, the SAH's measure.
double half_area(const Bounds3f& b) {
  if (b.empty()) return 0.;
  const Vec3d d(b.diagonal());
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// What splitting could save at most: the box's half area less that of infinitely many boxes
// along the triangle, which is the sum of its projected areas A (|n_x| + |n_y| + |n_z|).
double waste(const Triangle& v, const Bounds3f& box) {
  const Vec3d c = cross(Vec3d(v[1] - v[0]), Vec3d(v[2] - v[0]));
  return std::max(half_area(box) - 0.5 * (std::abs(c.x) + std::abs(c.y) + std::abs(c.z)), 0.);
}

// The exact bounds of the triangle's part inside `box`: the triangle clipped by the box's six
// planes in double (Sutherland & Hodgman 1974), its box rounded outwards by a float step more
// than the clipping's rounding, then cut back to `box`. Empty if the triangle misses the box.
Bounds3f clipped_bounds(const Triangle& v, const Bounds3f& box) {
  std::array<Vec3d, 9> poly{Vec3d(v[0]), Vec3d(v[1]), Vec3d(v[2])}, next;  // a triangle cut by 6 planes: ≤ 9 corners
  int n = 3;
  for (int a = 0; a < 3 && n > 0; ++a)
    for (int side = 0; side < 2 && n > 0; ++side) {
      const double plane = side ? box.hi[a] : box.lo[a];
      const auto inside = [&](const Vec3d& p) { return side ? p[a] <= plane : p[a] >= plane; };
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const Vec3d &p = poly[i], &q = poly[(i + 1) % n];
        if (inside(p)) next[m++] = p;
        if (inside(p) != inside(q)) {
          Vec3d x = p + (q - p) * ((plane - p[a]) / (q[a] - p[a]));
          x[a] = plane;
          next[m++] = x;
        }
      }
      poly = next, n = m;
    }
  Bounds3f out;
  if (n == 0) return out;
  for (int a = 0; a < 3; ++a) {
    double lo = poly[0][a], hi = poly[0][a];
    for (int i = 1; i < n; ++i) lo = std::min(lo, poly[i][a]), hi = std::max(hi, poly[i][a]);
    out.lo[a] = std::max(next_float_down(next_float_down(float(lo))), box.lo[a]);
    out.hi[a] = std::min(next_float_up(next_float_up(float(hi))), box.hi[a]);
  }
  return out;
}

// The plane a box is split at: the coarsest plane of the scene's grid of halvings that crosses
// it (the planes a spatial-median split of the scene, and so mostly the BVH, cuts at), on the
// box's longest axis among those of that level. Karras & Aila's choice.
struct SplitPlane {
  int axis = -1;
  float position = 0.f;
  int level = 64;  // the grid's: 1 for the scene's middle, 2 for its quarters, ...
};
SplitPlane split_plane(const Bounds3f& box, const Bounds3f& scene) {
  SplitPlane best;
  for (int a = 0; a < 3; ++a) {
    const double origin = scene.lo[a], extent = double(scene.hi[a]) - origin;
    if (!(box.hi[a] > box.lo[a]) || !(extent > 0.)) continue;
    const double x0 = (box.lo[a] - origin) / extent, x1 = (box.hi[a] - origin) / extent;
    for (int level = 1; level <= std::min(best.level, 40); ++level) {
      const double cells = std::ldexp(1., level), cell = std::floor(x1 * cells);
      if (std::floor(x0 * cells) == cell) continue;
      const float position = float(origin + cell / cells * extent);
      const bool longer = best.axis < 0 || box.hi[a] - box.lo[a] > box.hi[best.axis] - box.lo[best.axis];
      if (position > box.lo[a] && position < box.hi[a] && (level < best.level || longer)) best = {a, position, level};
      break;
    }
  }
  return best;
}

// Writes up to `pieces` boxes covering the triangle's part inside `box` to out; returns how many.
int split(const Triangle& v, const Bounds3f& box, int pieces, const Bounds3f& scene, Bounds3f* out) {
  const SplitPlane plane = pieces > 1 ? split_plane(box, scene) : SplitPlane{};
  if (plane.axis < 0) return *out = box, 1;
  Bounds3f left_box = box, right_box = box;
  left_box.hi[plane.axis] = plane.position;
  right_box.lo[plane.axis] = plane.position;
  const Bounds3f left = clipped_bounds(v, left_box), right = clipped_bounds(v, right_box);
  if (left.empty() || right.empty()) return split(v, left.empty() ? right : left, pieces, scene, out);
  // The pieces left go to the sides by their area.
  const double l = half_area(left), r = half_area(right);
  const int to_left = std::clamp(int(std::lround(pieces * l / std::max(l + r, 1e-300))), 1, pieces - 1);
  const int written = split(v, left, to_left, scene, out);
  return written + split(v, right, pieces - to_left, scene, out + written);
}

}  // namespace

PrimitiveBoxes split_triangles(std::span<const Triangle> triangles, float budget) {
  const size_t n = triangles.size();
  std::vector<Bounds3f> box(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const Triangle& v = triangles[i];
    const float area = triangle_area(v[0], v[1], v[2]);
    if (!(area > 0.f && std::isfinite(area))) return;  // never hit: left out of the tree
    for (const Vec3f& p : v) box[i].extend(p);
  });
  const Bounds3f scene = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n), Bounds3f{},
      [&](const tbb::blocked_range<size_t>& r, Bounds3f b) {
        for (size_t i = r.begin(); i < r.end(); ++i) b.extend(box[i]);
        return b;
      },
      [](Bounds3f a, const Bounds3f& b) {
        a.extend(b);
        return a;
      });

  // Each triangle's priority (waste · 2^−level)^(1/3), Karras & Aila's (level: of its split plane).
  std::vector<double> priority(n, 0.);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    if (box[i].empty() || budget <= 0.f) return;
    const SplitPlane plane = split_plane(box[i], scene);
    if (plane.axis < 0) return;
    priority[i] = std::cbrt(waste(triangles[i], box[i]) * std::ldexp(1., -plane.level));
  });
  const double total = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n), 0.,
      [&](const tbb::blocked_range<size_t>& r, double s) {
        for (size_t i = r.begin(); i < r.end(); ++i) s += priority[i];
        return s;
      },
      std::plus<>());
  size_t hittable = 0;
  for (const Bounds3f& b : box) hittable += !b.empty();
  const double scale = total > 0. ? budget * double(hittable) / total : 0.;

  // Slots: 1 + the triangle's share of the budget each (pieces that vanish leave empty boxes).
  std::vector<uint32_t> first(n + 1, 0);
  for (size_t i = 0; i < n; ++i)
    first[i + 1] = first[i] + (box[i].empty() ? 0 : 1 + uint32_t(std::min(priority[i] * scale, 64.)));
  PrimitiveBoxes out;
  out.bounds.resize(first[n]);
  out.prims.resize(first[n]);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const int pieces = int(first[i + 1] - first[i]);
    if (pieces == 0) return;
    split(triangles[i], box[i], pieces, scene, &out.bounds[first[i]]);
    std::fill_n(&out.prims[first[i]], pieces, uint32_t(i));
  });
  return out;
}

}  // namespace prism
