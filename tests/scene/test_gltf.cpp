// glTF loading: a minimal file in all its variants, and malformed files that must fail with a
// clear message (and, through the CLI, a non-zero exit and no output file).

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene_features.h"
#include "spectral/cie.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;
using test::base64;

namespace {

// One triangle (u16 indices), one emissive material, a camera and a point light, nested nodes.
struct TriangleGltf {
  std::vector<uint16_t> indices = {0, 1, 2};
  std::string buffer_uri;  // empty: embedded data URI
  std::string extra_json;  // spliced into the top-level object
  std::string node_extra;  // spliced into the mesh node

  std::string json() const {
    std::vector<unsigned char> bytes(36 + 8, 0);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::memcpy(bytes.data(), pos, 36);
    std::memcpy(bytes.data() + 36, indices.data(), 2 * indices.size());
    const std::string uri =
        buffer_uri.empty() ? "data:application/octet-stream;base64," + test::base64(bytes) : buffer_uri;
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 10, "color": [1, 0.5, 0.25]}]}},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [
    {"name": "root", "translation": [0, 0, 1], "children": [1, 2, 3]},
    {"name": "tri", "mesh": 0, "scale": [2, 2, 2])" +
           node_extra + R"(},
    {"name": "cam", "camera": 0, "translation": [0, 0, 5]},
    {"name": "lamp", "translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"name": "glow", "emissiveFactor": [1, 1, 1],
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}},
                 "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}],
  "buffers": [{"byteLength": 44, "uri": ")" +
           uri + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ])" + extra_json +
           "\n}\n";
  }
};

std::filesystem::path write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("a minimal glTF loads with its hierarchy, camera, light and emissive material") {
  const auto dir = test::temp_dir("gltf_ok");
  const Scene scene = load_gltf(write(dir, "tri.gltf", TriangleGltf{}.json()));
  REQUIRE(scene.meshes.size() == 1);
  REQUIRE(scene.instances.size() == 1);
  CHECK(scene.triangle_count() == 1);
  // Node transform: parent translation (0,0,1) · child scale 2.
  const Vec3d p = scene.instances[0].to_world.point({1, 0, 0});
  CHECK(p.x == Approx(2));
  CHECK(p.z == Approx(1));
  REQUIRE(scene.cameras.size() == 1);
  CHECK(scene.cameras[0].yfov == Approx(0.7f));
  CHECK(*scene.cameras[0].aspect == Approx(1.5f));
  REQUIRE(scene.point_lights.size() == 1);
  CHECK(scene.point_lights[0].position.y == Approx(2));
  CHECK(scene.point_lights[0].position.z == Approx(1));
  REQUIRE(scene.materials.size() == 1);
  REQUIRE(scene.materials[0].emission.has_value());
  CHECK(spectrum_to_xyz(*scene.materials[0].emission).y == Approx(5).epsilon(0.01));  // strength 5 × white
  const SceneFeatures f = analyze_features(scene);
  CHECK(f.emissive_triangles);
  CHECK(f.point_lights);
  CHECK_FALSE(f.environment);
}

TEST_CASE("primitives without position data are skipped, as raybench skips them") {
  // A compressed primitive (no POSITION data) before a plain one: only the plain one becomes a
  // mesh, so triangle ids stay those of raybench's global numbering.
  std::string json = TriangleGltf{}.json();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = json.find(from);
    REQUIRE(at != std::string::npos);
    json.replace(at, from.size(), to);
  };
  replace(R"("primitives": [)", R"("primitives": [{"attributes": {"POSITION": 2}, "indices": 1}, )");
  replace(R"("type": "SCALAR"})", R"("type": "SCALAR"}, {"componentType": 5126, "count": 3, "type": "VEC3"})");
  log::set_level(log::Level::quiet);
  const Scene scene = load_gltf(write(test::temp_dir("gltf_nodata"), "nodata.gltf", json));
  log::set_level(log::Level::info);
  REQUIRE(scene.meshes.size() == 1);
  CHECK(scene.meshes[0].positions[1] == Vec3f(1, 0, 0));
  CHECK(scene.triangle_count() == 1);
}

TEST_CASE("malformed glTF files fail with a message naming the file and the problem") {
  const auto dir = test::temp_dir("gltf_bad");
  const std::string good = TriangleGltf{}.json();

  const auto truncated = write(dir, "truncated.gltf", good.substr(0, good.size() / 2));
  CHECK_THROWS_WITH(load_gltf(truncated), Catch::Contains("truncated.gltf") && Catch::Contains("not a valid glTF"));

  TriangleGltf bad_index;
  bad_index.indices = {0, 1, 7};
  const auto out_of_range = write(dir, "index.gltf", bad_index.json());
  CHECK_THROWS_WITH(load_gltf(out_of_range), Catch::Contains("index.gltf") && Catch::Contains("index 7 out of range"));

  TriangleGltf missing;
  missing.buffer_uri = "missing.bin";
  const auto missing_buffer = write(dir, "missing.gltf", missing.json());
  CHECK_THROWS_WITH(load_gltf(missing_buffer), Catch::Contains("missing.gltf") && Catch::Contains("missing.bin"));

  TriangleGltf required;
  required.extra_json = R"(, "extensionsRequired": ["EXT_lights_image_based"])";
  CHECK_THROWS_WITH(load_gltf(write(dir, "ibl.gltf", required.json())),
                    Catch::Contains("requires extension EXT_lights_image_based"));
  // A compression Prism lacks leaves the index accessor without data, which the parser rejects;
  // the message names the extension, not the accessor.
  std::string compressed = required.json();
  compressed.replace(compressed.find(R"({"bufferView": 1, )"), 18, "{");
  compressed.replace(compressed.find("EXT_lights_image_based"), 22, "EXT_future_compression");
  CHECK_THROWS_WITH(load_gltf(write(dir, "future.gltf", compressed)),
                    Catch::Contains("requires extension EXT_future_compression") && !Catch::Contains("accessor"));

  TriangleGltf bad_mesh;
  bad_mesh.node_extra = R"(, "children": [9])";
  CHECK_THROWS_WITH(load_gltf(write(dir, "child.gltf", bad_mesh.json())), Catch::Contains("node 9"));

  TriangleGltf cycle;
  cycle.node_extra = R"(, "children": [0])";
  CHECK_THROWS_WITH(load_gltf(write(dir, "cycle.gltf", cycle.json())), Catch::Contains("cycle"));

  CHECK_THROWS_WITH(load_gltf(dir / "absent.gltf"), Catch::Contains("absent.gltf") && Catch::Contains("no such file"));
  CHECK_THROWS_AS(load_gltf(write(dir, "empty.glb", "glTF")), Error);
}

TEST_CASE("prism render exits non-zero on a malformed file and writes no output") {
  const auto dir = test::temp_dir("gltf_cli");
  TriangleGltf bad;
  bad.indices = {0, 1, 9};
  const auto scene = write(dir, "bad.gltf", bad.json());
  const auto out = dir / "out.exr";
  std::string err;
  const int code = test::run_prism("render \"" + scene.string() + "\" -o \"" + out.string() + "\" --spp 1", &err);
  CHECK(code != 0);
  CHECK(err.find("bad.gltf") != std::string::npos);
  CHECK(err.find("out of range") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
  CHECK(std::filesystem::is_empty(dir) == false);  // only the scene file is there
  for (const auto& entry : std::filesystem::directory_iterator(dir)) CHECK(entry.path().filename() == "bad.gltf");

  // Bad options fail before any work, too.
  CHECK(test::run_prism("render \"" + scene.string() + "\" -o \"" + out.string() + "\" --colorspace nonsense") != 0);
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("the default scene loads: a closed Cornell box with a light and a camera") {
  const Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/cornell.gltf");
  CHECK(scene.cameras.size() == 1);
  const SceneFeatures f = analyze_features(scene);
  CHECK(f.emissive_triangles);
  CHECK(scene.triangle_count() >= 30);
}

TEST_CASE("every shared glTF asset loads", "[shared]") {
  log::set_level(log::Level::quiet);
  for (const auto& file : test::shared_gltf_assets()) {
    INFO(file.string());
    CHECK(load_gltf(file).triangle_count() > 0);
  }
  log::set_level(log::Level::info);
}

TEST_CASE("glTF materials map to Prism's optics: transmission, ior, dispersion, volume, specular, metals, extras") {
  const auto dir = test::temp_dir("gltf_materials");
  TriangleGltf base;
  const auto with_material = [&](const std::string& material_json) {
    std::string json = base.json();
    const auto start = json.find("\"materials\": [");
    const auto end = json.find("],\n  \"buffers\"");
    json.replace(start, end - start + 1, "\"materials\": [" + material_json + "]");
    return load_gltf(write(dir, "m.gltf", json));
  };
  // Transmission with IOR, dispersion and an absorbing volume: a closed dispersive dielectric.
  Scene s = with_material(R"({"pbrMetallicRoughness": {"metallicFactor": 0},
      "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
      "KHR_materials_ior": {"ior": 1.6}, "KHR_materials_dispersion": {"dispersion": 0.5},
      "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2, "attenuationColor": [0.5, 0.5, 0.5]}}})");
  const auto* d = s.materials[0].dielectric();
  REQUIRE(d);
  CHECK_FALSE(d->thin_walled);
  CHECK(d->dispersive);
  CHECK(ior(d->ior, 587.56f) == Approx(1.6).margin(1e-4));
  CHECK(abbe_number(d->ior) == Approx(40).epsilon(5e-3));  // V_d = 20 / dispersion
  REQUIRE(d->interior.sigma_a);
  CHECK(evaluate(*d->interior.sigma_a, 550) == Approx(std::log(2.0) / 2).epsilon(1e-3));  // −ln(0.5) / 2
  // The colour is upsampled as the transmittance over attenuationDistance (see the slab render test).
  const auto* sigma = std::get_if<RgbAbsorptionSpectrum>(&*d->interior.sigma_a);
  REQUIRE(sigma);
  CHECK(sigma->inv_distance == Approx(0.5f));
  const SceneFeatures f = analyze_features(s);
  CHECK(f.dispersion);
  CHECK(f.absorption);

  // Transmission without a volume is a thin wall; without dispersion the index is constant.
  s = with_material(R"({"pbrMetallicRoughness": {"metallicFactor": 0},
      "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}})");
  REQUIRE(s.materials[0].dielectric());
  CHECK(s.materials[0].dielectric()->thin_walled);
  CHECK_FALSE(s.materials[0].dielectric()->dispersive);
  CHECK(ior(s.materials[0].dielectric()->ior, 400) == Approx(1.5));

  // metallic = 1: a conductor coloured by baseColor; extras name a measured metal or glass.
  s = with_material(R"({"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.5, 1], "metallicFactor": 1,
      "roughnessFactor": 0.3}})");
  const auto& metal = std::get<PbrMaterial>(s.materials[0].kind);
  CHECK(metal.metallic == 1);
  CHECK(metal.roughness == Approx(0.3f));
  CHECK_FALSE(metal.metal);
  CHECK(metal.base_color.g == Approx(0.6f));
  CHECK_FALSE(s.materials[0].dielectric());  // opaque
  s = with_material(R"({"extras": {"prism": {"metal": "Au"}}})");
  REQUIRE(std::get<PbrMaterial>(s.materials[0].kind).metal);
  CHECK(std::get<PbrMaterial>(s.materials[0].kind).metal->catalogue == "Au");
  CHECK(analyze_features(s).measured_metals);
  s = with_material(R"({"extras": {"prism": {"glass": "N-BK7"}}})");
  REQUIRE(s.materials[0].dielectric());
  CHECK(ior(s.materials[0].dielectric()->ior, 587.56f) == Approx(1.5168).margin(1e-4));

  // KHR_materials_specular scales the dielectric's reflectance; defaults follow glTF.
  s = with_material(R"({"pbrMetallicRoughness": {"metallicFactor": 0},
      "extensions": {"KHR_materials_specular": {"specularFactor": 0.25}}})");
  CHECK(std::get<PbrMaterial>(s.materials[0].kind).specular == Approx(0.25f));
  CHECK(std::get<PbrMaterial>(s.materials[0].kind).transmission == 0);

  // The layer extensions: clearcoat, sheen, iridescence, diffuse transmission, specular colour.
  s = with_material(R"({"extensions": {
      "KHR_materials_specular": {"specularColorFactor": [2, 1, 0.5]},
      "KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.1},
      "KHR_materials_sheen": {"sheenColorFactor": [0.2, 0.3, 0.4], "sheenRoughnessFactor": 0.6},
      "KHR_materials_iridescence": {"iridescenceFactor": 0.9, "iridescenceIor": 1.4, "iridescenceThicknessMaximum": 500},
      "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.3,
                                             "diffuseTransmissionColorFactor": [1, 0.5, 0.25]}}})");
  {
    const auto& p = std::get<PbrMaterial>(s.materials[0].kind);
    CHECK(p.specular_color == Rgb{2, 1, 0.5f});
    REQUIRE(p.clearcoat);
    CHECK(p.clearcoat->factor == Approx(0.8f));
    CHECK(p.clearcoat->roughness == Approx(0.1f));
    REQUIRE(p.sheen);
    CHECK(p.sheen->color == Rgb{0.2f, 0.3f, 0.4f});
    CHECK(p.sheen->roughness == Approx(0.6f));
    REQUIRE(p.iridescence);
    CHECK(p.iridescence->ior == Approx(1.4f));
    CHECK(p.inputs({}).iridescence_thickness == Approx(500));  // no texture: the maximum
    REQUIRE(p.diffuse_transmission);
    CHECK(p.diffuse_transmission->color == Rgb{1, 0.5f, 0.25f});
    CHECK(analyze_features(s).layers);
  }
  // Zero factors leave the layers out.
  s = with_material(R"({"extensions": {"KHR_materials_clearcoat": {}, "KHR_materials_sheen": {},
      "KHR_materials_iridescence": {}, "KHR_materials_diffuse_transmission": {}}})");
  CHECK_FALSE(analyze_features(s).layers);
  // A specular colour from its texture alone (factor 1) is a layer too: make_bsdf builds it layered.
  PbrMaterial& p = std::get<PbrMaterial>(s.materials[0].kind);
  CHECK_FALSE(analyze_features(s).textures);
  p.specular_color_texture = Texture{};
  CHECK(analyze_features(s).layers);
  // A layer's texture is one of the scene's textures too.
  p.specular_color_texture.reset();
  p.sheen.emplace();
  p.sheen->color_texture = Texture{};
  CHECK(analyze_features(s).textures);

  // Errors name the problem.
  CHECK_THROWS_WITH(with_material(R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 2]}}})"),
                    Catch::Contains("sheenColorFactor"));
  CHECK_THROWS_WITH(with_material(R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2}}})"),
                    Catch::Contains("clearcoatFactor"));
  CHECK_THROWS_WITH(with_material(R"({"extras": {"prism": {"metal": "Mithril"}}})"), Catch::Contains("Mithril"));
  CHECK_THROWS_WITH(with_material(R"({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
      "KHR_materials_ior": {"ior": 0.5}}})"),
                    Catch::Contains("ior"));
}

TEST_CASE("KHR_lights_punctual spot and directional lights load with their cones and node orientation") {
  const auto dir = test::temp_dir("gltf_lights");
  // A spot turned from −Z to −Y (−90° about X), a sun turned 45° about Y under a scaled parent,
  // a spot with the default cone that sets `range` twice, and a rejected cone.
  const auto gltf = [&](const std::string& cone) {
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "intensity": 5, "spot": )" +
           cone + R"(},
    {"type": "directional", "intensity": 3, "color": [1, 0.5, 0.25]},
    {"type": "spot", "intensity": 2, "range": 10, "spot": {}},
    {"type": "point", "range": 3}
  ]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 3, 4]}],
  "nodes": [
    {"translation": [1, 2, 3], "rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"scale": [2, 2, 2], "children": [2]},
    {"rotation": [0, 0.38268343, 0, 0.92387953], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"extensions": {"KHR_lights_punctual": {"light": 3}}}
  ]
})";
  };
  log::set_level(log::Level::quiet);
  const Scene scene = load_gltf(write(dir, "lights.gltf", gltf(R"({"innerConeAngle": 0.2, "outerConeAngle": 0.6})")));
  log::set_level(log::Level::info);
  REQUIRE(scene.spot_lights.size() == 2);
  const SpotLight& spot = scene.spot_lights[0];
  CHECK(spot.position.x == Approx(1));
  CHECK(spot.position.y == Approx(2));
  CHECK(spot.position.z == Approx(3));
  CHECK(spot.direction.x == Approx(0).margin(1e-6));
  CHECK(spot.direction.y == Approx(-1));
  CHECK(spot.direction.z == Approx(0).margin(1e-6));
  CHECK(spot.inner_angle == Approx(0.2f));
  CHECK(spot.outer_angle == Approx(0.6f));
  CHECK(spectrum_to_xyz(spot.intensity).y == Approx(5).epsilon(0.01));  // candela
  const SpotLight& default_spot = scene.spot_lights[1];
  CHECK(default_spot.inner_angle == 0);
  CHECK(default_spot.outer_angle == Approx(kPi / 4));
  CHECK(default_spot.direction.z == Approx(-1));

  REQUIRE(scene.directional_lights.size() == 1);
  const DirectionalLight& sun = scene.directional_lights[0];
  CHECK(sun.direction.x == Approx(-std::sqrt(0.5)));  // −Z turned 45° about +Y, unit despite the scale
  CHECK(sun.direction.y == Approx(0).margin(1e-6));
  CHECK(sun.direction.z == Approx(-std::sqrt(0.5)));
  // Lux × the colour's luminance (Rec.709: 0.2126 R + 0.7152 G + 0.0722 B).
  CHECK(spectrum_to_xyz(sun.illuminance).y == Approx(3 * (0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25)).epsilon(0.01));
  const SceneFeatures f = analyze_features(scene);
  CHECK(f.spot_lights);
  CHECK(f.directional_lights);
  CHECK(f.point_lights);

  CHECK_THROWS_WITH(load_gltf(write(dir, "cone.gltf", gltf(R"({"innerConeAngle": 0.7, "outerConeAngle": 0.6})"))),
                    Catch::Contains("cone.gltf") && Catch::Contains("innerConeAngle"));

  // `range` is ignored, with one warning per file however many lights set it.
  std::string err;
  const auto lights = dir / "lights.gltf";
  REQUIRE(test::run_prism("render \"" + lights.string() + "\" -o \"" + (dir / "out.exr").string() +
                              "\" --spp 1 --width 4 --height 4 --quiet",
                          &err) == 0);
  size_t count = 0;
  for (size_t at = err.find("range is ignored"); at != std::string::npos; at = err.find("range is ignored", at + 1))
    ++count;
  CHECK(count == 1);
}
