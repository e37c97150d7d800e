// The BVH against brute force: closest and any hit on random rays over random triangles, and
// watertightness on closed meshes.

#include <catch2/catch.hpp>

#include "accel/accel.h"
#include "accel/triangle.h"
#include "base/rng.h"
#include "base/warp.h"
#include "support/test_scenes.h"

using namespace prism;

namespace {

struct Soup {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;
};

Soup random_triangles(int count, Rng& rng) {
  Soup s;
  for (int i = 0; i < count; ++i) {
    const Vec3f c(rng.uniform() * 10 - 5, rng.uniform() * 10 - 5, rng.uniform() * 10 - 5);
    for (int k = 0; k < 3; ++k) {
      s.positions.push_back(c + Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
      s.indices.push_back(uint32_t(s.positions.size() - 1));
    }
  }
  return s;
}

// Closest hit by testing every triangle.
bool brute_force(const Soup& s, const Ray& ray, float& t, uint32_t& prim) {
  const WatertightRay wr(ray);
  bool found = false;
  t = ray.tmax;
  for (uint32_t p = 0; p < s.indices.size() / 3; ++p) {
    TriangleHit h;
    if (intersect_triangle(wr, s.positions[s.indices[3 * p]], s.positions[s.indices[3 * p + 1]],
                           s.positions[s.indices[3 * p + 2]], t, h)) {
      t = h.t;
      prim = p;
      found = true;
    }
  }
  return found;
}

Ray random_ray(Rng& rng) {
  const Vec3f o(rng.uniform() * 14 - 7, rng.uniform() * 14 - 7, rng.uniform() * 14 - 7);
  return {o, sample_uniform_sphere({rng.uniform(), rng.uniform()}), rng.uniform() < 0.2f ? 3.f : kInfinity};
}

}  // namespace

TEST_CASE("BVH closest hit and any hit equal brute force on random rays") {
  Rng rng(3, 0);
  const Soup soup = random_triangles(3000, rng);
  const AccelMesh mesh{soup.positions, soup.indices};
  const AccelInstance instance{0, Transform{}};
  const Accel accel({&mesh, 1}, {&instance, 1});
  REQUIRE(accel.triangle_count() == 3000);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = random_ray(rng);
    float t_ref;
    uint32_t prim_ref = 0;
    const bool ref = brute_force(soup, ray, t_ref, prim_ref);
    AccelHit hit;
    const bool got = accel.intersect(ray, hit);
    REQUIRE(got == ref);
    REQUIRE(accel.occluded(ray) == ref);
    if (ref) {
      ++hits;
      REQUIRE(hit.t == t_ref);
      REQUIRE(hit.prim == prim_ref);
      REQUIRE(hit.b0 + hit.b1 + hit.b2 == Approx(1.f));
    }
  }
  CHECK(hits > 2000);  // the test exercises hits, not only misses
}

TEST_CASE("instances place meshes and number triangles instance by instance") {
  Rng rng(5, 0);
  // Coordinates on a 1/1024 grid, so that the translated copy and the translated rays are exact.
  const auto snap = [](Vec3f v) {
    for (int i = 0; i < 3; ++i) v[i] = std::round(v[i] * 1024.f) / 1024.f;
    return v;
  };
  Soup soup = random_triangles(200, rng);
  for (Vec3f& p : soup.positions) p = snap(p);
  const AccelMesh mesh{soup.positions, soup.indices};
  const AccelInstance instances[] = {{0, Transform{}}, {0, Transform::translate({100, 0, 0})}};
  const Accel accel({&mesh, 1}, instances);
  for (int i = 0; i < 2000; ++i) {
    Ray ray = random_ray(rng);
    ray.o = snap(ray.o);
    // The ray from x + 100 meets the copy at +100 as the original ray meets the mesh, and may
    // also reach the untranslated instance 0.
    float t1 = 0, t0 = 0;
    uint32_t prim1 = 0, prim0 = 0;
    const bool hit1 = brute_force(soup, ray, t1, prim1);
    ray.o.x += 100;
    const bool hit0 = brute_force(soup, ray, t0, prim0);
    AccelHit hit;
    REQUIRE(accel.intersect(ray, hit) == (hit0 || hit1));
    if (hit1 && (!hit0 || t1 < t0)) {
      REQUIRE(hit.instance == 1);
      REQUIRE(hit.t == t1);
      REQUIRE(accel.global_prim(hit) == 200 + prim1);
    } else if (hit0) {
      REQUIRE(hit.instance == 0);
      REQUIRE(hit.t == t0);
      REQUIRE(accel.global_prim(hit) == prim0);
    }
  }
}

TEST_CASE("rays from inside a closed mesh never escape (watertight)") {
  const Mesh sphere = test::make_icosphere({0.1f, -0.2f, 0.3f}, 2.f, 4, 0);
  const AccelMesh mesh{sphere.positions, sphere.indices};
  const AccelInstance instance{0, Transform{}};
  const Accel accel({&mesh, 1}, {&instance, 1});
  Rng rng(9, 0);
  for (int i = 0; i < 100000; ++i) {
    // Aim at random vertices and edge midpoints: the hardest places for a non-watertight test.
    const uint32_t tri = uint32_t(rng.uniform() * float(sphere.indices.size() / 3));
    const Vec3f a = sphere.positions[sphere.indices[3 * tri]], b = sphere.positions[sphere.indices[3 * tri + 1]];
    const Vec3f target = rng.uniform() < 0.5f ? a : (a + b) * 0.5f;
    const Vec3f o(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    AccelHit hit;
    REQUIRE(accel.intersect({o, normalize(target - o), kInfinity}, hit));
  }
}

TEST_CASE("degenerate triangles are never hit, and empty scenes miss") {
  const std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5};
  const AccelMesh mesh{p, idx};
  const AccelInstance instance{0, Transform{}};
  const Accel accel({&mesh, 1}, {&instance, 1});
  AccelHit hit;
  CHECK_FALSE(accel.intersect({{0.5f, 1, 0}, {0, -1, 0}, kInfinity}, hit));
  CHECK_FALSE(accel.intersect({{0, 1, 1}, {0, -1, 0}, kInfinity}, hit));
  const Accel empty;
  CHECK_FALSE(empty.intersect({{0, 0, 0}, {0, 0, 1}, kInfinity}, hit));
  CHECK_FALSE(empty.occluded({{0, 0, 0}, {0, 0, 1}, kInfinity}));
}

TEST_CASE("a ray leaving a triangle's plane from a point on it never hits that triangle") {
  // A large quad in the plane y = 0: points on it have y = 0 exactly, so their error bound along
  // the normal is 0 and a spawned ray starts on the plane itself. Leaving at more than 45° from
  // the normal, the ray's largest axis is not y, and the sheared test computes t = 0 ± rounding.
  const Vec3f v0(-50, 0, -50), v1(-50, 0, 50), v2(50, 0, 50);
  Rng rng(7, 0);
  int hits = 0;
  for (int i = 0; i < 10000; ++i) {
    const float b0 = rng.uniform() * 0.5f, b1 = rng.uniform() * 0.5f;
    const Vec3f p = v0 * b0 + v1 * b1 + v2 * (1 - b0 - b1);
    const Vec3f w = sample_uniform_hemisphere(Vec2f(rng.uniform() * 0.7f, rng.uniform()));  // about +z
    TriangleHit h;
    hits += intersect_triangle(WatertightRay(Ray{p, {w.x, w.z, w.y}, kInfinity}), v0, v1, v2, kInfinity, h);
  }
  CHECK(hits == 0);
}
