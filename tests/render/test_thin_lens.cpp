// Depth of field (camera.h, ThinLens) against the thin-lens model it claims: a point in the plane
// in focus is imaged to a point, one at another depth to the aperture's shape scaled by
// r |s − d| / (s d) (round, or a regular polygon of `blades` sides), a lens of radius 0 is the
// pinhole bit for bit, and the bidirectional integrators, which see the scene through the lens from
// the light's side, agree with the path tracer.

#include <ImfDoubleAttribute.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/rng.h"
#include "core/render/camera.h"
#include "core/render/image_output.h"
#include "core/render/renderer.h"
#include "core/render/world.h"
#include "spectral/color_pipeline.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

constexpr int kSize = 128;
constexpr float kFov = 30.f;  // vertical, degrees

// A small square emitter facing the camera, `depth` in front of it on the view axis, and nothing
// else: the image is the aperture's blur of a point.
Scene point_scene(float depth, float side) {
  Scene scene;
  Material lamp = test::diffuse({0.f, 0.f, 0.f}, "lamp");
  lamp.emission = RgbIlluminantSpectrum(Rgb{1.f, 1.f, 1.f});
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-side / 2, -side / 2, -depth}, {side, 0, 0}, {0, side, 0}, 0));
  return scene;
}

std::vector<float> luminance_image(const World& world, const CameraDesc& desc, const ThinLens& lens, int spp,
                                   IntegratorKind integrator = IntegratorKind::path) {
  RenderOptions options;
  options.spp = spp;
  options.seed = 3;
  options.progress = false;
  options.integrator = integrator;
  const RenderResult r = render(world, Camera(desc, kSize, kSize, lens), options);
  const std::vector<float> xyz = r.state.film.xyz_image();
  std::vector<float> y(xyz.size() / 3);
  for (size_t i = 0; i < y.size(); ++i) y[i] = xyz[3 * i + 1];
  return y;
}

struct Spread {
  double total, cx, cy, r2;  // the image's sum, centroid and mean squared distance from it [pixels]
};

Spread spread(const std::vector<float>& y) {
  Spread s{0, 0, 0, 0};
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      const double v = y[size_t(py) * kSize + px];
      s.total += v, s.cx += v * (px + 0.5), s.cy += v * (py + 0.5);
    }
  s.cx /= s.total, s.cy /= s.total;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      const double dx = px + 0.5 - s.cx, dy = py + 0.5 - s.cy;
      s.r2 += y[size_t(py) * kSize + px] * (dx * dx + dy * dy);
    }
  s.r2 /= s.total;
  return s;
}

}  // namespace

TEST_CASE("a point in the plane in focus is imaged to a point, whatever the aperture") {
  const CameraDesc desc = test::look_at({0, 0, 0}, {0, 0, -1}, kFov);
  const ThinLens lens{0.2f, 2.f, 0, 0.f};
  const Camera camera(desc, kSize, kSize, lens);
  // Every ray through a film position meets the plane in focus at one point, from anywhere on the lens.
  Rng rng(1, 0);
  for (int i = 0; i < 100; ++i) {
    const float x = kSize * rng.uniform(), y = kSize * rng.uniform();
    const Ray chief = camera.generate_ray(x, y, {0.5f, 0.5f});  // from the lens centre
    const Vec3f focus = chief.o + chief.d * (2.f / -chief.d.z);
    const Ray ray = camera.generate_ray(x, y, {rng.uniform(), rng.uniform()});
    const Vec3f at = ray.o + ray.d * ((2.f + ray.o.z) / -ray.d.z);
    CHECK(length(at - focus) < 1e-5f);
    // And the light's side sees it at that film position through any lens point.
    const auto c = camera.connect(focus, {rng.uniform(), rng.uniform()});
    REQUIRE(c);
    CHECK(std::abs(c->raster.x - x) < 1e-3f);
    CHECK(std::abs(c->raster.y - y) < 1e-3f);
  }
  // Rendered: a 1 cm square 2 m away, its image about a pixel wide, keeps its light in the four
  // pixels at the image's centre and their neighbours, where a pinhole keeps it.
  const Scene scene = point_scene(2.f, 0.01f);  // the world keeps pointers into it
  const World world(scene, {});
  const std::vector<float> y = luminance_image(world, desc, lens, 64);
  double total = 0, centre = 0;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      total += y[size_t(py) * kSize + px];
      if (std::abs(px + 0.5 - kSize / 2) < 2 && std::abs(py + 0.5 - kSize / 2) < 2)
        centre += y[size_t(py) * kSize + px];
    }
  REQUIRE(total > 0);
  CHECK(centre / total > 0.999);
}

TEST_CASE("a point off the plane in focus is blurred to the aperture's shape, of the thin-lens size") {
  const CameraDesc desc = test::look_at({0, 0, 0}, {0, 0, -1}, kFov);
  // (The square's image, 4 pixels wide, is a fair share of the blur's: the rays of a blurred pixel
  // that find a smaller one are too few to measure the blur by.)
  const float s = 2.f, d = 4.f, r = 0.2f, side = 0.07f;
  const Scene scene = point_scene(d, side);
  const World world(scene, {});
  // The blur's radius on the image plane at distance 1 is r |s − d| / (s d); one pixel there is
  // 2 tan(fov / 2) / size.
  const double pixel = 2 * std::tan(radians(kFov) / 2) / kSize;
  const double radius = r * std::abs(s - d) / (s * d) / pixel;
  const double square = side / d / pixel;  // the emitter's own image, a square of this side
  for (const int blades : {0, 6}) {
    INFO(blades << " blades");
    const std::vector<float> y = luminance_image(world, desc, ThinLens{r, s, blades, 0.3f}, 256);
    const Spread sp = spread(y);
    CHECK(std::abs(sp.cx - kSize / 2) < 0.3);
    CHECK(std::abs(sp.cy - kSize / 2) < 0.3);
    // Mean squared radius: the aperture's, (R²/6)(1 + 2 cos²(π/n)) for a regular n-gon of
    // circumradius R (R²/2 for the disk), plus the square's (side²/6) and the pixel's (1/6).
    const double shape = blades ? (1 + 2 * std::pow(std::cos(kPi / blades), 2)) / 6 : 0.5;
    const double measured = std::sqrt((sp.r2 - square * square / 6 - 1.0 / 6) / shape);
    CHECK(measured == Approx(radius).epsilon(0.05));
    CHECK(radius > 10);  // a blur of many pixels, so the test tells
  }
}

TEST_CASE("a lens of radius 0 is the pinhole, bit for bit") {
  const auto dir = test::temp_dir("thin_lens_pinhole");
  const std::string scene = "\"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" --width 24 --height 24 --spp 4";
  const auto a = dir / "pinhole.exr", b = dir / "radius0.exr", c = dir / "lens.exr";
  REQUIRE(test::run_prism("render " + scene + " -q -o \"" + a.string() + "\"") == 0);
  REQUIRE(test::run_prism("render " + scene + " --lens-radius 0 --focus-distance 1 -q -o \"" + b.string() + "\"") == 0);
  REQUIRE(test::run_prism("render " + scene + " --aperture 2 -q -o \"" + c.string() + "\"") == 0);
  const RgbImage pinhole = read_exr(a.string()), radius0 = read_exr(b.string()), lens = read_exr(c.string());
  CHECK(pinhole.rgb == radius0.rgb);
  CHECK(pinhole.rgb != lens.rgb);
}

TEST_CASE("with a lens, BDPT and VCM see the same image as the path tracer") {
  // A floor lit by a square lamp above it, seen at an angle: the near floor and the far floor are
  // out of focus, and BDPT reaches the camera from the floor through the lens.
  Scene scene;
  Material lamp = test::diffuse({0.f, 0.f, 0.f}, "lamp");
  lamp.emission = RgbIlluminantSpectrum(Rgb{4.f, 4.f, 4.f});
  scene.materials.push_back(lamp);
  scene.materials.push_back(test::diffuse({0.7f, 0.6f, 0.5f}, "floor"));
  test::add_mesh(scene, test::make_quad({-0.5f, 1.5f, -0.5f}, {1, 0, 0}, {0, 0, 1}, 0));  // faces down
  test::add_mesh(scene, test::make_quad({-3, 0, -3}, {0, 0, 6}, {6, 0, 0}, 1));
  const World world(scene, {});
  const CameraDesc desc = test::look_at({0, 1.2f, 3}, {0, 0, 0}, 50.f);
  const ThinLens lens{0.15f, 3.2f, 5, 0.f};
  const auto image = [&](IntegratorKind integrator, uint64_t seed) {
    RenderOptions options;
    options.spp = 32;
    options.seed = seed;
    options.progress = false;
    options.integrator = integrator;
    options.path.max_depth = 4;
    const RenderResult r = render(world, Camera(desc, 48, 36, lens), options);
    std::vector<float> rgb = r.state.film.xyz_image();
    ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, rgb.data(), rgb.size() / 3);
    return test::TestRender{r.width(), r.height(), std::move(rgb), r.stats()};
  };
  const test::TestRender path = image(IntegratorKind::path, 1);
  for (const IntegratorKind other : {IntegratorKind::bdpt, IntegratorKind::vcm}) {
    const test::TestRender o = image(other, 2);
    for (int channel = 0; channel < 3; ++channel) {
      const test::MeanDifference m = test::mean_difference(path, o, channel);
      INFO("integrator " << int(other) << ", channel " << channel << ": " << m.difference << " ± " << m.standard_error
                         << " of " << path.mean(channel));
      CHECK(std::abs(m.difference) < 4 * m.standard_error + 1e-4);
      CHECK(m.standard_error < 0.02 * path.mean(channel));
    }
  }
}

TEST_CASE("a camera's lens from an f-number, a focus node or a distance, and the mistakes refused") {
  Scene scene = point_scene(4.f, 0.1f);
  scene.source = "lens.gltf";
  scene.node_origins = {{"target", {0.3f, 0.2f, -3.f}}, {"behind", {0.f, 0.f, 2.f}}};
  CameraDesc desc = test::look_at({0, 0, 0}, {0, 0, -1}, 40.f);
  CHECK_FALSE(thin_lens(desc, scene, {300, 200}).radius > 0);  // nothing asked: a pinhole
  // f/2 on a 36 mm film: f = 18 mm / tan(fov_x / 2), r = f / 4, in metres.
  desc.lens.f_number = 2.f;
  const float tan_half_x = std::tan(radians(40.f) / 2) * 300 / 200;
  ThinLens lens = thin_lens(desc, scene, {300, 200});
  CHECK(lens.radius == Approx(0.018 / tan_half_x / 4).epsilon(1e-5));
  CHECK(lens.focus_distance == Approx(4.f));  // the scene's centre, on the axis
  desc.lens.sensor_width = 24.f;
  CHECK(thin_lens(desc, scene, {300, 200}).radius == Approx(0.012 / tan_half_x / 4).epsilon(1e-5));
  desc.lens.focus_node = "target";
  CHECK(thin_lens(desc, scene, {300, 200}).focus_distance == Approx(3.f));  // its depth, not its distance
  desc.lens.focus_node = "behind";
  CHECK_THROWS_WITH(thin_lens(desc, scene, {300, 200}),
                    Catch::Contains("lens.gltf") && Catch::Contains("'behind'") && Catch::Contains("not in front"));
  desc.lens.focus_node = "nowhere";
  CHECK_THROWS_WITH(thin_lens(desc, scene, {300, 200}), Catch::Contains("no node named 'nowhere'"));
  desc.lens.focus_node.reset();
  desc.lens.blades = 2;
  CHECK_THROWS_WITH(thin_lens(desc, scene, {300, 200}), Catch::Contains("2 blades"));
  desc.lens.blades = 7;
  CHECK(thin_lens(desc, scene, {300, 200}).blades == 7);
  desc.projection = CameraDesc::Projection::orthographic;
  CHECK_THROWS_WITH(thin_lens(desc, scene, {300, 200}), Catch::Contains("needs a perspective camera"));
}

TEST_CASE("a camera's extras give it a lens, and the command line's options override them") {
  const auto dir = test::temp_dir("thin_lens_extras");
  std::ifstream in(PRISM_SOURCE_DIR "/data/scenes/cornell.gltf");
  std::stringstream text;
  text << in.rdbuf();
  const std::string camera = R"("name": "camera",)";
  const auto with_extras = [&](const std::string& extras) {
    std::string json = text.str();
    const size_t at = json.find(camera, json.find(R"("cameras")"));  // the camera's, not its node's
    REQUIRE(at != std::string::npos);
    json.replace(at, camera.size(), camera + R"( "extras": {"prism": )" + extras + "},");
    const auto file = dir / "lens.gltf";
    std::ofstream(file) << json;
    return "render \"" + file.string() + "\" --width 16 --height 16 --spp 1 -o \"" + (dir / "out.exr").string() + "\"";
  };
  std::string err;
  REQUIRE(test::run_prism(with_extras(R"({"lens_radius": 0.05, "focus_distance": 0.8, "blades": 6})"), &err) == 0);
  CHECK_THAT(err, Catch::Contains("depth of field: lens radius 0.05, in focus at 0.8 along the view axis, 6 blades"));
  REQUIRE(test::run_prism(with_extras(R"({"lens_radius": 0.05})") + " --lens-radius 0.02 --focus-distance 1.5", &err) ==
          0);
  CHECK_THAT(err, Catch::Contains("lens radius 0.02, in focus at 1.5"));
  Imf::InputFile exr((dir / "out.exr").c_str());  // and the header records it
  const auto* radius = exr.header().findTypedAttribute<Imf::DoubleAttribute>("prism.lensRadius");
  const auto* focus = exr.header().findTypedAttribute<Imf::DoubleAttribute>("prism.focusDistance");
  REQUIRE(radius != nullptr);
  REQUIRE(focus != nullptr);
  CHECK(radius->value() == Approx(0.02));
  CHECK(focus->value() == Approx(1.5));
  // Bad values: one line naming the file, the camera and the key; no image.
  std::filesystem::remove(dir / "out.exr");
  CHECK(test::run_prism(with_extras(R"({"aperture": -2})"), &err) == 1);
  CHECK_THAT(err, Catch::Contains("lens.gltf") && Catch::Contains("camera 'camera'") &&
                      Catch::Contains("extras.prism.aperture must be a positive"));
  CHECK(test::run_prism(with_extras(R"({"aperture": 2, "focus_node": "nowhere"})"), &err) == 1);
  CHECK_THAT(err, Catch::Contains("no node named 'nowhere'"));
  CHECK_FALSE(std::filesystem::exists(dir / "out.exr"));
}
