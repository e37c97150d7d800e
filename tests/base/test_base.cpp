// Core utilities: transforms, frames, random numbers, warps.

#include <catch2/catch.hpp>

#include "base/frame.h"
#include "base/rng.h"
#include "base/transform.h"
#include "base/warp.h"

using namespace prism;

TEST_CASE("transforms compose and invert") {
  const Transform t = Transform::translate({1, 2, 3}) * Transform::rotate(0.1, 0.7, -0.2, 0.68) *
                      Transform::scale({2, -0.5, 3});
  const Transform round = t * inverse(t);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) CHECK(round.m[i][j] == Approx(i == j ? 1 : 0).margin(1e-12));
  CHECK(determinant3x3(t) < 0);  // the negative scale mirrors
  const Vec3d p = t.point({1, 1, 1});
  const Vec3d back = inverse(t).point(p);
  CHECK(back.x == Approx(1));
  CHECK(back.y == Approx(1));
  CHECK(back.z == Approx(1));
  // A 90° turn about y (glTF quaternion x, y, z, w) takes +x to −z.
  const Vec3d v = Transform::rotate(0, std::sqrt(0.5), 0, std::sqrt(0.5)).vector({1, 0, 0});
  CHECK(v.z == Approx(-1));
}

TEST_CASE("frames are orthonormal and right-handed") {
  Rng rng(1, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f n = sample_uniform_sphere({rng.uniform(), rng.uniform()});
    const Frame f = Frame::from_z(n);
    CHECK(dot(f.x, f.y) == Approx(0).margin(1e-5));
    CHECK(length(f.x) == Approx(1).margin(1e-5));
    CHECK(length(cross(f.x, f.y) - n) == Approx(0).margin(1e-4));
    const Vec3f w = normalize(Vec3f(0.3f, -0.4f, 0.5f));
    CHECK(length(f.to_world(f.to_local(w)) - w) == Approx(0).margin(1e-5));
  }
}

TEST_CASE("PCG32 is deterministic, uniform in [0,1) and jumps ahead exactly") {
  Rng a(42, 7), b(42, 7);
  for (int i = 0; i < 100; ++i) REQUIRE(a.next_u32() == b.next_u32());
  Rng c(42, 7), d(42, 7);
  for (int i = 0; i < 1000; ++i) c.next_u32();
  d.advance(1000);
  CHECK(c.next_u32() == d.next_u32());
  Rng e(1, 0);
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const float u = e.uniform();
    REQUIRE(u >= 0.f);
    REQUIRE(u < 1.f);
    sum += u;
  }
  CHECK(sum / 100000 == Approx(0.5).margin(0.005));
}

TEST_CASE("cosine hemisphere samples have the density they report") {
  // E[g(w)/pdf(w)] = ∫ g over the hemisphere; with g = cos²θ the integral is 2π/3.
  Rng rng(2, 0);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const Vec3f w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    REQUIRE(w.z >= 0.f);
    sum += w.z * w.z / cosine_hemisphere_pdf(w.z);
  }
  CHECK(sum / n == Approx(2 * kPi / 3).epsilon(0.01));
}

TEST_CASE("uniform triangle barycentrics cover the triangle evenly") {
  Rng rng(4, 0);
  int in_corner = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const Vec3f b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
    REQUIRE(b.x >= 0.f);
    REQUIRE(b.y >= 0.f);
    REQUIRE(b.z >= -1e-6f);
    if (b.x > 0.5f) ++in_corner;  // the sub-triangle b0 > 1/2 has a quarter of the area
  }
  CHECK(double(in_corner) / n == Approx(0.25).margin(0.01));
}
