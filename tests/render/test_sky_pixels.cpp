// The renderer gives a pixel the constant sky's value without tracing its camera rays when the
// accel says nothing in the pencil of rays through the pixel can be hit (Camera::frustum,
// Accel::may_meet). That must be conservative: every camera ray through such a pixel leaves the
// scene. Checked with rays through the pixels' corners, edge midpoints and random points, for
// both projections, over flattened triangles and instances (rotated, scaled, mirrored) of a
// shared mesh; and it must cull most of the pixels whose sampled rays all miss, or it saves nothing.

#include <catch2/catch.hpp>

#include "core/base/rng.h"
#include "core/render/camera.h"
#include "core/render/world.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Scene scattered_scene() {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}));
  scene.meshes.push_back(test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.instances = {
      {0, Transform::translate({-3, 1, 0})},
      {0,
       Transform::translate({2.5, -1, -2}) * Transform::rotate(0.2, 0.4, 0.1, 0.9) * Transform::scale({1, 0.4, 0.7})},
      {0, Transform::translate({0.5, 2.5, -4}) * Transform::scale({0.6, 0.6, -0.6})},  // mirrored
  };
  Rng rng(5, 0);
  for (int i = 0; i < 12; ++i) {  // small triangles, flattened into the world tree
    const Vec3f c{8 * rng.uniform() - 4, 6 * rng.uniform() - 3, -6 * rng.uniform()};
    const Vec3f u{0.4f * rng.uniform(), 0.4f * rng.uniform(), 0.f}, v{0.f, 0.4f * rng.uniform(), 0.4f};
    test::add_mesh(scene, test::make_quad(c, u, v, 0));
  }
  return scene;
}

}  // namespace

TEST_CASE("a pixel whose rays the accel cannot meet has no camera ray that hits anything") {
  const Scene scene = scattered_scene();
  for (const bool orthographic : {false, true}) {
    CameraDesc desc = test::look_at({0.5f, 0.3f, 9}, {0, 0, -2}, 45.f);
    if (orthographic) {
      desc.projection = CameraDesc::Projection::orthographic;
      desc.ymag = 4.f;
    }
    for (const uint64_t instance_from : {uint64_t(0), uint64_t(1) << 16}) {  // instanced, then flattened
      INFO((orthographic ? "orthographic" : "perspective") << ", instance_from " << instance_from);
      const World world(scene, {.instance_from = instance_from});
      const Camera camera(desc, 64, 48);
      Rng rng(9, 0);
      int culled = 0, all_miss = 0, some_hit = 0;
      for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
          const bool cull = !world.accel().may_meet(camera.frustum(x, y, x + 1, y + 1));
          std::vector<Vec2f> film;
          for (const float fx : {0.f, 0.5f, 1.f})
            for (const float fy : {0.f, 0.5f, 1.f}) film.push_back({x + fx, y + fy});
          for (int i = 0; i < 24; ++i) film.push_back({x + rng.uniform(), y + rng.uniform()});
          bool hit = false;
          for (const Vec2f& f : film) {
            AccelHit h;
            hit |= world.accel().intersect(camera.generate_ray(f.x, f.y), h);
          }
          INFO("pixel " << x << ", " << y);
          REQUIRE(!(cull && hit));
          culled += cull;
          all_miss += !hit;
          some_hit += hit;
        }
      CHECK(some_hit > 200);              // the scene is in view
      CHECK(culled >= all_miss * 3 / 4);  // and the pixels around it are mostly culled
      CHECK(culled < camera.width() * camera.height());
    }
  }
}

TEST_CASE("a tile of pixels the accel cannot meet holds no pixel that it can") {
  const Scene scene = scattered_scene();
  const World world(scene, {.instance_from = 0});
  const Camera camera(test::look_at({0.5f, 0.3f, 9}, {0, 0, -2}, 45.f), 64, 48);
  int tiles_culled = 0;
  for (int y0 = 0; y0 < camera.height(); y0 += 16)
    for (int x0 = 0; x0 < camera.width(); x0 += 16) {
      if (world.accel().may_meet(camera.frustum(x0, y0, x0 + 16, y0 + 16))) continue;
      ++tiles_culled;
      for (int y = y0; y < y0 + 16; ++y)
        for (int x = x0; x < x0 + 16; ++x) REQUIRE(!world.accel().may_meet(camera.frustum(x, y, x + 1, y + 1)));
    }
  CHECK(tiles_culled > 0);
}
