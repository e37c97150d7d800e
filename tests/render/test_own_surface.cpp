// World::meets_own_surface: a shadow ray it calls blocked by its own closed surface is, when traced.

#include <catch2/catch.hpp>

#include "core/base/rng.h"
#include "core/base/warp.h"
#include "core/render/world.h"
#include "tests/support/test_scenes.h"

using namespace prism;

TEST_CASE("World: a ray into a closed translucent object, ending beyond it, meets the object when traced") {
  Scene scene;
  PbrMaterial rough_glass = PbrMaterial::plastic(Rgb{0.9f, 0.9f, 0.9f}, 0.4f);
  rough_glass.transmission = 1;
  scene.materials.push_back(Material{.name = "rough glass", .kind = rough_glass});
  Material cut_out{.name = "cut out", .kind = rough_glass, .alpha_mode = AlphaMode::mask};
  scene.materials.push_back(cut_out);
  scene.materials.push_back(test::diffuse(Rgb{0.5f, 0.5f, 0.5f}));
  const Mesh sphere = test::make_icosphere({0, 0, 0}, 1, 2, 0);
  Mesh open = sphere;
  open.indices.resize(open.indices.size() - 3);
  Mesh masked = sphere, opaque = sphere;
  masked.material = 1, opaque.material = 2;
  scene.meshes = {sphere, open, masked, opaque};
  // The closed sphere three times (moved; stretched; mirrored, which turns its winding inside out),
  // then the open one, the cut-out one and the one that lets no light through.
  const std::vector<std::pair<uint32_t, Transform>> placed = {
      {0, Transform::translate({0, 0, 0})},
      {0, Transform::translate({4, 0.5, 0}) * Transform::scale({1.5, 0.6, 1})},
      {0, Transform::translate({-4, 0, 1}) * Transform::scale({1, -1, 1})},
      {1, Transform::translate({0, 4, 0})},
      {2, Transform::translate({4, 4, 0})},
      {3, Transform::translate({-4, 4, 0})}};
  for (const auto& [mesh, to_world] : placed) scene.instances.push_back({mesh, to_world});
  const World world(scene);

  Rng rng(7, 0);
  for (uint32_t instance = 0; instance < placed.size(); ++instance) {
    const Vec3f centre(placed[instance].second.point({0, 0, 0}));
    int skipped = 0, tried = 0;
    for (int i = 0; i < 4000; ++i) {
      // A point on the sphere, reached from outside (its front) or from its centre (its back).
      const Vec3f d = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const bool inside = i % 2 == 1;
      const Ray to_surface = inside ? Ray{centre, d, kInfinity} : Ray{centre + d * 10.f, -d, kInfinity};
      const std::optional<SurfaceInteraction> si = world.intersect(to_surface);
      if (!si || si->instance != instance) continue;  // another object first, or out through the open one
      // A shadow ray from it to a point up to 20 m away, or to infinity.
      const Vec3f w = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const Ray shadow =
          i % 3 == 0 ? si->spawn(w)
                     : spawn_ray_to(si->p, si->p_error, si->n, si->p + w * (20 * rng.uniform()), Vec3f(0, 0, 0), w);
      ++tried;
      if (!world.meets_own_surface(*si, shadow)) continue;
      ++skipped;
      const std::optional<SurfaceInteraction> blocker = world.intersect(shadow);
      REQUIRE(blocker);
      REQUIRE(blocker->instance == instance);
      REQUIRE(world.transmittance(shadow) == 0);
    }
    INFO("instance " << instance << ": " << skipped << " of " << tried << " shadow rays known to be blocked");
    REQUIRE(tried > 1000);
    // Half of the directions from a point lead inside, and most points 20 m away lie outside.
    if (instance < 3)
      CHECK(skipped > tried / 4);
    else
      CHECK(skipped == 0);
  }
}
