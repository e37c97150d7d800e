// Surface features in renders: alpha MASK and BLEND, textures seen through the camera, vertex
// colours, normal maps that never leak light below the geometric surface.

#include <catch2/catch.hpp>

#include "core/scene/gltf_loader.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// A 2×1 texture: left texel (r,g,b,a0), right texel (r,g,b,a1).
Texture two_texels(std::array<uint8_t, 4> left, std::array<uint8_t, 4> right) {
  Texture t;
  std::vector<uint8_t> rgba(left.begin(), left.end());
  rgba.insert(rgba.end(), right.begin(), right.end());
  t.image = std::make_shared<Image>(2, 1, std::move(rgba));
  t.nearest = true;
  return t;
}

// A quad facing the camera, filling the image, in front of a uniform sky of radiance 1.
Scene quad_before_sky(Material m) {
  Scene scene;
  scene.materials.push_back(std::move(m));
  Mesh quad = test::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  quad.uv[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  test::add_mesh(scene, std::move(quad));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  return scene;
}

// A black surface: no diffuse, no specular reflection.
PbrMaterial black() {
  PbrMaterial p = PbrMaterial::plastic(Rgb{0, 0, 0}, 1);
  p.specular = 0;
  return p;
}

const CameraDesc kCamera = test::look_at({0, 0, 2}, {0, 0, 0}, 40.f);  // the quad fills the view

// A white Lambert floor (z = 0, 4 m wide) and, with `sheet`, a black BLEND sheet of alpha 0.3 a
// metre above it; no light yet. kUnderSheet looks down at the floor from between the two.
Scene floor_under_sheet(bool sheet) {
  Scene scene;
  PbrMaterial white = PbrMaterial::plastic(Rgb{1, 1, 1}, 1);
  white.specular = 0;
  scene.materials.push_back(Material{.name = "floor", .kind = white});
  test::add_mesh(scene, test::make_quad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 0));
  if (sheet) {
    PbrMaterial p = black();
    p.alpha = 0.3f;
    Material m{.name = "sheet", .kind = p};
    m.alpha_mode = AlphaMode::blend;
    scene.materials.push_back(std::move(m));
    test::add_mesh(scene, test::make_quad({-2, -2, 1}, {4, 0, 0}, {0, 4, 0}, 1));
  }
  return scene;
}
const CameraDesc kUnderSheet = test::look_at({0, 0, 0.5f}, {0, 0, 0}, 60.f);

// kUnderSheet's view of a lit scene at 1024 spp, 8×8, with light sampling (MIS) or BSDF sampling alone.
test::TestRender render_lit(const Scene& scene, bool next_event, uint64_t seed) {
  RenderOptions o;
  o.spp = 1024;
  o.seed = seed;
  o.progress = false;
  o.path.next_event = next_event;
  return test::render_rgb(scene, kUnderSheet, 8, 8, o);
}

// Light sampling and BSDF sampling alone render the same mean: the mean of the pixels' differences
// (green) is within 4 standard errors of 0, so the image's own structure cancels pixel by pixel;
// the standard error must be below max_error of the mean, for the check to be sharp.
void check_same_mean(const test::TestRender& mis, const test::TestRender& bsdf, double max_error = 0.01) {
  CHECK(mis.stats.invalid_samples == 0);
  double sum = 0, sum2 = 0, mean_bsdf = 0;
  const int n = int(bsdf.rgb.size() / 3);
  for (int i = 0; i < n; ++i) {
    const double d = mis.rgb[3 * i + 1] - bsdf.rgb[3 * i + 1];
    sum += d, sum2 += d * d, mean_bsdf += bsdf.rgb[3 * i + 1] / n;
  }
  const double diff = sum / n, error = std::sqrt((sum2 / n - diff * diff) / (n - 1));
  INFO("light sampling minus BSDF sampling alone: " << diff << " ± " << error << " of " << mean_bsdf);
  REQUIRE(mean_bsdf > 0);
  CHECK(error < max_error * mean_bsdf);
  CHECK(std::abs(diff) < 4 * error);
}

}  // namespace

TEST_CASE("alpha MASK cuts surfaces away where the texture's alpha is below the cutoff") {
  PbrMaterial p = black();
  p.base_color_texture = two_texels({255, 255, 255, 0}, {255, 255, 255, 255});
  Material m{.name = "mask", .kind = p};
  m.alpha_mode = AlphaMode::mask;
  const auto img = test::render_rgb(quad_before_sky(m), kCamera, 16, 16, 16);
  CHECK(img.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    CHECK(img.mean(c, 0, 0, 7, 16) == Approx(1).margin(0.02));   // cut away: the sky shows
    CHECK(img.mean(c, 9, 0, 16, 16) == Approx(0).margin(1e-6));  // kept: black
  }
  // Opaque mode ignores alpha.
  m.alpha_mode = AlphaMode::opaque;
  const auto opaque = test::render_rgb(quad_before_sky(m), kCamera, 16, 16, 4);
  for (int c = 0; c < 3; ++c) CHECK(opaque.mean(c) == Approx(0).margin(1e-6));
}

TEST_CASE("a camera ray that leaves at once sees the constant sky's exact mean, the same in every sample") {
  // The renderer's sky_xyz: no wavelength noise where the sky is seen straight (the quad cut away);
  // through a clear BLEND sheet (alpha 0) the path carries wavelengths, whose estimate has that mean.
  PbrMaterial p = black();
  p.alpha = 0;
  Material hole{.name = "hole", .kind = p};
  hole.alpha_mode = AlphaMode::mask;
  const Xyz xyz = sampled_xyz_mean(*quad_before_sky(hole).environment);
  float exact[3] = {xyz.x, xyz.y, xyz.z};
  ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, exact, 1);
  const auto straight = test::render_rgb(quad_before_sky(hole), kCamera, 8, 8, 4);
  for (size_t i = 0; i < straight.rgb.size(); ++i) CHECK(straight.rgb[i] == Approx(exact[i % 3]).epsilon(1e-6));
  CHECK(straight.stats.rays.primary == straight.stats.samples);  // one camera ray each, counted
  hole.alpha_mode = AlphaMode::blend;
  const auto through = test::render_rgb(quad_before_sky(hole), kCamera, 8, 8, 64);
  for (int c = 0; c < 3; ++c) CHECK(through.mean(c) == Approx(exact[c]).epsilon(1e-3));
}

TEST_CASE("alpha BLEND lets the sky through in proportion to 1 - alpha") {
  PbrMaterial p = black();
  p.alpha = 0.3f;
  Material m{.name = "blend", .kind = p};
  m.alpha_mode = AlphaMode::blend;
  const auto img = test::render_rgb(quad_before_sky(m), kCamera, 16, 16, 1024);
  test::check_mean(img, 0, 0, 16, 16, 0.7, 0.02);
}

TEST_CASE("alpha BLEND over a grey Lambertian: every sample carries the mean, past the last bounce too") {
  // The path passes a BLEND surface or stays on it with probabilities in proportion to the two
  // shares' throughputs at its BSDF sample: 1 − α = 0.7 and α f cos / pdf = 0.3 × 0.5. Under a
  // uniform sky, with BSDF sampling alone, both ways then carry 0.7 + 0.3 × 0.5 = 0.85 of the sky:
  // every pixel is 0.85 of the open sky's at 4 spp. (Choosing the surface with probability α
  // gave each sample 1 or 0.5 of it by chance.) At max depth 0 the sheet is a hole 0.7 of the time.
  PbrMaterial p = PbrMaterial::plastic(Rgb{0.5f, 0.5f, 0.5f}, 1);
  p.specular = 0;  // pure Lambert: f cos / pdf = 0.5 for every cosine-weighted sample
  p.alpha = 0.3f;
  Material m{.name = "blend", .kind = p};
  m.alpha_mode = AlphaMode::blend;
  const auto render = [&](const Material& material, int max_depth) {
    RenderOptions o;
    o.spp = 4;
    o.seed = 3;
    o.path.max_depth = max_depth;
    o.path.next_event = false;
    o.progress = false;
    return test::render_rgb(quad_before_sky(material), kCamera, 12, 12, o);
  };
  // The sky alone, through a clear sheet (alpha 0, passed at once): seen straight from the camera it
  // would be its exact mean (the renderer's sky_xyz), without the wavelengths' noise that the sheet's
  // render carries, sample for sample, like this one.
  Material hole = m;
  std::get<PbrMaterial>(hole.kind).alpha = 0;
  const auto sky = render(hole, 4), sheet = render(m, 4);
  CHECK(sheet.stats.invalid_samples == 0);
  for (size_t i = 0; i < sky.rgb.size(); ++i) {
    INFO("value " << i << ": " << sheet.rgb[i] << " through the sheet, " << sky.rgb[i] << " without");
    REQUIRE(sky.rgb[i] > 0);
    CHECK(sheet.rgb[i] == Approx(0.85 * sky.rgb[i]).epsilon(1e-4));
  }
  RenderOptions o;
  o.spp = 1024;
  o.path.max_depth = 0;
  o.progress = false;
  test::check_mean(test::render_rgb(quad_before_sky(m), kCamera, 8, 8, o), 0, 0, 8, 8, 0.7, 0.02);
}

TEST_CASE("alpha BLEND over a glossy surface is 1 - alpha of the sky plus alpha of the opaque surface") {
  // Unbiasedness where the BSDF sample's weight varies (a rough specular plastic, its light sampled):
  // the BLEND render's mean is 0.7 × the sky's (1) + 0.3 × the opaque surface's, from its own render.
  PbrMaterial p = PbrMaterial::plastic(Rgb{0.2f, 0.5f, 0.8f}, 0.4f);
  p.alpha = 0.3f;
  Material m{.name = "glossy", .kind = p};
  RenderOptions o;
  o.spp = 64;
  o.seed = 5;
  o.progress = false;
  const auto opaque = test::render_rgb(quad_before_sky(m), kCamera, 16, 16, o);
  m.alpha_mode = AlphaMode::blend;
  o.seed = 6;
  const auto blend = test::render_rgb(quad_before_sky(m), kCamera, 16, 16, o);
  CHECK(blend.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.7 + 0.3 * opaque.mean(c, 0, 0, 16, 16);
    const double error =
        std::hypot(blend.standard_error(c, 0, 0, 16, 16), 0.3 * opaque.standard_error(c, 0, 0, 16, 16));
    INFO("channel " << c << ": " << blend.mean(c, 0, 0, 16, 16) << " vs " << expected << " ± " << error);
    CHECK(error < 0.004);
    CHECK(blend.mean(c, 0, 0, 16, 16) == Approx(expected).margin(4 * error));
  }
}

TEST_CASE("alpha BLEND keeps its share of light sampling where the BSDF sample fails") {
  // A rough metal floor seen at a grazing angle, lit only by a sun (reached by light sampling
  // alone) under a black sky: many of its BSDF samples leave below the surface. Whatever the
  // sample, the BLEND floor must show alpha = 0.3 of the opaque floor's light (it showed 0.26 of
  // it, 15 standard errors short, when a failed sample always passed through).
  PbrMaterial p = PbrMaterial::metal_of(Rgb{0.9f, 0.9f, 0.9f}, 1);
  p.alpha = 0.3f;
  Material m{.name = "metal", .kind = p};
  const auto render = [&](AlphaMode mode, uint64_t seed) {
    Scene scene;
    Material material = m;
    material.alpha_mode = mode;
    scene.materials.push_back(std::move(material));
    test::add_mesh(scene, test::make_quad({-20, -20, 0}, {40, 0, 0}, {0, 40, 0}, 0));
    scene.directional_lights.push_back({"sun", normalize(Vec3f(0, -1, -0.3f)), RgbIlluminantSpectrum(Rgb{1, 1, 1})});
    RenderOptions o;
    o.spp = 64;
    o.seed = seed;
    o.progress = false;
    return test::render_rgb(scene, test::look_at({0, -3, 0.5f}, {0, 0, 0}, 10.f), 16, 16, o);
  };
  const auto opaque = render(AlphaMode::opaque, 7), blend = render(AlphaMode::blend, 8);
  CHECK(blend.stats.invalid_samples == 0);
  const double expected = 0.3 * opaque.mean(1, 0, 0, 16, 16);
  const double error = std::hypot(blend.standard_error(1, 0, 0, 16, 16), 0.3 * opaque.standard_error(1, 0, 0, 16, 16));
  INFO(blend.mean(1, 0, 0, 16, 16) << " vs " << expected << " ± " << error);
  REQUIRE(expected > 0);
  CHECK(error < 0.03 * expected);
  CHECK(blend.mean(1, 0, 0, 16, 16) == Approx(expected).margin(4 * error));
}

TEST_CASE("an area light seen through an alpha BLEND sheet: light sampling and BSDF sampling agree") {
  // A white floor lit by an emissive quad above a black BLEND sheet (alpha 0.3). A BSDF
  // sample that passes the sheet and reaches the light is weighed by MIS against light sampling,
  // whose solid-angle pdf depends on the distance from the floor: measured from the sheet instead,
  // the weights summed to more than 1. With MIS the mean must equal BSDF sampling's alone.
  const auto render = [](bool next_event, uint64_t seed) {
    Scene scene = floor_under_sheet(true);
    Material lamp = test::diffuse({0, 0, 0}, "lamp");
    lamp.emission = RgbIlluminantSpectrum(Rgb{4, 4, 4});
    scene.materials.push_back(std::move(lamp));
    test::add_mesh(scene, test::make_quad({-0.75f, 0.75f, 2}, {1.5f, 0, 0}, {0, -1.5f, 0}, 2));  // faces down
    return render_lit(scene, next_event, seed);
  };
  check_same_mean(render(true, 3), render(false, 4));
}

namespace {

// A white floor under a downward-facing emissive quad of material p in alpha mode `mode`, with the
// vertex alphas given, rendered by `integrator` (with light sampling or not).
test::TestRender render_under_lamp(PbrMaterial p, AlphaMode mode, std::array<float, 4> vertex_alpha,
                                   IntegratorKind integrator, bool next_event, uint64_t seed) {
  Scene scene = floor_under_sheet(false);
  Material lamp{.name = "lamp", .kind = p};
  lamp.alpha_mode = mode;
  lamp.emission = RgbIlluminantSpectrum(Rgb{4, 4, 4});
  scene.materials.push_back(std::move(lamp));
  test::add_mesh(scene, test::make_quad({-0.75f, 0.75f, 2}, {1.5f, 0, 0}, {0, -1.5f, 0}, 1));  // faces down
  for (float a : vertex_alpha) scene.meshes.back().colors.push_back({1, 1, 1, a});
  RenderOptions o;
  o.spp = 1024;
  o.seed = seed;
  o.progress = false;
  o.integrator = integrator;
  o.path.next_event = next_event;
  return test::render_rgb(scene, kUnderSheet, 8, 8, o);
}

}  // namespace

TEST_CASE("an emissive alpha BLEND surface emits alpha of its light, sampled or hit, in every integrator") {
  // The lamp's alpha is 0.6 × a vertex colour's 0.5: a path that hits it counts 0.3 of its
  // radiance, so light sampling must too (it counted all of it: light sampling's mean was 3.3x
  // BSDF sampling's alone). BDPT and the light tracer get their emission from the same light.
  PbrMaterial p = black();
  p.alpha = 0.6f;
  const auto render = [&](IntegratorKind integrator, bool next_event, uint64_t seed) {
    return render_under_lamp(p, AlphaMode::blend, {0.5f, 0.5f, 0.5f, 0.5f}, integrator, next_event, seed);
  };
  const auto bsdf = render(IntegratorKind::path, false, 4);
  check_same_mean(render(IntegratorKind::path, true, 3), bsdf);
  check_same_mean(render(IntegratorKind::bdpt, true, 5), bsdf);
  check_same_mean(render(IntegratorKind::light, true, 6), bsdf, 0.03);  // noisier: light paths reach the camera
}

TEST_CASE("an emissive alpha MASK surface emits only where it is not cut away, sampled or hit") {
  // Vertex alphas 0, 0, 1, 1 across the lamp against the cutoff 0.5: half of it is cut away, and a
  // path meets only the other half, so light sampling must find only that half's light.
  const auto render = [](IntegratorKind integrator, bool next_event, uint64_t seed) {
    return render_under_lamp(black(), AlphaMode::mask, {0, 0, 1, 1}, integrator, next_event, seed);
  };
  const auto bsdf = render(IntegratorKind::path, false, 4);
  check_same_mean(render(IntegratorKind::path, true, 3), bsdf);
  check_same_mean(render(IntegratorKind::bdpt, true, 5), bsdf);
}

TEST_CASE("light sampled through an alpha BLEND sheet arrives scaled by 1 - alpha, at every sample") {
  // A white Lambert floor lit by a point light through a black BLEND sheet of alpha 0.3, seen by a
  // camera under the sheet: only light sampling reaches a point light, and a shadow ray carries the
  // sheet's transmittance, so every pixel is 0.7 of the floor's without the sheet, not 0 or 1 of it
  // by chance. (Paths that bounce up meet the black sheet or the black sky: nothing more.)
  const auto render = [](bool sheet) {
    Scene scene = floor_under_sheet(sheet);
    scene.point_lights.push_back({"lamp", {0.2f, 0.1f, 2.f}, RgbIlluminantSpectrum(Rgb{1, 1, 1})});
    return test::render_rgb(scene, kUnderSheet, 12, 12, 4);
  };
  const auto open = render(false), through = render(true);
  CHECK(through.stats.invalid_samples == 0);
  for (size_t i = 0; i < open.rgb.size(); ++i) {
    INFO("value " << i << ": " << through.rgb[i] << " through the sheet, " << open.rgb[i] << " without");
    REQUIRE(open.rgb[i] > 0);
    CHECK(through.rgb[i] == Approx(0.7 * open.rgb[i]).epsilon(1e-4));
  }
}

TEST_CASE("a textured, vertex-coloured diffuse surface shows texture x factor x vertex colour") {
  PbrMaterial p = PbrMaterial::plastic(Rgb{1, 0.5f, 1}, 1);
  p.specular = 0;  // pure Lambert, so the answer is the albedo
  p.base_color_texture = two_texels({255, 255, 255, 255}, {128, 128, 128, 255});
  Scene scene = quad_before_sky(Material{.name = "tex", .kind = p});
  scene.meshes[0].colors.assign(4, {1, 1, 0.5f, 1});
  // Lit by the sky alone from the front; a closed box is not needed: E = π (uniform sky, hemisphere).
  const auto img = test::render_rgb(scene, kCamera, 16, 16, 256);
  const float right = srgb_to_linear(128);
  CHECK(img.mean(0, 0, 0, 7, 16) == Approx(1.0).margin(0.02));
  CHECK(img.mean(1, 0, 0, 7, 16) == Approx(0.5).margin(0.02));
  CHECK(img.mean(2, 0, 0, 7, 16) == Approx(0.5).margin(0.02));
  CHECK(img.mean(0, 9, 0, 16, 16) == Approx(right).margin(0.02));
  CHECK(img.mean(1, 9, 0, 16, 16) == Approx(0.5 * right).margin(0.02));
}

TEST_CASE("a normal map tilts the shading normal but never shades below the geometric surface") {
  // A normal map tilting every normal by 60°: a white Lambert plane under a uniform sky still
  // reflects at most what it receives, and never NaN.
  PbrMaterial p = PbrMaterial::plastic(Rgb{1, 1, 1}, 1);
  p.specular = 0;
  Material m{.name = "bumpy", .kind = p};
  const uint8_t x = uint8_t(std::lround((std::sin(radians(60)) + 1) / 2 * 255));
  const uint8_t z = uint8_t(std::lround((std::cos(radians(60)) + 1) / 2 * 255));
  m.normal_texture = two_texels({x, 128, z, 255}, {x, 128, z, 255});
  Scene scene = quad_before_sky(m);
  generate_tangents(scene.meshes[0], 0);
  const auto img = test::render_rgb(scene, kCamera, 16, 16, 256);
  CHECK(img.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    CHECK(img.mean(c) <= 1.0 + 0.02);
    CHECK(img.mean(c) > 0.3);
  }
}

TEST_CASE("anisotropy 0 renders the isotropic material bit for bit; a strong one changes the image") {
  // A rough metal quad with UVs (so generated tangents exist) under a point light: strength 0 keeps
  // the isotropic shading frame and lobe, whatever the rotation.
  const auto render = [](float strength, float rotation) {
    PbrMaterial p = PbrMaterial::metal_of(Rgb{0.9f, 0.9f, 0.9f}, 0.4f);
    p.anisotropy_strength = strength;
    p.anisotropy_rotation = {std::cos(rotation), std::sin(rotation)};
    Scene scene;
    scene.materials.push_back(Material{.name = "brushed", .kind = p});
    Mesh quad = test::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
    quad.uv[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    generate_tangents(quad, 0);
    test::add_mesh(scene, std::move(quad));
    scene.point_lights.push_back({"lamp", {0.3f, 0.2f, 1.f}, RgbIlluminantSpectrum(Rgb{1, 1, 1})});
    scene.environment = RgbIlluminantSpectrum(Rgb{0.2f, 0.2f, 0.2f});
    return test::render_rgb(scene, kCamera, 24, 24, 4);
  };
  const auto isotropic = render(0, 0);
  CHECK(render(0, 1.3f).rgb == isotropic.rgb);
  const auto brushed = render(0.9f, 0), turned = render(0.9f, kPi / 2);
  CHECK(brushed.stats.invalid_samples == 0);
  CHECK(brushed.rgb != isotropic.rgb);
  CHECK(brushed.rgb != turned.rgb);
}

TEST_CASE("the Khronos anisotropy assets load without warnings and render with zero invalid samples", "[shared]") {
  const auto root = test::shared_dir() / "assets" / "gltf";
  if (!test::shared_assets_present("assets/gltf")) return;
  for (const char* name : {"AnisotropyStrengthTest", "AnisotropyRotationTest"}) {
    const auto file = root / name / "glTF-Binary" / (std::string(name) + ".glb");
    INFO(file.string());
    std::string err;
    const auto exr = test::temp_dir("anisotropy_assets") / "out.exr";
    CHECK(test::run_prism("render \"" + file.string() + "\" -o \"" + exr.string() + "\" --spp 1 --width 16", &err) ==
          0);
    CHECK(err.find("ignoring") == std::string::npos);
    Scene scene = load_gltf(file);
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const CameraDesc camera = scene.cameras.empty() ? framing_camera(scene.world_bounds(), 1.f) : scene.cameras[0];
    const auto img = test::render_rgb(scene, camera, 32, 32, 4, 8);
    CHECK(img.stats.invalid_samples == 0);
    CHECK(img.mean(1) > 0);
  }
}
