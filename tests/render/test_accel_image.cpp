// The BVH does not change what the renderer draws: images rendered through the BVH are
// identical, bit for bit, to images rendered by testing every triangle for every ray (same
// scene, same seed). Any ray the BVH answered differently (a missed or wrongly ordered hit, a
// culled instance, a lost shadow) would change the image. Faces that coincide (a block's base on
// the floor) are hit at t within the triangle test's rounding of each other, and the BVH must
// still find the one of least rounded t that testing every triangle finds.

#include <catch2/catch.hpp>
#include <cstring>

#include "core/render/renderer.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

std::vector<float> render_xyz(const Scene& scene, const CameraDesc& camera, const AccelOptions& accel,
                              SamplerKind sampler = SamplerKind::independent, uint64_t seed = 3) {
  const World world(scene, accel);
  RenderOptions options;
  options.spp = 4;
  options.seed = seed;
  options.sampler = sampler;
  options.path.max_depth = 8;
  options.progress = false;
  return render(world, Camera(camera, 48, 36), options).state.film.xyz_image();
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Spheres sharing one mesh (which the BVH instances when told to), on a floor, lit by a lamp, an emissive
// quad and the sky.
Scene shared_mesh_scene() {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.8f, 0.6f, 0.4f}));
  Material glow = test::diffuse({0, 0, 0}, "glow");
  glow.emission = RgbIlluminantSpectrum(Rgb{4, 4, 4});
  scene.materials.push_back(glow);
  scene.meshes.push_back(test::make_icosphere({0, 0, 0}, 1.f, 2, 0));
  scene.instances = {
      {0, Transform::translate({-2, 1, 0})},
      {0, Transform::translate({0.5, 0.8, -1}) * Transform::scale({0.8, 0.8, 0.8})},
      {0,
       Transform::translate({2, 1.2, 0.5}) * Transform::rotate(0.2, 0.4, 0.1, 0.9) * Transform::scale({1, 1.5, 0.7})},
  };
  test::add_mesh(scene, test::make_quad({-6, 0, -6}, {0, 0, 12}, {12, 0, 0}, 0));
  test::add_mesh(scene, test::make_quad({-1, 4, -1}, {2, 0, 0}, {0, 0, 2}, 1));
  scene.point_lights.push_back({"lamp", {3, 5, 4}, RgbIlluminantSpectrum(Rgb{30, 30, 30})});
  scene.environment = RgbIlluminantSpectrum(Rgb{0.1f, 0.15f, 0.3f});
  return scene;
}

}  // namespace

TEST_CASE("the BVH renders the image that testing every triangle renders, bit for bit") {
  SECTION("the default Cornell box, its blocks' bases on its floor") {
    const Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/cornell.gltf");
    for (const SamplerKind sampler : {SamplerKind::independent, SamplerKind::sobol})
      for (const uint64_t seed : {3, 6, 7, 8, 12}) {
        INFO("sampler " << int(sampler) << ", seed " << seed);
        const auto bvh = render_xyz(scene, scene.cameras[0], {}, sampler, seed);
        const auto reference = render_xyz(scene, scene.cameras[0], {.brute_force = true}, sampler, seed);
        REQUIRE(same_bits(bvh, reference));
        CHECK(*std::max_element(bvh.begin(), bvh.end()) > 0.f);
      }
  }
  SECTION("a shared mesh, traced through its instances") {
    const Scene scene = shared_mesh_scene();
    const auto camera = test::look_at({0, 3, 8}, {0, 0.5f, 0}, 50.f);
    const auto bvh = render_xyz(scene, camera, {.instance_from = 0});  // (by default so small a mesh is flattened)
    REQUIRE(same_bits(bvh, render_xyz(scene, camera, {.instance_from = 0, .brute_force = true})));
    // The comparison sees the last bit: the same spheres flattened into world space (rounded
    // differently) already give a different image.
    CHECK_FALSE(same_bits(bvh, render_xyz(scene, camera, {.flatten_instances = true})));
  }
}
