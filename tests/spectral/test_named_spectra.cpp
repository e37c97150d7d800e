// The named illuminants against the CIE's published chromaticities, blackbodies against
// illuminant A, tabulated spectra outside their points, and white balance.

#include <catch2/catch.hpp>
#include <cmath>

#include "spectral/cie.h"
#include "spectral/color_difference.h"
#include "spectral/named_spectra.h"
#include "spectral/white_balance.h"

using namespace prism;

namespace {

struct Chromaticity {
  double x, y;
};

Chromaticity chromaticity(const Spectrum& s) {
  const Xyz c = spectrum_to_xyz(s);
  const double sum = double(c.x) + c.y + c.z;
  return {c.x / sum, c.y / sum};
}

}  // namespace

TEST_CASE("named illuminants have the chromaticities the CIE publishes for them (2° observer)") {
  // CIE 15:2018 (and CIE 15:2004 for A, D and F); the CIE computes them from 5 nm tables,
  // Prism from 1 nm ones, hence 5e-4.
  const std::pair<const char*, Chromaticity> published[] = {
      {"A", {0.44757, 0.40745}},      {"D50", {0.34567, 0.35850}},  {"D55", {0.33242, 0.34743}},
      {"D65", {0.31271, 0.32902}},    {"D75", {0.29902, 0.31485}},  {"E", {1 / 3.0, 1 / 3.0}},
      {"F1", {0.3131, 0.3371}},       {"F2", {0.3721, 0.3751}},     {"F3", {0.4091, 0.3941}},
      {"F4", {0.4402, 0.4031}},       {"F5", {0.3138, 0.3452}},     {"F6", {0.3779, 0.3882}},
      {"F7", {0.3129, 0.3292}},       {"F8", {0.3458, 0.3586}},     {"F9", {0.3741, 0.3727}},
      {"F10", {0.3458, 0.3588}},      {"F11", {0.3805, 0.3769}},    {"F12", {0.4370, 0.4042}},
      {"LED-B1", {0.4560, 0.4078}},   {"LED-B2", {0.4357, 0.4012}}, {"LED-B3", {0.3756, 0.3723}},
      {"LED-B4", {0.3422, 0.3502}},   {"LED-B5", {0.3118, 0.3236}}, {"LED-BH1", {0.4474, 0.4066}},
      {"LED-RGB1", {0.4557, 0.4211}}, {"LED-V1", {0.4548, 0.4044}}, {"LED-V2", {0.3781, 0.3775}},
  };
  for (const auto& [name, xy] : published) {
    INFO(name);
    const auto s = named_illuminant(name);
    REQUIRE(s);
    const Chromaticity c = chromaticity(*s);
    CHECK(c.x == Approx(xy.x).margin(5e-4));
    CHECK(c.y == Approx(xy.y).margin(5e-4));
  }
  CHECK(named_illuminants().size() == std::size(published));
  // The CIE's names of the fluorescent lamps name the same tables.
  CHECK(chromaticity(*named_illuminant("FL11")).x == chromaticity(*named_illuminant("F11")).x);
  CHECK_FALSE(named_illuminant("F13"));
  CHECK_FALSE(named_illuminant("d65"));
}

TEST_CASE("a blackbody of 2856 K has the chromaticity of illuminant A within 0.001") {
  const Chromaticity a = chromaticity(*named_illuminant("A")), b = chromaticity(BlackbodySpectrum(2856));
  CHECK(std::abs(a.x - b.x) < 0.001);
  CHECK(std::abs(a.y - b.y) < 0.001);
  // A by its defining formula at 560 nm is 100.
  CHECK(illuminant_a(560) == Approx(100).epsilon(1e-12));
}

TEST_CASE("a tabulated spectrum holds its ends, or is 0 beyond them") {
  const TabulatedSpectrum hold({400, 500}, {2, 4}), zero({400, 500}, {2, 4}, TabulatedSpectrum::Outside::zero);
  CHECK(hold(350) == 2);
  CHECK(hold(600) == 4);
  CHECK(zero(399.9f) == 0);
  CHECK(zero(500.1f) == 0);
  for (const TabulatedSpectrum* s : {&hold, &zero}) {
    CHECK((*s)(400) == 2);
    CHECK((*s)(450) == 3);
    CHECK((*s)(500) == 4);
  }
}

TEST_CASE("white balance: the illuminant's white becomes D65's, neutrals stay neutral, luminance is kept") {
  const Xyz d65 = spectrum_to_xyz(cie().d65);
  for (const char* name : {"A", "F11", "LED-B1", "D50"}) {
    INFO(name);
    const Xyz white = spectrum_to_xyz(*named_illuminant(name));
    const WhiteBalance wb = WhiteBalance::to_d65(name, white);
    // The illuminant's white at any luminance goes to D65's at that luminance.
    const Xyz scaled{white.x * 0.3f / white.y, 0.3f, white.z * 0.3f / white.y};
    const Xyz adapted = wb(scaled);
    CHECK(adapted.x == Approx(0.3 * d65.x).epsilon(1e-5));
    CHECK(adapted.y == Approx(0.3).epsilon(1e-5));
    CHECK(adapted.z == Approx(0.3 * d65.z).epsilon(1e-5));
  }
  // Balancing for D65 itself changes nothing.
  const WhiteBalance identity = WhiteBalance::to_d65("D65", d65);
  for (int i = 0; i < 9; ++i) CHECK(identity.m[i] == Approx(i % 4 == 0 ? 1 : 0).margin(1e-6));
}

TEST_CASE("CIEDE2000 gives Sharma, Wu and Dalal's test values") {
  // Pairs 1, 2, 3, 7, 17 and 25 of their table (Color Res. Appl. 30(1), 2005).
  const struct {
    Lab a, b;
    double delta;
  } pairs[] = {
      {{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
      {{50, 3.1571, -77.2803}, {50, 0, -82.7485}, 2.8615},
      {{50, 2.8361, -74.0200}, {50, 0, -82.7485}, 3.4412},
      {{50, 0, 0}, {50, -1, 2}, 2.3669},
      {{50, 2.5, 0}, {73, 25, -18}, 27.1492},
      {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
  };
  for (const auto& p : pairs) {
    CHECK(ciede2000(p.a, p.b) == Approx(p.delta).margin(1e-4));
    CHECK(ciede2000(p.b, p.a) == Approx(p.delta).margin(1e-4));
  }
  CHECK(ciede2000({50, 10, 10}, {50, 10, 10}) == 0);
  // CIELAB of the white itself is L = 100, a = b = 0.
  const Lab white = to_lab({0.95047f, 1.f, 1.08883f}, {0.95047f, 1.f, 1.08883f});
  CHECK(white.l == Approx(100));
  CHECK(white.a == Approx(0).margin(1e-9));
}
