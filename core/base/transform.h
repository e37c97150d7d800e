#pragma once
// Affine transforms as 4x4 double matrices (the scene loader composes node hierarchies in double
// and rounds to float once, at the leaves).

#include <array>

#include "core/base/bounds.h"
#include "core/base/vec.h"

namespace prism {

struct Transform {
  std::array<std::array<double, 4>, 4> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

  static Transform translate(const Vec3d& t);
  static Transform scale(const Vec3d& s);
  // Rotation from a unit quaternion (x, y, z, w), glTF's convention.
  static Transform rotate(double qx, double qy, double qz, double qw);
  // From 16 numbers in column-major order (glTF node.matrix).
  static Transform from_column_major(const double* values);

  Transform operator*(const Transform& b) const;
  Vec3d point(const Vec3d& p) const;
  Vec3d vector(const Vec3d& v) const;
  bool operator==(const Transform&) const = default;
};

// An affine transform's top three rows rounded to float: the compact form each instance keeps
// (48 bytes, not 128, so that millions of instances fit). Applied in double like Transform, so
// every structure built from an instance sees the same numbers.
struct AffineTransform {
  std::array<std::array<float, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  AffineTransform() = default;
  AffineTransform(const Transform& t);  // implicit: rounds each entry (the bottom row is dropped)
  Transform transform() const;          // exact
  Transform inverse() const;            // by the adjugate, in double; all zeros when singular
  double determinant() const;           // of the linear part: < 0 means the transform mirrors
  Vec3d point(const Vec3d& p) const;
  Vec3d vector(const Vec3d& v) const;
  // A float point transformed in double and rounded once: how the accel places a mesh's triangles
  // in world space, so that World's lights and shading points are the very triangles rays hit.
  Vec3f point_rounded(const Vec3f& p) const { return Vec3f(point(Vec3d(p))); }
  bool operator==(const AffineTransform&) const = default;
};

// Inline: the accel applies them on every entry into an instance and to every vertex of a hit on one.
inline Vec3d Transform::point(const Vec3d& p) const {
  const double x = m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3];
  const double y = m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3];
  const double z = m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3];
  const double w = m[3][0] * p.x + m[3][1] * p.y + m[3][2] * p.z + m[3][3];
  return w == 1 ? Vec3d(x, y, z) : Vec3d(x, y, z) / w;
}
inline Vec3d Transform::vector(const Vec3d& v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
inline Vec3d AffineTransform::point(const Vec3d& p) const {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}
inline Vec3d AffineTransform::vector(const Vec3d& v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Transform inverse(const Transform& t);
Transform transpose(const Transform& t);
double determinant3x3(const Transform& t);  // of the linear part: < 0 means the transform mirrors

// World-space box of a box under an affine transform, rounded outwards, and padded by a little
// more than the rounding of a ray transformed into the instance's space: the accel's world tree
// never culls an instance that the ray, in object space, would hit, and every point of the box
// placed by point_rounded lies inside.
Bounds3f transform_bounds(const AffineTransform& m, const Bounds3f& b);

}  // namespace prism
