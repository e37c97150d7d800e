// glTF geometry that moves: morph targets, skins and animation channels, each checked against
// vertex positions worked out by hand (to 1e-5), and re-posing a loaded file for frames.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = test::temp_dir("gltf_animation_" + name) / (name + ".gltf");
  std::ofstream(path) << text;
  return path;
}

// The world position of vertex `v` of instance `i`.
Vec3d world_vertex(const Scene& scene, size_t i, size_t v) {
  const Instance& inst = scene.instances.at(i);
  return inst.to_world.point(Vec3d(scene.meshes[inst.mesh].positions.at(v)));
}

void check_near(const Vec3d& got, const Vec3d& expected) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), expected (" << expected.x << ", " << expected.y << ", "
               << expected.z << ")");
  CHECK(std::abs(got.x - expected.x) < 1e-5);
  CHECK(std::abs(got.y - expected.y) < 1e-5);
  CHECK(std::abs(got.z - expected.z) < 1e-5);
}

}  // namespace

TEST_CASE("morph targets blend with the node's weights, else the mesh's, sparse targets too") {
  test::GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int nrm = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int t0 = b.floats({0, 0, 0, 1, 0, 0, 0, 2, 0}, "VEC3");  // dense: stretches x and y
  const int n0 = b.floats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");  // tilts the normals towards +x
  const int t1 = b.sparse(3, "VEC3", {2}, {0, 0, 4});            // sparse: lifts vertex 2 in z
  const auto path = write("morph", b.json(fmt::format(R"(
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [{{"mesh": 0, "weights": [0.5, 0.25]}}, {{"mesh": 0, "translation": [10, 0, 0]}}],
  "meshes": [{{"weights": [1, 0], "primitives": [{{"attributes": {{"POSITION": {}, "NORMAL": {}}},
    "targets": [{{"POSITION": {}, "NORMAL": {}}}, {{"POSITION": {}}}]}}]}}])",
                                                      pos, nrm, t0, n0, t1)));
  const Scene scene = load_gltf(path);
  REQUIRE(scene.instances.size() == 2);
  REQUIRE(scene.meshes.size() == 2);  // each node poses its own copy
  // Node 0 (its own weights 0.5, 0.25): p = p0 + 0.5 Δ0 + 0.25 Δ1.
  check_near(world_vertex(scene, 0, 1), {1.5, 0, 0});
  check_near(world_vertex(scene, 0, 2), {0, 2, 1});
  const Vec3f n = scene.meshes[scene.instances[0].mesh].normals[0];
  check_near(Vec3d(n), Vec3d(normalize(Vec3f(0.5f, 0, 1))));
  // Node 1 (the mesh's weights 1, 0), placed by its translation.
  check_near(world_vertex(scene, 1, 1), {12, 0, 0});
  check_near(world_vertex(scene, 1, 2), {10, 3, 0});
}

TEST_CASE("a two-bone skin poses its vertices by joint matrices times inverse bind matrices") {
  // Bone 0 at the origin, bone 1 one unit up and turned 90° about +z. The skinned node's own
  // translation (100, 0, 0) must be ignored; vertex 3 takes its second joint from JOINTS_1.
  test::GltfBuilder b;
  const int pos = b.floats({1, 2, 0, 0, 1, 0, 1, 1, 0, 1, 1, 0}, "VEC3");
  const int nrm = b.floats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
  const int joints0 = b.u16({1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0}, "VEC4");
  const int weights0 = b.floats({1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0, 0, 0}, "VEC4");
  const int joints1 = b.u16({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  const int weights1 = b.floats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0}, "VEC4");
  // Inverse bind matrices (column-major): identity, and a translation by (0, −1, 0).
  const int ibm = b.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,  //
                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
                           "MAT4");
  const int indices = b.u16({0, 1, 2});
  const auto path = write("skin", b.json(fmt::format(R"(
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [
    {{"mesh": 0, "skin": 0, "translation": [100, 0, 0]}},
    {{"children": [2]}},
    {{"translation": [0, 1, 0], "rotation": [0, 0, 0.70710678118654752, 0.70710678118654752]}}
  ],
  "skins": [{{"joints": [1, 2], "inverseBindMatrices": {}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}, "NORMAL": {}, "JOINTS_0": {}, "WEIGHTS_0": {},
    "JOINTS_1": {}, "WEIGHTS_1": {}}}, "indices": {}}}]}}])",
                                                     ibm, pos, nrm, joints0, weights0, joints1, weights1, indices)));
  const Scene scene = load_gltf(path);
  REQUIRE(scene.instances.size() == 1);
  CHECK(scene.instances[0].to_world == Transform{});
  // Bone 1 maps (x, y) to (1 − y, x) + (0, 1): bind-relative (x, y − 1), turned (−(y − 1), x), moved up.
  check_near(world_vertex(scene, 0, 0), {-1, 2, 0});     // all bone 1
  check_near(world_vertex(scene, 0, 1), {0, 1, 0});      // on the joint: both bones agree
  check_near(world_vertex(scene, 0, 2), {0.5, 1.5, 0});  // half (1, 1, 0), half (0, 2, 0)
  check_near(world_vertex(scene, 0, 3), {0.5, 1.5, 0});  // the same, its bone 1 from JOINTS_1
  // Normals by the inverse transpose: bone 1 turns +x to +y; the half-half blend ½(I + R) is a
  // 45° turn scaled by 1/√2, whose inverse transpose turns +x by 45°.
  const auto& normals = scene.meshes[0].normals;
  check_near(Vec3d(normals[0]), {0, 1, 0});
  check_near(Vec3d(normals[1]), {std::sqrt(0.5), std::sqrt(0.5), 0});
}

TEST_CASE("malformed animations, morph targets and skins fail with a message naming the file") {
  test::GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int times = b.floats({0, 1}, "SCALAR");
  const int three = b.floats({0, 0, 0}, "VEC3");
  const int six = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  const int joints = b.u16({0, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0}, "VEC4");
  const int weights = b.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  const auto gltf = [&](const std::string& mesh, const std::string& extra) {
    return b.json(R"("scenes": [{"nodes": [0, 1]}], "nodes": [)" + mesh +
                  R"(, {}], "meshes": [{"primitives": [{"attributes": {"POSITION": )" + std::to_string(pos) + "}}]}]" +
                  extra);
  };
  const auto animation = [&](int output, const std::string& interpolation, const std::string& path) {
    return fmt::format(R"(, "animations": [{{"samplers": [{{"input": {}, "output": {}, "interpolation": "{}"}}],
      "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "{}"}}}}]}}])",
                       times, output, interpolation, path);
  };
  const auto fails = [&](const std::string& name, const std::string& json, const std::string& message) {
    INFO(name);
    GltfOptions options;
    options.time = 0.5;
    CHECK_THROWS_WITH(load_gltf(write(name, json), options),
                      Catch::Contains(name + ".gltf") && Catch::Contains(message));
  };
  fails("keys", gltf(R"({"mesh": 0})", animation(three, "LINEAR", "translation")), "3 values for 2 keys of 3 each");
  fails("cubic", gltf(R"({"mesh": 0})", animation(six, "CUBICSPLINE", "translation")), "6 values for 2 keys of 9 each");
  fails("interpolation", gltf(R"({"mesh": 0})", animation(six, "SMOOTH", "translation")),
        "unknown interpolation 'SMOOTH'");
  fails("weights", gltf(R"({"mesh": 0})", animation(six, "LINEAR", "weights")), "node without morph targets");
  fails("skin", gltf(R"({"mesh": 0, "skin": 3})", ""), "skin 3");
  // A vertex naming joint 5 of a one-joint skin.
  std::string skinned = gltf(R"({"mesh": 0, "skin": 0})", R"(, "skins": [{"joints": [1]}])");
  const std::string attributes = "\"POSITION\": " + std::to_string(pos);
  skinned.replace(skinned.find(attributes), attributes.size(),
                  attributes + fmt::format(R"(, "JOINTS_0": {}, "WEIGHTS_0": {})", joints, weights));
  fails("joint", skinned, "vertex 1 names joint 5 of a skin with 1");
}

namespace {

Scene at(const std::filesystem::path& file, double time, const std::string& animation) {
  GltfOptions options;
  options.time = time;
  options.animation = animation;
  return load_gltf(file, options);
}

}  // namespace

TEST_CASE("animation channels at a time between keys: STEP, LINEAR with slerp, CUBICSPLINE") {
  const auto file = test::write_animated_triangle(test::temp_dir("gltf_animation_animated"));
  // STEP holds the first key until the second.
  check_near(world_vertex(at(file, 1.5, "step"), 0, 0), {1, 2, 3});
  check_near(world_vertex(at(file, 2, "step"), 0, 0), {5, 6, 7});
  // LINEAR at a quarter: the rotation slerped to 22.5° about +y; the morph weight 0.25 lifts z.
  const Scene linear = at(file, 0.5, "linear");
  const double a = kPi / 8;
  check_near(world_vertex(linear, 0, 1), {std::cos(a) + 0.25 * std::sin(a), 0, -std::sin(a) + 0.25 * std::cos(a)});
  check_near(world_vertex(linear, 0, 0), {0.25 * std::sin(a), 0, 0.25 * std::cos(a)});
  // CUBICSPLINE at s = 1/2 of td = 2: p = ½ v0 + td/8 b0 + ½ v1 − td/8 a1.
  const Vec3d v0(0, 0, 0), b0(1, 2, 3), a1(4, 5, 6), v1(7, 8, 9);
  const Vec3d s = v0 * 0.5 + b0 * 0.25 + v1 * 0.5 - a1 * 0.25;
  check_near(world_vertex(at(file, 1, "cubic"), 0, 1), {s.x, 0, 0});
  check_near(world_vertex(at(file, 1, "cubic"), 0, 2), {0, s.y, 0});
  check_near(world_vertex(at(file, 1.5, "0"), 0, 0), {1, 2, 3});  // an animation by its index
  // Before the first key and after the last, the end values hold.
  check_near(world_vertex(at(file, -3, "step"), 0, 0), {1, 2, 3});
  check_near(world_vertex(at(file, 9, "cubic"), 0, 1), {7, 0, 0});
  // The first animation by default, as viewers play a file; every one at once with "all". Without a
  // time, the file's own pose.
  check_near(world_vertex(at(file, 2, ""), 0, 0), {5, 6, 7});  // "step" alone: moved by (5, 6, 7)
  // At t = 2, vertex 0 lifted to (0, 0, 1) by weight 1, scaled to (0, 0, 9), turned 90° about +y
  // to (9, 0, 0), moved by (5, 6, 7).
  check_near(world_vertex(at(file, 2, "all"), 0, 0), {14, 6, 7});
  check_near(world_vertex(load_gltf(file), 0, 1), {1, 0, 0});
  CHECK_THROWS_WITH(at(file, 0, "walk"), Catch::Contains("animated.gltf") && Catch::Contains("no animation 'walk'") &&
                                             Catch::Contains("'linear'"));
}

TEST_CASE("a loaded file re-poses for each frame, rewriting only what moved") {
  GltfOptions options;
  options.time = 0;
  options.animation = "linear";
  GltfScene gltf(test::write_animated_triangle(test::temp_dir("gltf_animation_animated")), options);
  const size_t meshes = gltf.scene().meshes.size();
  const Vec3f* positions = gltf.scene().meshes[0].positions.data();
  CHECK(gltf.animated());
  CHECK_FALSE(gltf.pose(0));   // the same pose
  CHECK_FALSE(gltf.pose(-1));  // before the first key: the same values
  REQUIRE(gltf.pose(0.5));
  CHECK(gltf.scene().meshes.size() == meshes);
  CHECK(gltf.scene().meshes[0].positions.data() == positions);  // rewritten in place
  const double a = kPi / 8;                                     // as in the test above
  check_near(world_vertex(gltf.scene(), 0, 1),
             {std::cos(a) + 0.25 * std::sin(a), 0, -std::sin(a) + 0.25 * std::cos(a)});
}

TEST_CASE("prism render --frames renders an animation's frames to a numbered sequence") {
  const auto file = test::write_animated_triangle(test::temp_dir("gltf_animation_animated"));
  const auto dir = test::temp_dir("gltf_frames");
  const std::string common = "render \"" + file.string() + "\" --spp 1 --width 8 --height 8 --env 1,1,1 -q";
  std::string err;
  REQUIRE(test::run_prism(common + " -o \"" + (dir / "out.##.exr").string() + "\" --frames 1:3 --fps 2", &err) == 0);
  INFO(err);
  for (const char* frame : {"out.01.exr", "out.02.exr", "out.03.exr"}) CHECK(std::filesystem::exists(dir / frame));
  // Without a # pattern the frame number goes before the extension.
  REQUIRE(test::run_prism(common + " -o \"" + (dir / "plain.exr").string() + "\" --frames 0:0") == 0);
  CHECK(std::filesystem::exists(dir / "plain.0000.exr"));
  // Bad ranges fail before any work.
  CHECK(test::run_prism(common + " -o \"" + (dir / "bad.#.exr").string() + "\" --frames 3:1", &err) == 1);
  CHECK(err.find("--frames '3:1'") != std::string::npos);
  CHECK(test::run_prism(common + " -o \"" + (dir / "bad.#.exr").string() + "\" --frames 0:1 --time 1") == 2);
  CHECK(test::run_prism(common + " -o \"" + (dir / "bad.#.exr").string() + "\" --frames 0:1 --fps 0") == 1);
  CHECK_FALSE(std::filesystem::exists(dir / "bad.0.exr"));
}

TEST_CASE("animations that set the same property are named when played together, and the first plays alone") {
  const auto dir = test::temp_dir("gltf_animation_shared");
  // The "cubic" animation made to move the node, as "step" does: a walk and a run of one skeleton.
  std::ifstream in(test::write_animated_triangle(dir));
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string scale = R"("path": "scale")";
  REQUIRE(json.find(scale) != std::string::npos);
  json.replace(json.find(scale), scale.size(), R"("path": "translation")");
  const auto file = dir / "shared.gltf";
  std::ofstream(file) << json;
  const std::string info = "info \"" + file.string() + "\" --time 1";
  std::string err;
  REQUIRE(test::run_prism(info + " --animation all", &err) == 0);
  CHECK_THAT(err, Catch::Contains("shared.gltf: animations 'step' and 'cubic' both set node 0") &&
                      Catch::Contains("translation") && Catch::Contains("the later one wins"));
  REQUIRE(test::run_prism(info, &err) == 0);  // the first alone: nothing is set twice
  CHECK_THAT(err,
             !Catch::Contains("the later one wins") && Catch::Contains("3 animations; a time plays the first, 'step'"));
  REQUIRE(test::run_prism(info + " --animation cubic", &err) == 0);
  CHECK_THAT(err, !Catch::Contains("the later one wins") && !Catch::Contains("3 animations"));
}
