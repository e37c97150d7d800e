// World shades meshes whose shading arrays are copies of another's from that one (glTF primitives
// sharing accessors but not materials): a hit still gets its own mesh's material, and a mesh that
// differs in any shading array keeps its own.

#include <catch2/catch.hpp>

#include "core/render/world.h"
#include "tests/support/test_scenes.h"

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
  for (int i = 0; i < 6; ++i) scene.materials.push_back(test::diffuse(Rgb{0.1f * (i + 1), 0.5f, 0.5f}));
  PbrMaterial brushed = PbrMaterial::plastic(Rgb{0.5f, 0.5f, 0.5f}, 0.5f);
  brushed.anisotropy_strength = 0.5f;  // reads the tangents
  scene.materials.push_back(Material{.name = "brushed", .kind = brushed});
  const Vec3f tilted = normalize(Vec3f{0.3f, 0, 1});
  test::add_mesh(scene, quad_at(-3, 0));            // the first of its kind
  test::add_mesh(scene, quad_at(0, 1));             // a copy but for its material
  test::add_mesh(scene, quad_at(3, 2, 2));          // other TEXCOORD_0
  test::add_mesh(scene, quad_at(6, 3, 1, tilted));  // other normals
  Mesh uv1 = quad_at(9, 4), colored = quad_at(12, 5), tangents = quad_at(15, 6);
  uv1.uv[1] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  colored.colors.assign(4, {0.25f, 0.5f, 0.75f, 1});
  tangents.tangents.assign(4, {0, 1, 0, 1});
  for (Mesh* m : {&uv1, &colored, &tangents}) test::add_mesh(scene, std::move(*m));
  const World world(scene);

  for (int i = 0; i < 7; ++i) CHECK(hit_below(world, -2 + 3 * i).material == &scene.materials[i]);
  const SurfaceInteraction a = hit_below(world, -2);
  CHECK(hit_below(world, 4).at.uv[0].x == Approx(2 * a.at.uv[0].x));
  CHECK(hit_below(world, 4).at.uv[0].y == Approx(2 * a.at.uv[0].y));
  CHECK(hit_below(world, 7).ns.x == Approx(tilted.x));
  CHECK(hit_below(world, 10).at.uv[1].x == Approx(3 * a.at.uv[0].x));
  CHECK(hit_below(world, 13).at.vertex_color[2] == Approx(0.75f));
  CHECK(hit_below(world, 16).tangent.y == Approx(1));
}
