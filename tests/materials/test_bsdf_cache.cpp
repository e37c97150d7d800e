// BsdfCache: a path's next BSDF is the one make_bsdf would make there, whichever of make_bsdf's
// inputs changed since the last point (material, texture, vertex colour, coat normal, front medium),
// and a layered BSDF kept through a hit on another material; and PbrMaterial::textured(), its hint
// that a material's inputs vary over the surface, and SurfaceInputs::textured, what it relies on.

#include <catch2/catch.hpp>
#include <memory>

#include "materials/bsdf_cache.h"

using namespace prism;

namespace {

constexpr int N = 8;

SampledWavelengths<N> wavelengths() { return SampledWavelengths<N>::sample({0.31f, 0.77f}); }

// A layered material (clear coat, sheen, film, specular colour, diffuse transmission) over a
// half-metal base.
PbrMaterial layered() {
  PbrMaterial p;
  p.base_color = {0.7f, 0.4f, 0.2f};
  p.metallic = 0.5f, p.roughness = 0.4f;
  p.specular_color = {1.2f, 1.f, 0.6f};
  p.clearcoat.emplace();
  p.clearcoat->factor = 0.8f, p.clearcoat->roughness = 0.2f;
  p.sheen.emplace();
  p.sheen->color = {0.5f, 0.5f, 1.f}, p.sheen->roughness = 0.5f;
  p.iridescence.emplace();
  p.iridescence->factor = 0.5f, p.iridescence->ior = 1.6f, p.iridescence->thickness_max = 250;
  p.diffuse_transmission.emplace();
  p.diffuse_transmission->factor = 0.3f;
  return p;
}

// A 2×1 base-colour texture: red on the left half, blue on the right (nearest).
Texture red_blue() {
  Texture t;
  t.image = std::make_shared<Image>(2, 1, std::vector<uint8_t>{255, 0, 0, 255, 0, 0, 255, 255});
  t.nearest = true;
  return t;
}

SurfacePoint point(float u) {
  SurfacePoint at;
  at.uv[0] = {u, 0.5f};
  return at;
}

// Whether two BSDFs have the same f and pdf, bit for bit, over a few pairs of directions.
bool same(const Bsdf<N>& a, const Bsdf<N>& b) {
  const Vec3f wos[] = {normalize(Vec3f(0.3f, 0.1f, 0.9f)), normalize(Vec3f(-0.6f, 0.2f, 0.3f))};
  const Vec3f wis[] = {normalize(Vec3f(-0.2f, 0.4f, 0.8f)), normalize(Vec3f(0.5f, -0.5f, 0.2f)),
                       normalize(Vec3f(0.1f, 0.3f, -0.7f))};
  for (const Vec3f& wo : wos)
    for (const Vec3f& wi : wis) {
      const BsdfEval<N> x = bsdf_eval(a, wo, wi), y = bsdf_eval(b, wo, wi);
      if (x.pdf != y.pdf) return false;
      for (int i = 0; i < N; ++i)
        if (x.f[i] != y.f[i]) return false;
    }
  return true;
}

// After `before`, BsdfCache gives at `after` what make_bsdf makes there, and that differs from the
// BSDF at `before` (or the check could not tell a stale BSDF from a fresh one).
void check_follows(const Material& m0, const SurfacePoint& before, const Dielectric* front0, const Material& m1,
                   const SurfacePoint& after, const Dielectric* front1) {
  const SampledWavelengths<N> lambda = wavelengths();
  BsdfCache<N> last;
  const Bsdf<N> old = make_bsdf(m0, before, lambda, front0), fresh = make_bsdf(m1, after, lambda, front1);
  REQUIRE(std::holds_alternative<LayeredBsdf<N>>(old));  // the kind BsdfCache keeps
  REQUIRE_FALSE(same(old, fresh));
  CHECK(same(last.of(m0, before, lambda, front0), old));
  CHECK(same(last.of(m1, after, lambda, front1), fresh));
}

}  // namespace

TEST_CASE("BsdfCache makes the BSDF again when any of make_bsdf's inputs changes") {
  const Material plain{"layered", layered(), {}, false};
  PbrMaterial textured_pbr = layered();
  textured_pbr.base_color = {1, 1, 1};
  textured_pbr.base_color_texture = red_blue();
  const Material textured{"textured", textured_pbr, {}, false};
  PbrMaterial other_pbr = layered();
  other_pbr.dielectric = Dielectric(ConstantIor{1.8f});  // not among the inputs at a point: only the material tells
  const Material other{"other", other_pbr, {}, false};
  const Dielectric water(ConstantIor{1.33f});

  SECTION("the texture at the new point") {
    check_follows(textured, point(0.25f), nullptr, textured, point(0.75f), nullptr);
  }
  SECTION("the vertex colour") {
    SurfacePoint tinted = point(0.25f);
    tinted.vertex_color = {0.5f, 1, 1, 1};
    check_follows(plain, point(0.25f), nullptr, plain, tinted, nullptr);
  }
  SECTION("the coat's normal") {
    SurfacePoint tilted = point(0.25f);
    tilted.coat_normal = normalize(Vec3f(0.3f, 0, 1));
    check_follows(plain, point(0.25f), nullptr, plain, tilted, nullptr);
  }
  SECTION("the material's colours upsampled once (World's constant spectra)") {
    PbrMaterial green = layered();
    green.base_color = {0.1f, 0.8f, 0.1f};
    const ConstantSpectra spectra(green);
    SurfacePoint upsampled = point(0.25f);
    upsampled.spectra = &spectra;
    check_follows(plain, point(0.25f), nullptr, plain, upsampled, nullptr);
  }
  SECTION("the front medium") { check_follows(plain, point(0.25f), nullptr, plain, point(0.25f), &water); }
  SECTION("the material") { check_follows(plain, point(0.25f), nullptr, other, point(0.25f), nullptr); }
  SECTION("a diffuse material after a layered one") {
    const Material diffuse{"diffuse", DiffuseMaterial{ConstantSpectrum{0.5f}}, {}, false};
    check_follows(plain, point(0.25f), nullptr, diffuse, point(0.25f), nullptr);
  }
}

TEST_CASE(
    "BsdfCache's kept BSDF, its caches filled from other directions, is the one make_bsdf makes at the next point") {
  // An untextured material at new texture coordinates: the key is equal, so the BSDF is kept, with
  // what its caches (E(μ_o) and the like) hold from the directions it was evaluated from before.
  const SampledWavelengths<N> lambda = wavelengths();
  const Material plain{"layered", layered(), {}, false};
  BsdfCache<N> last;
  const Bsdf<N>& first = last.of(plain, point(0.25f), lambda, nullptr);
  REQUIRE(std::holds_alternative<LayeredBsdf<N>>(first));
  bsdf_eval(first, normalize(Vec3f(0.7f, -0.2f, 0.4f)), normalize(Vec3f(0.1f, 0.2f, 0.9f)));
  CHECK(same(last.of(plain, point(0.75f), lambda, nullptr), make_bsdf(plain, point(0.75f), lambda, nullptr)));
}

TEST_CASE("BsdfCache keeps a layered BSDF through a hit on another material") {
  // A path from a sphere to the floor and back: the floor's BSDF is made beside the kept one, which
  // is returned again (the same object, not made again) and is still the one make_bsdf makes. (A
  // first layered material puts the kept one in the place a BSDF made again would not take.)
  const SampledWavelengths<N> lambda = wavelengths();
  PbrMaterial thicker = layered();
  thicker.iridescence->thickness_max = 400;
  const Material plain{"layered", layered(), {}, false}, other{"layered, thicker film", thicker, {}, false};
  const Material diffuse{"diffuse", DiffuseMaterial{ConstantSpectrum{0.5f}}, {}, false};
  BsdfCache<N> last;
  last.of(other, point(0.25f), lambda, nullptr);
  const Bsdf<N>& first = last.of(plain, point(0.25f), lambda, nullptr);
  REQUIRE(std::holds_alternative<LayeredBsdf<N>>(first));
  CHECK(same(last.of(diffuse, point(0.25f), lambda, nullptr), make_bsdf(diffuse, point(0.25f), lambda, nullptr)));
  const Bsdf<N>& again = last.of(plain, point(0.75f), lambda, nullptr);
  CHECK(&again == &first);
  CHECK(same(again, make_bsdf(plain, point(0.75f), lambda, nullptr)));
}

TEST_CASE("PbrMaterial::textured names every texture whose texels reach the inputs") {
  // Each texture slot alone, with a texture whose halves differ in every channel (G = 0 on the
  // right: a thin wall for the thickness texture). The inputs at the two halves differ, and
  // textured() must say so (BsdfCache would otherwise compare them in vain), and so must the inputs
  // (BsdfCache takes inputs read from no texture to be the same at every point).
  Texture t;
  t.image = std::make_shared<Image>(2, 1, std::vector<uint8_t>{255, 255, 255, 255, 30, 0, 90, 0});
  t.nearest = true;
  using Set = void (*)(PbrMaterial&, const Texture&);
  const Set slots[] = {
      [](PbrMaterial& p, const Texture& x) { p.base_color_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.metallic_roughness_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.transmission_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.thickness_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.specular_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.specular_color_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.clearcoat->texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.clearcoat->roughness_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.sheen->color_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.sheen->roughness_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.iridescence->texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.iridescence->thickness_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.diffuse_transmission->texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.diffuse_transmission->color_texture = x; },
      [](PbrMaterial& p, const Texture& x) { p.anisotropy_strength = 0.5f, p.anisotropy_texture = x; },
  };
  CHECK_FALSE(layered().textured());
  CHECK_FALSE(layered().inputs(point(0.25f)).textured);
  int i = 0;
  for (const Set set : slots) {
    INFO("slot " << i++);
    PbrMaterial p = layered();
    p.transmission = 0.5f;
    set(p, t);
    CHECK_FALSE(p.inputs(point(0.25f)) == p.inputs(point(0.75f)));  // the texture reaches the inputs
    CHECK(p.textured());
    CHECK(p.inputs(point(0.25f)).textured);
  }
}
