#include "core/base/transform.h"

#include <algorithm>
#include <cmath>

#include "core/base/math.h"

namespace prism {

Transform Transform::translate(const Vec3d& t) {
  Transform r;
  r.m[0][3] = t.x;
  r.m[1][3] = t.y;
  r.m[2][3] = t.z;
  return r;
}

Transform Transform::scale(const Vec3d& s) {
  Transform r;
  r.m[0][0] = s.x;
  r.m[1][1] = s.y;
  r.m[2][2] = s.z;
  return r;
}

Transform Transform::rotate(double x, double y, double z, double w) {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  if (n > 0) x /= n, y /= n, z /= n, w /= n;
  Transform r;
  r.m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0};
  r.m[1] = {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0};
  r.m[2] = {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0};
  return r;
}

Transform Transform::from_column_major(const double* v) {
  Transform r;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) r.m[row][col] = v[col * 4 + row];
  return r;
}

Transform Transform::operator*(const Transform& b) const {
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

Transform transpose(const Transform& t) {
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = t.m[j][i];
  return r;
}

double determinant3x3(const Transform& t) {
  const auto& m = t.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// General 4x4 inverse by Gauss-Jordan elimination with partial pivoting. A singular matrix
// (e.g. a zero scale) yields all zeros, which downstream code treats as degenerate geometry.
Transform inverse(const Transform& t) {
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = t.m[i][j];
      a[i][j + 4] = i == j ? 1 : 0;
    }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (a[pivot][col] == 0) return Transform{{}};
    if (pivot != col)
      for (int j = 0; j < 8; ++j) std::swap(a[col][j], a[pivot][j]);
    const double inv = 1 / a[col][col];
    for (int j = 0; j < 8; ++j) a[col][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == col || a[r][col] == 0) continue;
      const double f = a[r][col];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
    }
  }
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][j + 4];
  return r;
}

AffineTransform::AffineTransform(const Transform& t) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) m[i][j] = float(t.m[i][j]);
}

Transform AffineTransform::transform() const {
  Transform t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) t.m[i][j] = m[i][j];
  return t;
}

double AffineTransform::determinant() const {
  const auto a = [&](int i, int j) { return double(m[i][j]); };
  return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
         a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
}

// [A t]⁻¹ = [A⁻¹ −A⁻¹t] with A⁻¹ = adj(A) / det(A).
Transform AffineTransform::inverse() const {
  const auto a = [&](int i, int j) { return double(m[i][j]); };
  const double det = determinant();
  if (det == 0 || !std::isfinite(det)) return Transform{{}};
  Transform r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // Cofactor of a(j, i): the adjugate is the transposed cofactor matrix.
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      r.m[i][j] = (a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)) / det;
    }
  for (int i = 0; i < 3; ++i) r.m[i][3] = -(r.m[i][0] * a(0, 3) + r.m[i][1] * a(1, 3) + r.m[i][2] * a(2, 3));
  return r;
}

Bounds3f transform_bounds(const AffineTransform& m, const Bounds3f& b) {
  Vec3d lo(kInfinity, kInfinity, kInfinity), hi(-kInfinity, -kInfinity, -kInfinity);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3d p = m.point(Vec3d(b.corner(corner)));
    lo = min(lo, p), hi = max(hi, p);
  }
  const double magnitude =
      std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)});
  const double pad = magnitude * 0x1p-20;
  Bounds3f out;
  for (int a = 0; a < 3; ++a) {
    out.lo[a] = next_float_down(float(lo[a] - pad));
    out.hi[a] = next_float_up(float(hi[a] + pad));
  }
  return out;
}

}  // namespace prism
