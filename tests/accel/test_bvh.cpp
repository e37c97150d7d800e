// The acceleration structure against brute force. Accel defines the closest hit as the smallest
// (t, global triangle number) over all triangles, so a correct BVH agrees with testing every
// triangle bit for bit: same hit or miss, same t, same triangle, same barycentrics. Checked on
// random rays, on adversarial rays (through vertices, along edges, axis-parallel in the planes
// of boxes, from inside boxes, at huge and tiny coordinates), on degenerate and coincident
// triangles, on pathological distributions, through instances, and for watertightness.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <optional>

#include "accel/accel.h"
#include "accel/bvh_traverse.h"
#include "accel/triangle.h"
#include "core/base/frame.h"
#include "core/base/rng.h"
#include "core/base/warp.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

using Triangle = std::array<Vec3f, 3>;

struct Soup {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;

  void add(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
    for (const Vec3f& p : {a, b, c}) {
      indices.push_back(uint32_t(positions.size()));
      positions.push_back(p);
    }
  }
  void add(const Mesh& mesh) {
    for (size_t i = 0; i < mesh.indices.size(); i += 3)
      add(mesh.positions[mesh.indices[i]], mesh.positions[mesh.indices[i + 1]], mesh.positions[mesh.indices[i + 2]]);
  }
  Triangle triangle(size_t p) const {
    return {positions[indices[3 * p]], positions[indices[3 * p + 1]], positions[indices[3 * p + 2]]};
  }
};

struct TestScene {
  std::vector<Soup> meshes;
  std::vector<AccelInstance> instances;

  Accel build(const AccelOptions& options = {}) const {
    std::vector<AccelMesh> m;
    for (const Soup& s : meshes) m.push_back({s.positions, s.indices});
    return Accel(m, instances, options);
  }
  // Every triangle in world space, in Accel's global numbering, transformed as Accel does.
  std::vector<Triangle> world_triangles() const {
    std::vector<Triangle> out;
    for (const AccelInstance& inst : instances) {
      const Soup& s = meshes[inst.mesh];
      for (size_t p = 0; p < s.indices.size() / 3; ++p) {
        Triangle t = s.triangle(p);
        for (Vec3f& v : t) v = inst.to_world.point_rounded(v);
        out.push_back(t);
      }
    }
    return out;
  }
};

TestScene single(Soup soup) {
  TestScene s;
  s.meshes.push_back(std::move(soup));
  s.instances.push_back({0, Transform{}});
  return s;
}

struct Reference {
  bool hit = false;
  uint32_t prim = 0;
  TriangleHit h{};
};

// Tests every triangle; keeps the smallest (t, number), as Accel defines the closest hit.
class BruteForce {
 public:
  static constexpr int kLanes = TriangleBlock::kLanes;
  explicit BruteForce(const std::vector<Triangle>& triangles)
      : triangles_(triangles), blocks_((triangles.size() + kLanes - 1) / kLanes) {
    for (uint32_t p = 0; p < triangles.size(); ++p)
      blocks_[p / kLanes].set(int(p % kLanes), triangles[p][0], triangles[p][1], triangles[p][2], p);
  }
  Reference operator()(const Ray& ray) const {
    const WatertightRay wr(ray);
    Reference best;
    best.h.t = ray.tmax;
    for (const TriangleBlock& block : blocks_) {
      const BlockHits hits = intersect_triangles(wr, block, best.h.t);
      for (int lane = 0; lane < kLanes; ++lane) {
        const uint32_t p = block.id[lane];
        const bool closer = hits.t[lane] < best.h.t || (best.hit && hits.t[lane] == best.h.t && p < best.prim);
        if ((hits.mask >> lane & 1) && closer) best = {true, p, hits.lane(lane)};
      }
    }
    return best;
  }
  const Triangle& triangle(uint32_t p) const { return triangles_[p]; }

 private:
  std::vector<Triangle> triangles_;
  std::vector<TriangleBlock> blocks_;
};

std::string describe(const Ray& r) {
  return fmt::format("ray o=({:a}, {:a}, {:a}) d=({:a}, {:a}, {:a}) tmax={}", r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z,
                     r.tmax);
}

// Accel must answer exactly as brute force does.
void require_exact(const Accel& accel, const BruteForce& brute_force, const Ray& ray) {
  const Reference ref = brute_force(ray);
  INFO(describe(ray));
  AccelHit hit;
  REQUIRE(accel.intersect(ray, hit) == ref.hit);
  REQUIRE(accel.occluded(ray) == ref.hit);
  if (!ref.hit) return;
  REQUIRE(hit.t == ref.h.t);
  REQUIRE(accel.global_prim(hit) == ref.prim);
  REQUIRE(hit.b0 == ref.h.b0);
  REQUIRE(hit.b1 == ref.h.b1);
  REQUIRE(hit.b2 == ref.h.b2);
  // The vertices handed back are the hit triangle's, in world space, bit for bit.
  for (int k = 0; k < 3; ++k) REQUIRE(hit.v[k] == brute_force.triangle(ref.prim)[k]);
}

// Two accels over the same triangles answer a ray alike, bit for bit: hit or miss (closest and
// any), and the hit's t, instance, triangle, barycentrics and world-space vertices. The hit, if any.
std::optional<AccelHit> require_same(const Accel& accel, const Accel& reference, const Ray& ray) {
  INFO(describe(ray));
  AccelHit hit, ref;
  const bool got = accel.intersect(ray, hit);
  REQUIRE(got == reference.intersect(ray, ref));
  REQUIRE(accel.occluded(ray) == got);
  if (!got) return std::nullopt;
  REQUIRE(hit.t == ref.t);
  REQUIRE(hit.instance == ref.instance);
  REQUIRE(hit.prim == ref.prim);
  REQUIRE(hit.b0 == ref.b0);
  REQUIRE(hit.b1 == ref.b1);
  REQUIRE(hit.b2 == ref.b2);
  for (int k = 0; k < 3; ++k) REQUIRE(hit.v[k] == ref.v[k]);
  return hit;
}

Vec3f random_in(Rng& rng, float lo, float hi) {
  return {lo + (hi - lo) * rng.uniform(), lo + (hi - lo) * rng.uniform(), lo + (hi - lo) * rng.uniform()};
}

Soup random_triangles(int count, Rng& rng) {
  Soup s;
  for (int i = 0; i < count; ++i) {
    const Vec3f c = random_in(rng, -5, 5);
    s.add(c + random_in(rng, -0.5f, 0.5f), c + random_in(rng, -0.5f, 0.5f), c + random_in(rng, -0.5f, 0.5f));
  }
  return s;
}

Ray random_ray(Rng& rng) {
  return {random_in(rng, -7, 7), sample_uniform_sphere({rng.uniform(), rng.uniform()}),
          rng.uniform() < 0.2f ? 3.f : kInfinity};
}

// Closed unit cubes at integer positions, some sharing faces, as 12 triangles each.
void add_cube(Soup& s, const Vec3f& lo) {
  const auto corner = [&](int i) { return lo + Vec3f(float(i & 1), float(i >> 1 & 1), float(i >> 2 & 1)); };
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& f : faces) {
    s.add(corner(f[0]), corner(f[1]), corner(f[2]));
    s.add(corner(f[0]), corner(f[2]), corner(f[3]));
  }
}

// Boxes, a grid of quads, a sphere, slivers, zero-area and coincident triangles.
Soup adversarial_scene() {
  Soup s;
  for (const Vec3f lo : {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(-2, 0, 1), Vec3f(0, 0, -3)})
    add_cube(s, lo);
  for (int x = -4; x < 4; ++x)
    for (int z = -4; z < 4; ++z) s.add(test::make_quad({float(x), -1, float(z)}, {1, 0, 0}, {0, 0, 1}, 0));
  s.add(test::make_icosphere({3, 1, 2}, 1.f, 2, 0));
  s.add({-3, 2, -3}, {3, 2.001f, -3}, {3, 2, -2.999f});  // long and thin
  s.add({-3, 3, 0}, {3, 3, 0}, {0, 3, 0});               // zero area: collinear
  s.add({1, 1, 1}, {1, 1, 1}, {1, 1, 1});                // zero area: one point
  s.add({0, 0, 0}, {1, 0, 0}, {1, 1, 0});                // coincides with a cube face's triangle
  return s;
}

// Rays a BVH or a triangle test is most likely to get wrong.
std::vector<Ray> adversarial_rays(const Soup& s, Rng& rng) {
  std::vector<Ray> rays;
  const size_t n = s.indices.size() / 3;
  for (int i = 0; i < 6000; ++i) {
    const Triangle tri = s.triangle(size_t(rng.uniform() * float(n)) % n);
    const Vec3f o = random_in(rng, -6, 6);
    switch (i % 6) {
      case 0:
        rays.push_back({o, normalize(tri[0] - o), kInfinity});
        break;  // at a vertex
      case 1:
        rays.push_back({o, normalize((tri[0] + tri[1]) * 0.5f - o), kInfinity});
        break;   // at an edge
      case 2: {  // along an edge, from outside it or from its first vertex
        const Vec3f e = tri[1] - tri[0];
        if (length(e) == 0.f) continue;
        rays.push_back({rng.uniform() < 0.5f ? tri[0] - e : tri[0], normalize(e), kInfinity});
        break;
      }
      case 3: {  // axis-parallel, from grid points and half-grid points: in the planes of faces
        Vec3f g(std::round(o.x * 2) / 2, std::round(o.y * 2) / 2, std::round(o.z * 2) / 2);
        Vec3f d(0, 0, 0);
        d[i / 6 % 3] = (i / 18) % 2 ? 1.f : -1.f;
        rays.push_back({g, d, kInfinity});
        break;
      }
      case 4:
        rays.push_back({random_in(rng, 0.f, 2.f), sample_uniform_sphere({rng.uniform(), rng.uniform()}),
                        rng.uniform() < 0.5f ? 0.7f : kInfinity});  // from inside the boxes
        break;
      default:
        rays.push_back({o, sample_uniform_sphere({rng.uniform(), rng.uniform()}), kInfinity});
    }
  }
  return rays;
}

}  // namespace

TEST_CASE("closest hit and any hit equal brute force on random rays") {
  Rng rng(3, 0);
  const TestScene scene = single(random_triangles(3000, rng));
  const Accel accel = scene.build();
  const BruteForce brute_force(scene.world_triangles());
  REQUIRE(accel.triangle_count() == 3000);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = random_ray(rng);
    require_exact(accel, brute_force, ray);
    AccelHit h;
    hits += accel.intersect(ray, h);
  }
  CHECK(hits > 2000);  // the test exercises hits, not only misses
}

TEST_CASE("leaves of 1 to 12 triangles (a block partly or wholly used, two blocks) equal brute force") {
  // n overlapping triangles in one cluster are a single leaf; 64 such clusters far apart are a
  // leaf each. Rays aimed into the clusters hit several triangles of a leaf, in any lane of its
  // first block and in its second.
  Rng rng(21, 0);
  for (int n = 1; n <= 12; ++n) {
    for (const int clusters : {1, 64}) {
      INFO(n << " triangles in each of " << clusters << " clusters");
      Soup soup;
      std::vector<Vec3f> centres;
      for (int c = 0; c < clusters; ++c) {
        const Vec3f centre(float(c % 4) * 10, float(c / 4 % 4) * 10, float(c / 16) * 10);
        centres.push_back(centre);
        for (int i = 0; i < n; ++i)
          soup.add(centre + random_in(rng, -1, 1), centre + random_in(rng, -1, 1), centre + random_in(rng, -1, 1));
      }
      const TestScene scene = single(soup);
      const Accel accel = scene.build();
      constexpr int kLanes = TriangleBlock::kLanes;
      if (clusters == 1 && n <= kLanes) {
        // One leaf under the root node: one block and the two per-instance numbers; where triangles lie
        // on the scene's convex hull, a byte per triangle and the instance's first one there.
        bool hull = false;
        for (uint32_t p = 0; p < uint32_t(n); ++p) hull |= accel.hull(0, p).has_value();
        CHECK(accel.memory_bytes() ==
              sizeof(BvhNode) + sizeof(TriangleBlock) + 2 * sizeof(uint32_t) + (hull ? n + sizeof(uint32_t) : 0));
      }
      const BruteForce brute_force(scene.world_triangles());
      int hits = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3f target =
            centres[size_t(rng.uniform() * float(clusters)) % centres.size()] + random_in(rng, -0.3f, 0.3f);
        const Vec3f o = target + sample_uniform_sphere({rng.uniform(), rng.uniform()}) * 5.f;
        const Ray ray{o, normalize(target - o), rng.uniform() < 0.2f ? 5.f : kInfinity};
        require_exact(accel, brute_force, ray);
        AccelHit h;
        hits += accel.intersect(ray, h);
      }
      CHECK(hits > 40);
    }
  }
}

TEST_CASE("a tree that is one leaf is entered only by rays through its box") {
  // A small scene fits one leaf; its root node's box is what spares rays that miss it the
  // triangle tests (most camera rays miss a small scene).
  const std::array<Bounds3f, 3> prims = {Bounds3f{{0, 0, 0}, {1, 1, 1}}, Bounds3f{{1, 0, 0}, {2, 1, 1}},
                                         Bounds3f{{0, 1, 0}, {1, 2, 1}}};
  std::vector<uint32_t> slots;
  const Bvh bvh = Bvh::build(prims, {.block_size = TriangleBlock::kLanes}, slots);
  const auto leaves_entered = [&](const Ray& ray) {
    int entered = 0;
    float tmax = ray.tmax;
    bvh.traverse<false, TriangleBlock>(
        ray, tmax, 0.f, nullptr,
        [&](uint32_t, uint32_t) {
          ++entered;
          return false;
        },
        [](uint32_t) { return false; });
    return entered;
  };
  CHECK(leaves_entered(Ray{{1, 1, -5}, {0, 0, 1}, kInfinity}) == 1);
  CHECK(leaves_entered(Ray{{3, 3, -5}, {0, 0, 1}, kInfinity}) == 0);  // beside the box
  CHECK(leaves_entered(Ray{{1, 1, -5}, {0, 0, 1}, 4.f}) == 0);        // ends before it
  CHECK(leaves_entered(Ray{{1, 1, 5}, {0, 0, 1}, kInfinity}) == 0);   // beyond it, leaving
}

TEST_CASE("adversarial rays equal brute force, at ordinary, huge and tiny coordinates") {
  Rng rng(4, 0);
  const Soup base = adversarial_scene();
  const std::vector<Ray> base_rays = adversarial_rays(base, rng);
  struct Scale {
    float factor, offset;
  };
  for (const Scale sc : {Scale{1, 0}, Scale{1e6f, 3e6f}, Scale{1e-6f, 0}, Scale{1e-6f, 1e-5f}}) {
    INFO("scale " << sc.factor << ", offset " << sc.offset);
    Soup soup = base;
    for (Vec3f& p : soup.positions) p = p * sc.factor + Vec3f(sc.offset, sc.offset, sc.offset);
    const TestScene scene = single(soup);
    const Accel accel = scene.build();
    const BruteForce brute_force(scene.world_triangles());
    int hits = 0;
    for (Ray ray : base_rays) {
      ray.o = ray.o * sc.factor + Vec3f(sc.offset, sc.offset, sc.offset);
      ray.tmax *= sc.factor;
      require_exact(accel, brute_force, ray);
      AccelHit h;
      hits += accel.intersect(ray, h);
    }
    CHECK(hits > 2000);
  }
}

TEST_CASE("coincident and exponentially spaced triangles build and trace exactly") {
  // 3000 copies of one triangle (every split fails: median splits, ties between all of them)
  // and a triangle every power of two (SAH splits off one at a time: the depth limit applies).
  Soup soup;
  for (int i = 0; i < 3000; ++i) soup.add({0, -1, -1}, {0, 1, -1}, {0, 0, 1});
  for (int k = 0; k < 120; ++k) {
    const float x = std::ldexp(1.f, k - 60);
    soup.add({x, -1, -1}, {x, 1, -1}, {x, 0, 1});
  }
  const TestScene scene = single(soup);
  const Accel accel = scene.build();
  const BruteForce brute_force(scene.world_triangles());
  Rng rng(5, 0);
  for (int i = 0; i < 2000; ++i) {
    const float x = std::ldexp(1.f, int(rng.uniform() * 130) - 65) * (rng.uniform() < 0.1f ? -1.f : 1.f);
    const Vec3f d = i % 2 ? Vec3f(1, 0, 0) : normalize(Vec3f(1, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    const Vec3f o(x, 0.1f * (rng.uniform() - 0.5f), 0.1f * (rng.uniform() - 0.5f));
    require_exact(accel, brute_force, {o, d, kInfinity});
  }
  AccelHit hit;
  REQUIRE(accel.intersect({{-1, 0, 0}, {1, 0, 0}, kInfinity}, hit));
  CHECK(accel.global_prim(hit) == 0);  // of all the equally close copies, the first
}

TEST_CASE("shared meshes traced through their instances' transforms") {
  Rng rng(6, 0);
  TestScene scene;
  scene.meshes.push_back(random_triangles(500, rng));
  Soup sphere;
  sphere.add(test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.meshes.push_back(sphere);
  scene.instances = {
      {1, Transform::translate({0, 0, 6}) * Transform::rotate(0.3, 0.2, 0.1, 0.9) * Transform::scale({2, 1, 0.5})},
      {0, Transform{}},
      {1, Transform::translate({-6, 1, 0}) * Transform::scale({1.5, 1.5, -1.5})},  // mirrored
      {0, Transform::translate({0, -12, 0}) * Transform::rotate(0, 0, 0.7071, 0.7071)},
      {1, Transform::translate({5, -3, 1})},
  };
  const Accel accel = scene.build({.instance_from = 0});  // (by default meshes this small are flattened)
  const Accel reference = scene.build({.instance_from = 0, .brute_force = true});
  const Accel flat = scene.build({.flatten_instances = true});
  const BruteForce brute_force(scene.world_triangles());
  CHECK(accel.memory_bytes() < flat.memory_bytes());  // the shared meshes are stored once
  int hits = 0, prim_differs = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray = random_ray(rng);
    ray.o = ray.o * 2.f;
    INFO(describe(ray));
    // Exactly as testing every triangle in the same spaces ...
    const std::optional<AccelHit> hit = require_same(accel, reference, ray);
    // A shared mesh's triangle comes back in world space, transformed exactly as flattening
    // transforms it (so as World's lights and the shading point see it), mirrored ones too.
    if (hit)
      for (int k = 0; k < 3; ++k) REQUIRE(hit->v[k] == brute_force.triangle(accel.global_prim(*hit))[k]);
    // ... and, to rounding, as the same triangles flattened into world space.
    require_exact(flat, brute_force, ray);
    AccelHit f;
    REQUIRE(flat.intersect(ray, f) == hit.has_value());
    if (hit) {
      ++hits;
      // Rounding follows the coordinates' magnitude, not only t's (as raybench's check says).
      const float magnitude = std::max({hit->t, f.t, std::abs(ray.o.x), std::abs(ray.o.y), std::abs(ray.o.z)});
      CHECK(std::abs(hit->t - f.t) <= 2e-5f * magnitude);
      prim_differs += accel.global_prim(*hit) != flat.global_prim(f);
    }
  }
  CHECK(hits > 500);
  CHECK(prim_differs <= hits / 1000);
}

TEST_CASE("a large mesh and its copies (the same bits, other materials) share one tree, small ones stay flat") {
  Rng rng(8, 0);
  Soup sphere;  // 81,920 triangles: its copy adds more than AccelOptions::instance_from's default flattened
  sphere.add(test::make_icosphere({0, 0, 0}, 1.f, 6, 0));
  TestScene copies;
  copies.meshes = {sphere, sphere, random_triangles(100, rng)};
  copies.instances = {
      {0, Transform::translate({0, 0, 3})}, {1, Transform::rotate(0.3, 0.2, 0.1, 0.9)}, {2, Transform{}}};
  TestScene one = copies;  // the second instance names the first mesh itself
  one.instances[1].mesh = 0;
  TestScene nearly = copies;  // one coordinate of the copy one float apart: a mesh of its own
  nearly.meshes[1].positions[7].x = std::nextafter(nearly.meshes[1].positions[7].x, 2.f);
  const Accel accel = copies.build();
  const Accel reference = one.build();
  CHECK(accel.memory_bytes() == reference.memory_bytes());
  CHECK(nearly.build().memory_bytes() > accel.memory_bytes());
  TestScene small;  // 100 triangles named by two instances, and a copy: flattened unless told otherwise
  small.meshes = {copies.meshes[2], copies.meshes[2]};
  small.instances = {{0, Transform{}}, {0, Transform::translate({1, 0, 0})}, {1, Transform::translate({2, 0, 0})}};
  CHECK(small.build().memory_bytes() == small.build({.flatten_instances = true}).memory_bytes());
  CHECK(small.build({.instance_from = 0}).memory_bytes() < small.build().memory_bytes());
  int hits = 0;
  for (int i = 0; i < 20000; ++i) hits += require_same(accel, reference, random_ray(rng)).has_value();
  CHECK(hits > 500);
}

TEST_CASE("a forest of instances of a small mesh, with empty instances among them") {
  Rng rng(7, 0);
  TestScene scene;
  scene.meshes = {random_triangles(3, rng), Soup{}, random_triangles(20, rng)};  // shared, empty, flattened
  for (int i = 0; i < 400; ++i) {
    const Vec3f at = random_in(rng, -8, 8);
    scene.instances.push_back({0, Transform::translate(Vec3d(at)) * Transform::rotate(0.5, 0.5, 0.5, 0.5) *
                                      Transform::scale({0.5, 0.5, i % 2 ? 0.5 : -0.5})});
    // Empty instances between the others: the same first triangle number as the next one.
    if (i % 100 == 0) scene.instances.push_back({1, Transform{}});
    if (i == 200) scene.instances.push_back({2, Transform{}});
  }
  const Accel accel = scene.build({.instance_from = 0});
  // Too many instances for their inverses to be kept beside so small a tree: each is inverted
  // on entry, and the whole accel stays smaller than the inverses alone would be.
  CHECK(accel.memory_bytes() < scene.instances.size() * sizeof(Transform));
  const Accel reference = scene.build({.instance_from = 0, .brute_force = true});
  const BruteForce brute_force(scene.world_triangles());
  // Global triangle number -> (instance, triangle), counted here independently of the accel.
  std::vector<std::pair<uint32_t, uint32_t>> owner;
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    for (uint32_t p = 0; p < scene.meshes[scene.instances[i].mesh].indices.size() / 3; ++p) owner.push_back({i, p});
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = random_ray(rng);
    INFO(describe(ray));
    const std::optional<AccelHit> hit = require_same(accel, reference, ray);
    if (!hit) continue;
    ++hits;
    const uint32_t global = accel.global_prim(*hit);
    REQUIRE(owner[global] == std::pair(hit->instance, hit->prim));
    for (int k = 0; k < 3; ++k) REQUIRE(hit->v[k] == brute_force.triangle(global)[k]);
  }
  CHECK(hits > 500);
}

TEST_CASE("instances number their triangles instance by instance") {
  Rng rng(5, 0);
  // Coordinates on a 1/1024 grid, so that the translated copy and the translated rays are exact.
  const auto snap = [](Vec3f v) {
    for (int i = 0; i < 3; ++i) v[i] = std::round(v[i] * 1024.f) / 1024.f;
    return v;
  };
  Soup soup = random_triangles(200, rng);
  for (Vec3f& p : soup.positions) p = snap(p);
  TestScene scene = single(soup);
  scene.instances.push_back({0, Transform::translate({100, 0, 0})});
  const Accel accel = scene.build();
  const BruteForce brute_force(scene.world_triangles());
  for (int i = 0; i < 2000; ++i) {
    Ray ray = random_ray(rng);
    ray.o = snap(ray.o) + Vec3f(rng.uniform() < 0.5f ? 100.f : 0.f, 0, 0);
    require_exact(accel, brute_force, ray);
    AccelHit hit;
    if (accel.intersect(ray, hit)) CHECK(hit.instance == (accel.global_prim(hit) >= 200 ? 1u : 0u));
  }
}

TEST_CASE("rays from inside a closed mesh never escape (watertight)") {
  struct Placement {
    float scale;
    Vec3f offset;
  };
  for (const Placement pl :
       {Placement{1, {0.1f, -0.2f, 0.3f}}, Placement{1e-6f, {2e-6f, 0, 0}}, Placement{1e5f, {3e6f, -1e6f, 2e6f}}}) {
    INFO("scale " << pl.scale);
    const Mesh sphere = test::make_icosphere(pl.offset, 2.f * pl.scale, 4, 0);
    Soup soup;
    soup.add(sphere);
    TestScene scene = single(soup);
    // The same sphere again, shared, so the instanced path is held to the same standard.
    scene.instances.push_back({0, Transform::translate({0, 0, 10.0 * pl.scale})});
    const Accel accel = scene.build();
    Rng rng(9, 0);
    for (int i = 0; i < 50000; ++i) {
      // Aim at vertices and edge midpoints: the hardest places for a non-watertight test.
      const Triangle tri = soup.triangle(size_t(rng.uniform() * float(soup.indices.size() / 3)));
      const Vec3f shift = i % 2 ? Vec3f(0, 0, 10.f * pl.scale) : Vec3f(0, 0, 0);
      const Vec3f target = (rng.uniform() < 0.5f ? tri[0] : (tri[0] + tri[1]) * 0.5f) + shift;
      const Vec3f o = pl.offset + shift + random_in(rng, -0.5f, 0.5f) * pl.scale;
      const Ray ray{o, normalize(target - o), kInfinity};
      INFO(describe(ray));
      AccelHit hit;
      REQUIRE(accel.intersect(ray, hit));
      REQUIRE(accel.occluded(ray));
    }
  }
}

TEST_CASE("degenerate triangles are never hit, and empty scenes miss") {
  Soup soup;
  soup.add({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  soup.add({0, 0, 1}, {0, 0, 1}, {0, 0, 1});
  const Accel accel = single(soup).build();
  CHECK(accel.triangle_count() == 2);
  AccelHit hit;
  CHECK_FALSE(accel.intersect({{0.5f, 1, 0}, {0, -1, 0}, kInfinity}, hit));
  CHECK_FALSE(accel.intersect({{0, 1, 1}, {0, -1, 0}, kInfinity}, hit));
  const Accel empty;
  CHECK_FALSE(empty.intersect({{0, 0, 0}, {0, 0, 1}, kInfinity}, hit));
  CHECK_FALSE(empty.occluded({{0, 0, 0}, {0, 0, 1}, kInfinity}));
}

TEST_CASE("a ray leaving a surface point never re-hits that surface (conservative t)") {
  // Points exactly on an axis-aligned plane have no rounding error to offset by, so the
  // triangle test itself must reject the t ≈ 0 self-hit at any direction, grazing ones included.
  const std::vector<Vec3f> p = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  const AccelMesh mesh{p, idx};
  const AccelInstance instance{0, Transform{}};
  const Accel accel({&mesh, 1}, {&instance, 1});
  Rng rng(21, 0);
  for (int i = 0; i < 100000; ++i) {
    const Vec3f o(rng.uniform() * 1.8f - 0.9f, rng.uniform() * 1.8f - 0.9f, 0.f);
    Vec3f d = sample_uniform_hemisphere({rng.uniform(), rng.uniform()});
    if (i % 2) d.z = std::min(d.z, 1e-3f);  // many grazing directions
    AccelHit hit;
    REQUIRE_FALSE(accel.intersect({o, normalize(d), kInfinity}, hit));
  }
}

TEST_CASE("no triangle lies on a hull whose points were rounded to infinity") {
  Soup sphere, far;
  sphere.add(test::make_icosphere({0, 0, 0}, 1.f, 1, 0));
  far.add(test::make_icosphere({0, 0, 0}, 1.f, 1, 0));
  far.positions[0].x += 0.5f;  // not a copy of the sphere: flattened too
  TestScene scene;
  scene.meshes = {sphere, far};
  scene.instances = {{0, Transform{}}, {1, Transform::scale({1e39, 1e39, 1e39})}};
  const Accel accel = scene.build();
  for (uint32_t p = 0; p < sphere.indices.size() / 3; ++p) REQUIRE_FALSE(accel.hull(0, p));
}

TEST_CASE("a ray leaving a triangle on a convex hull to the open side cannot meet what the hull holds") {
  Soup sphere, pair, lone;
  sphere.add(test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  pair.add(test::make_icosphere({0, 0, 0}, 1.f, 1, 0));  // two spheres in one mesh: not one convex body
  pair.add(test::make_icosphere({3, 0, 0}, 1.f, 1, 0));
  lone.add(test::make_icosphere({0, 0, 0}, 1.f, 2, 0));  // used once: in the world tree
  TestScene scene;
  scene.meshes = {sphere, pair, lone};
  scene.instances = {{0, Transform::translate({0, 0, 0})},
                     {0, Transform::translate({2.5f, 0.3f, 0}) * Transform::scale({1, 2, 0.7})},
                     {0, Transform::translate({-1, 2.4f, 0.5f}) * Transform::scale({1.2, -1, 1})},  // mirrored
                     {1, Transform::translate({0, -3, 0})},
                     {1, Transform::translate({0, -3, 3})},
                     {2, Transform::translate({6, 0, 0}) * Transform::scale({1, 1.5f, 1})}};
  const Accel accel = scene.build({.instance_from = 0});
  const Accel flat = scene.build({.flatten_instances = true});
  const auto on = [&](const Accel& a, uint32_t instance) {
    const size_t triangles = scene.meshes[scene.instances[instance].mesh].indices.size() / 3;
    int count = 0;
    for (uint32_t p = 0; p < triangles; ++p) count += a.hull(instance, p).has_value();
    return std::pair{count, int(triangles)};
  };
  // Every triangle of a convex mesh is on its hull, none of the pair's facing its twin. In the world
  // tree, a triangle is on the whole scene's hull: the lone sphere's, but not where it faces the
  // others (their instances' boxes count as points of the scene); flattened, neither are the spheres'
  // that face one another.
  CHECK(on(accel, 1).first == on(accel, 1).second);
  CHECK(accel.hull(1, 0)->skip == 1);
  CHECK(on(accel, 3).first > 0);
  CHECK(on(accel, 3).first < on(accel, 3).second);
  CHECK(on(accel, 5).first > on(accel, 5).second / 5);
  CHECK(on(accel, 5).first < on(accel, 5).second);
  for (uint32_t instance = 0; instance < scene.instances.size(); ++instance) {
    CHECK(on(flat, instance).first < on(flat, instance).second);
    for (uint32_t p = 0; p < uint32_t(on(flat, instance).second); ++p)
      if (const auto h = flat.hull(instance, p)) REQUIRE(h->skip == kEveryInstance);
  }
  CHECK(on(flat, 5).first > 0);
  const auto first_on = [&](const Accel& a, uint32_t instance) {
    for (uint32_t p = 0;; ++p)
      if (a.hull(instance, p)) return a.hull(instance, p)->skip;
  };
  CHECK(first_on(accel, 5) == kEveryInstance);

  // From points on the triangles, rays away from the hull's side: skipping what the hull holds
  // changes no hit (they meet the other instances, or nothing). The opposite ray meets the instance.
  const std::vector<Triangle> world = scene.world_triangles();
  for (const Accel* a : {&accel, &flat}) {
    Rng rng(31, 0);
    int skipped = 0, hits = 0, nothing = 0;
    for (int i = 0; i < 20000; ++i) {
      const uint32_t instance = uint32_t(rng.uniform() * scene.instances.size()) % scene.instances.size();
      const Soup& mesh = scene.meshes[scene.instances[instance].mesh];
      const uint32_t prim = uint32_t(rng.uniform() * (mesh.indices.size() / 3)) % (mesh.indices.size() / 3);
      const auto hull = a->hull(instance, prim);
      if (!hull) continue;
      const Triangle& t = world[a->global_prim({0, 0, 0, 0, instance, prim, {}})];
      const Vec3f b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
      const Vec3f p = t[0] * b.x + t[1] * b.y + t[2] * b.z;
      const Vec3f n = normalize(cross(t[1] - t[0], t[2] - t[0]));
      const Vec3f away = dot(hull->centroid - p, n) > 0 ? -n : n;
      const Vec3f d = Frame::from_z(away).to_world(sample_uniform_hemisphere({rng.uniform(), rng.uniform()}));
      if (dot(d, away) < 1e-4f) continue;
      const Vec3f error = (abs(t[0] * b.x) + abs(t[1] * b.y) + abs(t[2] * b.z)) * gamma(7);
      Ray ray = spawn_ray(p, error, n, d);
      INFO(describe(ray));
      AccelHit full, skipping;
      const bool hit = a->intersect(ray, full);
      const bool occluded = a->occluded(ray);
      if (hull->skip == kEveryInstance) REQUIRE_FALSE(hit);
      ray.skip_instance = hull->skip;
      REQUIRE(a->intersect(ray, skipping) == hit);
      REQUIRE(a->occluded(ray) == occluded);
      if (hit) {
        REQUIRE(skipping.instance == full.instance);
        REQUIRE(skipping.prim == full.prim);
        REQUIRE(skipping.t == full.t);
        REQUIRE(full.instance != instance);
      }
      ++skipped, hits += hit, nothing += hull->skip == kEveryInstance;
      AccelHit back;
      REQUIRE(a->intersect(spawn_ray(p, error, n, -d), back));
      REQUIRE(back.instance == instance);
    }
    CHECK(skipped > (a == &accel ? 5000 : 2000));  // flattened, only the scene's hull: fewer triangles
    CHECK(nothing > 500);
    if (a == &accel) CHECK(hits > 500);
  }
}
