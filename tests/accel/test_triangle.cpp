// The eight-wide watertight triangle test: against an independent double-precision
// Möller–Trumbore oracle, and lane by lane (a triangle's answer does not depend on its lane or
// its neighbours).

#include <catch2/catch.hpp>

#include "accel/triangle.h"
#include "core/base/rng.h"
#include "core/base/warp.h"

using namespace prism;

namespace {

Vec3f random_point(Rng& rng, float scale) {
  return Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * scale;
}

// Möller & Trumbore 1997 in double: t and the barycentrics (b1, b2) of v1 and v2.
bool oracle(const Ray& ray, const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, double& t, double& b1, double& b2) {
  const Vec3d o(ray.o), d(ray.d), e1 = Vec3d(v1) - Vec3d(v0), e2 = Vec3d(v2) - Vec3d(v0);
  const Vec3d p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0) return false;
  const Vec3d s = o - Vec3d(v0);
  b1 = dot(s, p) / det;
  const Vec3d q = cross(s, e1);
  b2 = dot(d, q) / det;
  t = dot(e2, q) / det;
  return b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && t > 0;
}

BlockHits test_one(const Ray& ray, const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, int lane = 0) {
  TriangleBlock block;
  block.set(lane, v0, v1, v2, 7);
  return intersect_triangles(WatertightRay(ray), block, ray.tmax);
}

}  // namespace

TEST_CASE("the watertight test agrees with a double-precision oracle away from edges") {
  Rng rng(11, 0);
  int hits = 0, compared = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3f v0 = random_point(rng, 2), v1 = random_point(rng, 2), v2 = random_point(rng, 2);
    const Vec3f o = random_point(rng, 6);
    const Ray ray{o, normalize(random_point(rng, 2) - o), kInfinity};
    double t = 0, b1 = 0, b2 = 0;
    const bool expected = oracle(ray, v0, v1, v2, t, b1, b2);
    // Within float rounding of an edge, or grazing, either answer is right.
    if (std::min({b1, b2, 1 - b1 - b2}) > -1e-4 && std::min({b1, b2, 1 - b1 - b2}) < 1e-4) continue;
    const BlockHits got = test_one(ray, v0, v1, v2);
    ++compared;
    REQUIRE(bool(got.mask & 1) == expected);
    if (expected) {
      ++hits;
      const TriangleHit h = got.lane(0);
      CHECK(h.t == Approx(t).epsilon(1e-4));
      CHECK(h.b1 == Approx(b1).margin(1e-4));
      CHECK(h.b2 == Approx(b2).margin(1e-4));
      CHECK(h.b0 + h.b1 + h.b2 == Approx(1.f).epsilon(1e-5));
    }
  }
  CHECK(compared > 190000);
  CHECK(hits > 10000);
}

TEST_CASE("a ray grazing a small triangle hits it where it crosses its plane") {
  // From raybench's TransmissionTest shadow rays: 2.8e-5 above a 2 cm floor triangle, descending
  // at 4.6e-5 rad, the ray crosses it at t = 0.6125. A rounding bound that takes the shear's
  // factor as 1 called this t uncertain by 0.63 and dropped the hit.
  const Ray ray{{0.47935390f, -0.39996639f, 1.15646303f}, {-0.99870944f, -4.5787307e-05f, -0.05078885f}, 1.2233250f};
  const BlockHits h = test_one(ray, {-0.12583613f, -0.39999443f, 1.12920797f},
                               {-0.14330773f, -0.39999443f, 1.11508405f}, {-0.14233065f, -0.39999443f, 1.12925732f});
  REQUIRE(h.mask == 1);
  CHECK(h.lane(0).t == Approx(0.6124838).epsilon(1e-5));

  // At random: rays grazing triangles of any orientation at 0.06° to 0.6°, aimed at the centroid.
  // (The bound is conservative: at a grazing angle α it grows as 1 / sin α, and below about 1e-4
  // rad it can exceed t for a triangle not aligned with an axis; such hits may be dropped.)
  Rng rng(5, 0);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.f, 4 * rng.uniform() - 2);  // triangles from 1 cm to 100 m
    const Vec3f v0 = random_point(rng, scale), v1 = random_point(rng, scale), v2 = random_point(rng, scale);
    const Vec3f n = triangle_normal(v0, v1, v2), c = (v0 + v1 + v2) / 3.f, along = normalize(v1 - v0);
    const float sin_angle = std::pow(10.f, -3 + rng.uniform()), distance = scale * (1 + rng.uniform());
    const Vec3f o = c - along * distance + n * (distance * sin_angle);
    const Ray grazing{o, normalize(c - o), kInfinity};
    double t = 0, b1 = 0, b2 = 0;
    if (!oracle(grazing, v0, v1, v2, t, b1, b2) || std::min({b1, b2, 1 - b1 - b2}) < 1e-3) continue;
    ++compared;
    const BlockHits got = test_one(grazing, v0, v1, v2);
    INFO("scale " << scale << ", sin of the grazing angle " << sin_angle);
    REQUIRE(got.mask == 1);
    CHECK(got.lane(0).t == Approx(t).epsilon(1e-6 / sin_angle));  // float rounding, amplified by 1 / sin α
  }
  CHECK(compared > 10000);
}

TEST_CASE("a triangle's answer does not depend on its lane or on the other lanes") {
  Rng rng(12, 0);
  for (int i = 0; i < 20000; ++i) {
    // A block of triangles around a common point the ray passes near, two sharing an edge, so that
    // hits and misses mix in one block. Every other time on an integer grid, with an
    // axis-parallel ray from a grid point: rays then pass exactly through edges and vertices,
    // where the edge functions are exactly 0 and are decided in double.
    const bool grid = i % 2;
    const auto point = [&](float scale) {
      const Vec3f p = random_point(rng, scale);
      return grid ? Vec3f(std::round(p.x), std::round(p.y), std::round(p.z)) : p;
    };
    const Vec3f c = point(1);
    constexpr int kLanes = TriangleBlock::kLanes;
    Vec3f v[kLanes][3];
    for (auto& tri : v)
      for (Vec3f& p : tri) p = c + point(4);
    v[1][0] = v[0][1], v[1][1] = v[0][0];
    const Vec3f o = c + point(4);
    const Ray ray{o, grid ? Vec3f(0, 0, o.z > c.z ? -1.f : 1.f) : normalize(c + point(0.5f) - o), kInfinity};
    const Ray aimed{o, normalize((v[0][0] + v[0][1]) * 0.5f - o), kInfinity};  // at the shared edge
    for (const Ray& r : {ray, aimed}) {
      TriangleBlock block;
      for (int lane = 0; lane < kLanes; ++lane) block.set(lane, v[lane][0], v[lane][1], v[lane][2], lane);
      const BlockHits all = intersect_triangles(WatertightRay(r), block, r.tmax);
      for (int lane = 0; lane < kLanes; ++lane) {
        const int mirror = kLanes - 1 - lane;  // the same triangle alone, in another lane
        const BlockHits alone = test_one(r, v[lane][0], v[lane][1], v[lane][2], mirror);
        REQUIRE(bool(all.mask >> lane & 1) == bool(alone.mask >> mirror & 1));
        if (all.mask >> lane & 1) {
          const TriangleHit a = all.lane(lane), b = alone.lane(mirror);
          REQUIRE(a.t == b.t);
          REQUIRE(a.b0 == b.b0);
          REQUIRE(a.b1 == b.b1);
          REQUIRE(a.b2 == b.b2);
        }
      }
    }
  }
}

TEST_CASE("the test respects tmax, and unused or degenerate lanes never hit") {
  const Vec3f v0(-1, -1, 0), v1(1, -1, 0), v2(0, 1, 0);
  const Ray ray{{0, 0, 1}, {0, 0, -1}, kInfinity};
  CHECK(test_one(ray, v0, v1, v2).mask == 1);
  CHECK(test_one({ray.o, ray.d, 1.f}, v0, v1, v2).mask == 1);  // t = tmax: a candidate (ties)
  CHECK(test_one({ray.o, ray.d, 0.999f}, v0, v1, v2).mask == 0);
  CHECK(test_one({{0, 0, -1}, ray.d, kInfinity}, v0, v1, v2).mask == 0);  // behind the origin
  CHECK(test_one({{0, 0, 0}, ray.d, kInfinity}, v0, v1, v2).mask == 0);   // t = 0
  CHECK(intersect_triangles(WatertightRay(ray), TriangleBlock{}, kInfinity).mask == 0);
  CHECK(test_one(ray, v0, v1, (v0 + v1) * 0.5f).mask == 0);  // zero area
  CHECK(test_one(ray, v0, v0, v0).mask == 0);
  CHECK(test_one({{0, 0, 0}, {1, 0, 0}, kInfinity}, v0, v1, v2).mask == 0);  // in the triangle's plane
}
