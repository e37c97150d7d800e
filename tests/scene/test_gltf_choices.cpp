// glTF primitive modes, scenes and material variants: what a file offers and the user chooses;
// `prism info` and the Khronos sample assets these features come from (in the shared assets,
// PRISM_SHARED_DIR).

#include <catch2/catch.hpp>
#include <fstream>

#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = test::temp_dir("gltf_choices_" + name) / (name + ".gltf");
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("triangle strips and fans become the triangles glTF's winding rules give") {
  // A zigzag of five vertices as a list, an indexed strip and a non-indexed fan.
  test::GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0}, "VEC3");
  const int list = b.u16({0, 1, 2, 1, 3, 2, 2, 3, 4});
  const int strip = b.u16({0, 1, 2, 3, 4});
  const auto gltf = [&](const std::string& primitives) {
    return b.json(R"("scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [)" + primitives +
                  "]}]");
  };
  const auto primitive = [&](int mode, int indices) {
    return fmt::format(R"({{"attributes": {{"POSITION": {}}}, "mode": {}{}}})", pos, mode,
                       indices < 0 ? "" : fmt::format(R"(, "indices": {})", indices));
  };
  const Scene as_list = load_gltf(write("list", gltf(primitive(4, list))));
  const Scene as_strip = load_gltf(write("strip", gltf(primitive(5, strip))));
  const Scene as_fan = load_gltf(write("fan", gltf(primitive(6, -1))));
  // Strip triangle i: (i, i+1+i%2, i+2−i%2); fan triangle i: (i+1, i+2, 0). Both keep one winding.
  CHECK(as_strip.meshes.at(0).indices == std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4});
  CHECK(as_fan.meshes.at(0).indices == std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0});

  // The strip's image is the list's, bit for bit.
  Scene scenes[2] = {as_list, as_strip};
  std::vector<float> images[2];
  for (int i = 0; i < 2; ++i) {
    scenes[i].environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    images[i] = test::render_rgb(scenes[i], test::look_at({1, 0.5f, 3}, {1, 0.5f, 0}, 40), 16, 16, 2).rgb;
  }
  CHECK(images[0] == images[1]);

  // Points and lines are left out with one warning per file, however many there are.
  std::string err;
  const auto lines = write(
      "lines", gltf(primitive(1, -1) + "," + primitive(0, -1) + "," + primitive(3, -1) + "," + primitive(4, list)));
  REQUIRE(test::run_prism("info \"" + lines.string() + "\"", &err) == 0);
  CHECK(err.find("points and lines are not rendered") != std::string::npos);
  CHECK(err.find("not rendered") == err.rfind("not rendered"));
}

TEST_CASE("the option --scene chooses among the file's scenes, by default the file's `scene`") {
  test::GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const auto file = write("scenes", b.json(fmt::format(R"(
  "scene": 1,
  "scenes": [{{"nodes": [0]}}, {{"nodes": [1]}}],
  "nodes": [{{"mesh": 0}}, {{"mesh": 0, "translation": [5, 0, 0]}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}}}}}]}}])",
                                                       pos)));
  const auto x_of = [](const Scene& s) { return s.instances.at(0).to_world.point({0, 0, 0}).x; };
  CHECK(x_of(load_gltf(file)) == 5);
  GltfOptions options;
  options.scene = 0;
  CHECK(x_of(load_gltf(file, options)) == 0);
  options.scene = 2;
  CHECK_THROWS_WITH(load_gltf(file, options),
                    Catch::Contains("scenes.gltf") && Catch::Contains("--scene 2") && Catch::Contains("2 scene(s)"));
}

namespace {

std::filesystem::path variants_file() {
  test::GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  return write("variants", b.json(fmt::format(R"(
  "extensionsUsed": ["KHR_materials_variants"],
  "extensions": {{"KHR_materials_variants": {{"variants": [{{"name": "red"}}, {{"name": "blue"}}, {{"name": "green"}}]}}}},
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "materials": [{{"name": "plain"}}, {{"name": "crimson"}}, {{"name": "navy"}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}}}, "material": 0,
    "extensions": {{"KHR_materials_variants": {{"mappings": [{{"material": 1, "variants": [0]}},
                                                             {{"material": 2, "variants": [1]}}]}}}}}}]}}])",
                                              pos)));
}

}  // namespace

TEST_CASE("KHR_materials_variants: --variant switches the primitives' materials") {
  const auto file = variants_file();
  const auto material_of = [&](const std::string& variant) {
    GltfOptions options;
    options.variant = variant;
    const Scene s = load_gltf(file, options);
    return s.materials.at(s.meshes.at(0).material).name;
  };
  CHECK(material_of("") == "plain");
  CHECK(material_of("red") == "crimson");
  CHECK(material_of("blue") == "navy");
  CHECK(material_of("green") == "plain");  // no mapping: the primitive's own material
  CHECK_THROWS_WITH(material_of("teal"), Catch::Contains("variants.gltf") && Catch::Contains("'teal'") &&
                                             Catch::Contains("'red', 'blue', 'green'"));
}

TEST_CASE("prism info lists scenes, variants, extensions with what Prism does, counts and bounds") {
  std::string out, err;
  REQUIRE(test::run_prism("info \"" + variants_file().string() + "\"", &err, &out) == 0);
  INFO(out << err);
  CHECK(out.find("scenes: 1") != std::string::npos);
  CHECK(out.find("material variants: 3") != std::string::npos);
  CHECK(out.find("'green'") != std::string::npos);
  CHECK(out.find("KHR_materials_variants (used): material sets, chosen with --variant NAME") != std::string::npos);
  CHECK(out.find("triangles: 1 in 1 instances") != std::string::npos);
  CHECK(out.find("bounds: (0, 0, 0) to (1, 1, 0)") != std::string::npos);
  CHECK(out.find("features:") != std::string::npos);
  CHECK(err.empty());
  CHECK(test::run_prism("info \"" + variants_file().string() + "\" --variant teal", &err) == 1);
  CHECK(err.find("no material variant 'teal'") != std::string::npos);
}

TEST_CASE("the shared assets of glTF's geometry and animation features load without warnings and render", "[shared]") {
  const auto root = test::shared_dir() / "assets" / "gltf";
  if (!test::shared_assets_present("assets/gltf")) return;
  for (const char* name :
       {"MeshPrimitiveModes", "SimpleMorph", "MorphPrimitivesTest", "SimpleSkin", "RiggedSimple", "BoxAnimated",
        "InterpolationTest", "MultipleScenes", "MaterialsVariantsShoe", "Cameras", "NegativeScaleTest"}) {
    const auto file = root / name / "glTF" / (std::string(name) + ".gltf");
    INFO(file.string());
    REQUIRE(std::filesystem::exists(file));
    std::string out, err;
    CHECK(test::run_prism("info \"" + file.string() + "\" --time 0.5", &err, &out) == 0);
    CHECK(err.find("ignoring") == std::string::npos);
    CHECK(err.find("error") == std::string::npos);
    // Posed half a second in (animated assets move; the others ignore the time), lit evenly.
    log::set_level(log::Level::quiet);
    GltfOptions options;
    options.time = 0.5;
    Scene scene = load_gltf(file, options);
    log::set_level(log::Level::info);
    CHECK(scene.triangle_count() > 0);
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const CameraDesc camera = scene.cameras.empty() ? framing_camera(scene.world_bounds(), 1.f) : scene.cameras[0];
    const auto img = test::render_rgb(scene, camera, 24, 24, 2, 8);
    CHECK(img.stats.invalid_samples == 0);
    CHECK(img.mean(1) > 0);
  }
}
