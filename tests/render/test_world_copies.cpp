// World shades meshes whose shading arrays are copies of another's from that one (glTF primitives
// sharing accessors but not materials): a hit still gets its own mesh's material, and a mesh that
// differs in any shading array keeps its own.

#include <catch2/catch.hpp>

#include "render/world.h"
#include "support/test_scenes.h"

using namespace prism;

namespace {

// A 2 m quad at z = 0 with its lower-left corner at x, facing +z, texture coordinates scaled by s.
Mesh quad_at(float x, uint32_t material, float s = 1, Vec3f normal = {0, 0, 1}) {
  Mesh m = test::make_quad({x, -1, 0}, {2, 0, 0}, {0, 2, 0}, material);
  m.uv[0] = {{0, 0}, {s, 0}, {s, s}, {0, s}};
  m.normals.assign(4, normal);
  return m;
}

// The hit straight below (x, 0, 1).
SurfaceInteraction hit_below(const World& world, float x) {
  const std::optional<SurfaceInteraction> si = world.intersect(Ray{{x, 0, 1}, {0, 0, -1}, kInfinity});
  REQUIRE(si);
  return *si;
}

}  // namespace

TEST_CASE("World: meshes with copied shading arrays keep their own materials and differences") {
  Scene scene;
  for (int i = 0; i < 4; ++i) scene.materials.push_back(test::diffuse(Rgb{0.2f * (i + 1), 0.5f, 0.5f}));
  const Vec3f tilted = normalize(Vec3f{0.3f, 0, 1});
  test::add_mesh(scene, quad_at(-3, 0));              // the first of its kind
  test::add_mesh(scene, quad_at(0, 1));               // a copy but for its material
  test::add_mesh(scene, quad_at(3, 2, 2));            // other texture coordinates
  test::add_mesh(scene, quad_at(6, 3, 1, tilted));    // other normals
  const World world(scene);

  const SurfaceInteraction a = hit_below(world, -2), b = hit_below(world, 1), c = hit_below(world, 4),
                           d = hit_below(world, 7);
  CHECK(a.material == &scene.materials[0]);
  CHECK(b.material == &scene.materials[1]);
  CHECK(c.material == &scene.materials[2]);
  CHECK(d.material == &scene.materials[3]);
  CHECK(b.at.uv[0].x == Approx(a.at.uv[0].x));
  CHECK(c.at.uv[0].x == Approx(2 * a.at.uv[0].x));
  CHECK(c.at.uv[0].y == Approx(2 * a.at.uv[0].y));
  CHECK(a.ns.z == Approx(1));
  CHECK(d.ns.x == Approx(tilted.x));
  CHECK(d.ns.z == Approx(tilted.z));
}
