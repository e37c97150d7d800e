// data/scenes/metamerism.gltf (make_metamerism.py): two paints whose reflectances differ by a
// metameric black for D65 match under D65 and part under illuminant A and F11, as rendered and
// as the colorimetry of their spectra says.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene/gltf_loader.h"
#include "core/scene/spectrum_input.h"
#include "spectral/cie.h"
#include "spectral/color_difference.h"
#include "spectral/named_spectra.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// The mean XYZ of an interleaved image over the pixels [x0, x1) × [y0, y1).
Xyz window_mean(const std::vector<float>& xyz, int width, int x0, int y0, int x1, int y1) {
  double s[3] = {0, 0, 0};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) s[c] += xyz[(size_t(y) * width + x) * 3 + c];
  const double n = double(x1 - x0) * (y1 - y0);
  return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}

// ∫ρ S {x̄, ȳ, z̄} / ∫S ȳ: the XYZ of a diffuse paint under a light of spectrum S.
Xyz paint_xyz(const Spectrum& rho, const Spectrum& s) {
  const CieTables& t = cie();
  double sum[3] = {0, 0, 0}, norm = 0;
  for (double l = kLambdaMin + 0.05; l < kLambdaMax; l += 0.1) {
    const double v = evaluate(s, float(l));
    sum[0] += evaluate(rho, float(l)) * v * t.x(float(l)), sum[1] += evaluate(rho, float(l)) * v * t.y(float(l));
    sum[2] += evaluate(rho, float(l)) * v * t.z(float(l)), norm += v * t.y(float(l));
  }
  return {float(sum[0] / norm), float(sum[1] / norm), float(sum[2] / norm)};
}

}  // namespace

TEST_CASE("metamerism: two paints match under D65 (CIEDE2000 < 0.5) and part under A and F11") {
  Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/metamerism.gltf");
  const Spectrum& smooth = *std::get<PbrMaterial>(scene.materials.at(1).kind).base_reflectance;
  const Spectrum& metamer = *std::get<PbrMaterial>(scene.materials.at(2).kind).base_reflectance;
  RenderOptions options;
  options.spp = 32;
  options.progress = false;
  const int width = 64, height = 40;  // the camera's 1.6:1
  for (const char* light : {"D65", "A", "F11"}) {
    INFO(light);
    const Spectrum s = *named_illuminant(light);
    scene.environment = spectrum_with_luminance(s, 1);
    const World world(scene);
    const std::vector<float> xyz =
        render(world, Camera(scene.cameras.at(0), width, height), options).state.film.xyz_image();
    // The patches' centres at x = ∓0.7 of a 3.85 × 2.41 view; a window of ±0.3 inside each.
    const Xyz left = window_mean(xyz, width, 16, 15, 25, 25), right = window_mean(xyz, width, 39, 15, 48, 25);
    const Xyz white = sampled_xyz_mean(*scene.environment);  // the perfect diffuser's
    const double rendered = ciede2000(to_lab(left, white), to_lab(right, white));
    const double expected = ciede2000(to_lab(paint_xyz(smooth, s), white), to_lab(paint_xyz(metamer, s), white));
    INFO("CIEDE2000: rendered " << rendered << ", from the spectra " << expected);
    CHECK(std::abs(rendered - expected) < 0.3);
    if (std::string(light) == "D65")
      CHECK(rendered < 0.5);
    else
      CHECK(rendered > 2);
  }
}
