// Colour: spectra to XYZ, the OCIO pipeline to output spaces, and RGB -> spectrum -> RGB.

#include <catch2/catch.hpp>
#include <limits>

#include "core/base/error.h"
#include "core/base/rng.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"
#include "spectral/wavelengths.h"

using namespace prism;

namespace {
Rgb xyz_to_rec709(const Xyz& xyz) {
  float px[3] = {xyz.x, xyz.y, xyz.z};
  ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, px, 1);
  return {px[0], px[1], px[2]};
}

// Colour of a reflectance lit by the working space's white (the normalised D65).
Rgb reflectance_rgb(const Spectrum& reflectance) {
  const auto& d65 = cie().d65;
  std::vector<float> lit;
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
    lit.push_back(evaluate(reflectance, float(l)) * d65(float(l)));
  return xyz_to_rec709(spectrum_to_xyz(DenselySampledSpectrum(int(kLambdaMin), lit)));
}
}  // namespace

TEST_CASE("D65 -> XYZ -> linear Rec.709 through the shipped OCIO config stays white") {
  const Xyz xyz = spectrum_to_xyz(cie().d65);
  CHECK(xyz.y == Approx(1.0).epsilon(1e-6));
  const Rgb rgb = xyz_to_rec709(xyz);
  CHECK(rgb.r == Approx(rgb.g).margin(1e-3));
  CHECK(rgb.g == Approx(rgb.b).margin(1e-3));
  CHECK(rgb.g == Approx(1.0).margin(1e-3));
}

TEST_CASE("D65 chromaticity from the shipped CIE tables") {
  const Xyz xyz = spectrum_to_xyz(cie().d65);
  const float sum = xyz.x + xyz.y + xyz.z;
  CHECK(xyz.x / sum == Approx(0.31273).margin(2e-5));  // CIE 15: 0.31272, 0.32903
  CHECK(xyz.y / sum == Approx(0.32902).margin(2e-5));
}

TEST_CASE("RGB albedo -> spectrum -> XYZ -> RGB round trip within 0.01") {
  Rng rng(7, 0);
  for (int i = 0; i < 100; ++i) {
    const Rgb in{rng.uniform(), rng.uniform(), rng.uniform()};
    const Rgb out = reflectance_rgb(RgbAlbedoSpectrum(in));
    INFO("rgb " << in.r << ", " << in.g << ", " << in.b);
    for (int c = 0; c < 3; ++c) CHECK(out[c] == Approx(in[c]).margin(0.01));
  }
  const Rgb saturated[] = {{0.9f, 0, 0}, {0, 0.9f, 0}, {0, 0, 0.9f}, {0.9f, 0.9f, 0}, {0, 0.9f, 0.9f}, {0.9f, 0, 0.9f}};
  for (const Rgb& in : saturated) {
    const Rgb out = reflectance_rgb(RgbAlbedoSpectrum(in));
    INFO("rgb " << in.r << ", " << in.g << ", " << in.b);
    for (int c = 0; c < 3; ++c) CHECK(out[c] == Approx(in[c]).margin(0.01));
  }
}

TEST_CASE("RGB albedo spectra stay between 0 and 1, and grey is exactly flat") {
  Rng rng(11, 0);
  for (int i = 0; i < 200; ++i) {
    const Spectrum s = RgbAlbedoSpectrum(Rgb{rng.uniform(), rng.uniform(), rng.uniform()});
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5.f) {
      REQUIRE(evaluate(s, l) >= 0.f);
      REQUIRE(evaluate(s, l) <= 1.f);
    }
  }
  for (float v : {0.f, 0.18f, 0.5f, 1.f}) {
    const Spectrum s = RgbAlbedoSpectrum(Rgb{v, v, v});
    for (float l : {360.f, 550.f, 830.f}) CHECK(evaluate(s, l) == Approx(v).margin(1e-6));
  }
}

TEST_CASE("RGB spectra at a path's wavelengths, all lanes at once, equal each lane's alone bit for bit") {
  // sample<8> evaluates the sigmoid on all lanes at once (SIMD); it must round as one at a time,
  // greys 0 and 1 (the sigmoid's clamped ends) included.
  Rng rng(12, 0);
  for (int i = 0; i < 100; ++i) {
    const Rgb c = i == 0 ? Rgb{0, 0, 0} : i == 1 ? Rgb{1, 1, 1} : Rgb{rng.uniform(), rng.uniform(), rng.uniform()};
    const auto lambda = SampledWavelengths<8>::sample({rng.uniform(), rng.uniform()});
    for (const Spectrum& s : {Spectrum(RgbAlbedoSpectrum(c)), Spectrum(RgbUnboundedSpectrum(c * 3.f)),
                              Spectrum(RgbIlluminantSpectrum(c)), Spectrum(RgbAbsorptionSpectrum(c, 2.f))}) {
      const SampledSpectrum<8> lanes = sample(s, lambda);
      for (int k = 0; k < 8; ++k) {
        INFO("colour " << c[0] << " " << c[1] << " " << c[2] << ", kind " << s.index() << ", lane " << k);
        CHECK(lanes[k] == evaluate(s, lambda[k]));
      }
    }
  }
  for (float v : {0.f, 1.f}) {
    const auto lambda = SampledWavelengths<8>::sample({0.3f, 0.7f});
    const SampledSpectrum<8> grey = sample(Spectrum(RgbAlbedoSpectrum(Rgb{v, v, v})), lambda);
    for (int k = 0; k < 8; ++k) CHECK(grey[k] == v);
  }
}

TEST_CASE("to_xyz ignores what a terminated lane carries, NaN and infinity included") {
  // Past a dispersive interface only the hero lane is followed (its pdf alone non-zero); the other
  // lanes' values are left as they were and must not reach the pixel.
  auto lambda = SampledWavelengths<8>::sample({0.4f, 0.6f});
  lambda.terminate_secondary();
  SampledSpectrum<8> clean(0.f), dirty(std::numeric_limits<float>::quiet_NaN());
  clean[0] = dirty[0] = 2.f;
  dirty[1] = std::numeric_limits<float>::infinity();
  const Xyz a = to_xyz(clean, lambda), b = to_xyz(dirty, lambda);
  REQUIRE(a.y > 0);
  CHECK(b.x == a.x);
  CHECK(b.y == a.y);
  CHECK(b.z == a.z);
}

TEST_CASE("RGB illuminant and unbounded spectra reproduce their colour") {
  // An emitter of RGB c has the colour c (its shape times the space's white).
  for (const Rgb in : {Rgb{1, 1, 1}, Rgb{4, 2, 1}, Rgb{0.2f, 0.5f, 3.f}}) {
    const Rgb out = xyz_to_rec709(spectrum_to_xyz(RgbIlluminantSpectrum(in)));
    for (int c = 0; c < 3; ++c) CHECK(out[c] == Approx(in[c]).epsilon(0.01).margin(0.01));
  }
  const Rgb in{2.f, 0.5f, 0.1f};
  const Rgb out = reflectance_rgb(RgbUnboundedSpectrum(in));
  for (int c = 0; c < 3; ++c) CHECK(out[c] == Approx(in[c]).epsilon(0.01).margin(0.01));
}

TEST_CASE("tabulated spectra interpolate linearly and hold their end values") {
  const Spectrum s = TabulatedSpectrum({400, 500, 600}, {1, 3, 2});
  CHECK(evaluate(s, 450) == Approx(2));
  CHECK(evaluate(s, 550) == Approx(2.5));
  CHECK(evaluate(s, 360) == Approx(1));
  CHECK(evaluate(s, 800) == Approx(2));
}

TEST_CASE("blackbody spectrum follows Planck's law, peak normalised to 1") {
  // B(λ = 500 nm, T = 5000 K) = 1.21e13 W / (m² sr m) (from 2hc²/λ⁵ / (e^{hc/λkT} − 1)).
  CHECK(BlackbodySpectrum::planck(500.f, 5000.f) == Approx(1.2104e13).epsilon(1e-3));
  const Spectrum s = BlackbodySpectrum(5000.f);
  CHECK(evaluate(s, 579.55f) == Approx(1.0).epsilon(1e-4));  // Wien: 2.8977721e-3 / 5000 m
  CHECK(evaluate(s, 400.f) < 1.f);
  CHECK(evaluate(s, 800.f) < 1.f);
}

TEST_CASE("output colour spaces and their chromaticities") {
  const auto& cp = ColorPipeline::standard();
  const Chromaticities rec709 = cp.chromaticities(ColorPipeline::kDefaultOutput);
  CHECK(rec709.red[0] == Approx(0.64).margin(1e-4));
  CHECK(rec709.red[1] == Approx(0.33).margin(1e-4));
  CHECK(rec709.green[0] == Approx(0.30).margin(1e-4));
  CHECK(rec709.blue[1] == Approx(0.06).margin(1e-4));
  CHECK(rec709.white[0] == Approx(0.3127).margin(1e-4));
  CHECK(rec709.white[1] == Approx(0.3290).margin(1e-4));
  const Chromaticities ap1 = cp.chromaticities("ACEScg");
  CHECK(ap1.red[0] == Approx(0.713).margin(1e-4));
  CHECK(ap1.white[0] == Approx(0.32168).margin(1e-4));
  const Chromaticities ap0 = cp.chromaticities("ACES2065-1");
  CHECK(ap0.red[0] == Approx(0.7347).margin(1e-4));
  CHECK(ap0.blue[1] == Approx(-0.0770).margin(1e-4));
  const Chromaticities xyz = cp.chromaticities(ColorPipeline::kXyz);
  CHECK(xyz.red[0] == Approx(1));
  CHECK(xyz.green[1] == Approx(1));
  CHECK(xyz.white[0] == Approx(1.0 / 3));

  CHECK(cp.canonical_name("acescg") == "ACEScg");
  CHECK(cp.canonical_name("lin_srgb") == ColorPipeline::kDefaultOutput);
  CHECK_THROWS_WITH(cp.canonical_name("Rec.2020 nonsense"), Catch::Contains("ACES2065-1"));
  CHECK_THROWS_AS(cp.canonical_name("Raw"), Error);
}

TEST_CASE("the sRGB display view encodes scene-linear values") {
  const float grey = 0.18f;
  Xyz xyz = spectrum_to_xyz(cie().d65) * grey;
  float px[3] = {xyz.x, xyz.y, xyz.z};
  ColorPipeline::standard().xyz_to_display(ColorPipeline::kDefaultDisplay, ColorPipeline::kDefaultView, px, 1);
  for (float v : px) CHECK(v == Approx(0.4613).margin(2e-3));  // sRGB encoding of 0.18
}
