// Textures: sRGB decoding, wrap modes, filtering and KHR_texture_transform map texture
// coordinates to the expected texels.

#include <catch2/catch.hpp>

#include "materials/texture.h"

using namespace prism;

namespace {

// A 4×4 checker: texel (x, y) is white when x + y is even, black otherwise; alpha = 10·x + y.
Texture checker(Wrap wrap = Wrap::repeat, bool nearest = true) {
  std::vector<uint8_t> rgba;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const uint8_t v = (x + y) % 2 == 0 ? 255 : 0;
      rgba.insert(rgba.end(), {v, v, v, uint8_t(10 * x + y)});
    }
  Texture t;
  t.image = std::make_shared<Image>(4, 4, std::move(rgba));
  t.wrap_s = t.wrap_t = wrap;
  t.nearest = nearest;
  return t;
}

// The texel a nearest lookup at uv returns, as (x, y) recovered from its alpha.
std::pair<int, int> texel_at(const Texture& t, Vec2f uv) {
  const int a = int(std::lround(t.lookup(uv, false)[3] * 255));
  return {a / 10, a % 10};
}

}  // namespace

TEST_CASE("sRGB-encoded texels decode to linear by IEC 61966-2-1") {
  CHECK(srgb_to_linear(0) == 0.f);
  CHECK(srgb_to_linear(255) == Approx(1.f));
  CHECK(srgb_to_linear(128) == Approx(0.2158605f).epsilon(1e-5));
  CHECK(srgb_to_linear(10) == Approx(10 / 255.0 / 12.92).epsilon(1e-5));  // the linear segment
}

TEST_CASE("texture coordinates address texels from the top-left corner, with each wrap mode") {
  const Texture t = checker();
  CHECK(texel_at(t, {0.1f, 0.1f}) == std::pair{0, 0});
  CHECK(texel_at(t, {0.9f, 0.1f}) == std::pair{3, 0});
  CHECK(texel_at(t, {0.1f, 0.9f}) == std::pair{0, 3});
  CHECK(texel_at(t, {1.1f, -0.1f}) == std::pair{0, 3});  // repeat
  const Texture clamped = checker(Wrap::clamp_to_edge);
  CHECK(texel_at(clamped, {1.6f, -3.f}) == std::pair{3, 0});
  const Texture mirrored = checker(Wrap::mirrored_repeat);
  CHECK(texel_at(mirrored, {1.1f, 0.1f}) == std::pair{3, 0});  // reflected back at the edge
  CHECK(texel_at(mirrored, {2.1f, 0.1f}) == std::pair{0, 0});
  CHECK(texel_at(t, {std::nanf(""), kInfinity}) == std::pair{0, 0});  // never crashes
}

TEST_CASE("bilinear filtering blends the four nearest texels") {
  const Texture t = checker(Wrap::repeat, false);
  CHECK(t.lookup({0.125f, 0.125f}, false)[0] == Approx(1.f));  // a texel centre
  CHECK(t.lookup({0.25f, 0.125f}, false)[0] == Approx(0.5f));  // halfway to its black neighbour
  CHECK(t.lookup({0.25f, 0.25f}, false)[0] == Approx(0.5f));   // the corner of four texels
}

TEST_CASE("bilinear filtering blends across an edge as the wrap mode says") {
  // Halfway between the last column and the one beyond it (or the first and the one before),
  // in the top row: alpha = 10·x, so the blend of columns a and b reads 5·(a + b).
  const auto alpha = [](const Texture& t, float u) { return t.lookup({u, 0.125f}, false)[3] * 255; };
  const Texture repeat = checker(Wrap::repeat, false), clamped = checker(Wrap::clamp_to_edge, false),
                mirrored = checker(Wrap::mirrored_repeat, false);
  CHECK(alpha(repeat, 1.f) == Approx(15));  // columns 3 and 0
  CHECK(alpha(repeat, 0.f) == Approx(15));  // columns 3 (the one before 0) and 0
  CHECK(alpha(repeat, 2.f) == Approx(15));
  CHECK(alpha(repeat, -1.f) == Approx(15));
  CHECK(alpha(clamped, 1.f) == Approx(30));  // column 3 twice
  CHECK(alpha(clamped, 0.f) == Approx(0));
  CHECK(alpha(mirrored, 1.f) == Approx(30));  // column 3 and its mirror image, 3
  CHECK(alpha(mirrored, 0.f) == Approx(0));
  CHECK(alpha(mirrored, 2.f) == Approx(0));  // column 0 (mirrored twice) and its mirror image
}

TEST_CASE("KHR_texture_transform: offset, rotation and scale map coordinates as the extension defines") {
  Texture t = checker();
  t.transform.scale = {0.5f, 0.5f};  // uv ∈ [0,1] covers the top-left 2×2 texels
  CHECK(texel_at(t, {0.9f, 0.9f}) == std::pair{1, 1});
  t.transform = {};
  t.transform.offset = {0.5f, 0.f};
  CHECK(texel_at(t, {0.1f, 0.1f}) == std::pair{2, 0});
  // Rotation by +90°: (u, v) → (v, −u) (the extension's matrix [[cos, sin], [−sin, cos]]).
  t.transform = {};
  t.transform.rotation = kPi / 2;
  CHECK(texel_at(t, {0.1f, 0.9f}) == std::pair{3, 3});  // (0.9, −0.1) wraps to (0.9, 0.9)
  // Offset, rotation and scale together: T · R · S.
  t.transform = {{0.25f, 0.5f}, {2.f, 2.f}, kPi};
  // S: (0.2, 0.1) → (0.4, 0.2); R(π): → (−0.4, −0.2); T: → (−0.15, 0.3) → wraps to (0.85, 0.3).
  CHECK(texel_at(t, {0.2f, 0.1f}) == std::pair{3, 1});
}
