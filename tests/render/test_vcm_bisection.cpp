// A measurement, not a check (hidden: ctest does not run it): the image mean of two integrators
// on data/scenes/dispersion.gltf over SEEDS independent renders each, with the standard error
// from the spread of the per-seed means (VCM's pixels share photons and wavelengths within an
// iteration, so the spread of pixels within one image says nothing about its mean's error).
// It finds where two integrators' means part, by turning the scene's features off one at a time
// (a base coincident with the floor, for one, offsets VCM's mean against BDPT's); e.g.
//   VARIANT=1 SPP=128 SEEDS=12 build/tests/tests_render "[vcm-bisection]"
// VARIANT bits: 1 prism of constant index, 2 prism diffuse, 4 emitter without its glossy coat,
// 8 floor and wall black, 16 prism lowered 1 mm onto the floor (its base coincident with the floor,
// which offsets VCM's mean). I1, I2: the integrators (IntegratorKind order: 0 path, 2 bdpt, 3 vcm,
// 4 light; −1 none). Also W, SPP, SEEDS, DEPTH, WL (wavelengths), RADIUS (0: default).
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>

#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "materials/catalogue.h"
#include "tests/support/test_scenes.h"
using namespace prism;
static int env_int(const char* n, int d) {
  const char* s = std::getenv(n);
  return s ? std::atoi(s) : d;
}
static float env_f(const char* n, float d) {
  const char* s = std::getenv(n);
  return s ? float(std::atof(s)) : d;
}
TEST_CASE("vcm against bdpt on the dispersive prism: image means over seeds", "[.][vcm-bisection]") {
  log::set_level(log::Level::quiet);
  Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/dispersion.gltf");
  const int variant = env_int("VARIANT", 0);
  for (Material& m : scene.materials) {
    if (m.name == "flint_glass") {
      if (variant & 1) m.kind = PbrMaterial::glass(Dielectric(ConstantIor{1.78472f}));
      if (variant & 2) m = test::diffuse({0.5f, 0.5f, 0.5f}, m.name);
    }
    if (m.name == "light" && (variant & 4)) {
      auto e = m.emission;
      m = test::diffuse({0, 0, 0}, m.name);
      m.emission = e;
    }
    if ((m.name == "floor" || m.name == "wall") && (variant & 8)) m = test::diffuse({0, 0, 0}, m.name);
  }
  if (variant & 16)
    for (Mesh& mesh : scene.meshes)
      if (mesh.name == "prism")
        for (Vec3f& p : mesh.positions) p.y -= 1e-3f;
  const int W = env_int("W", 64), spp = env_int("SPP", 64), seeds = env_int("SEEDS", 8), depth = env_int("DEPTH", 16);
  const char* integrators[] = {"path", "whitted", "bdpt", "vcm", "light"};
  for (int integ : {env_int("I1", 2), env_int("I2", 3)}) {
    if (integ < 0) continue;
    double s1 = 0, s2 = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      RenderOptions o;
      o.spp = spp;
      o.path.max_depth = depth;
      o.seed = uint64_t(seed) + 1000u * uint64_t(env_int("SEEDBASE", 0));
      o.threads = 2;
      o.integrator = IntegratorKind(integ);
      o.wavelengths = env_int("WL", 8);
      o.merge_radius = env_f("RADIUS", 0.f);
      const auto img = test::render_rgb(scene, scene.cameras.at(0), W, W, o);
      const double m = (img.mean(0) + img.mean(1) + img.mean(2)) / 3;
      s1 += m, s2 += m * m;
    }
    const double mean = s1 / seeds, se = std::sqrt(std::max(0.0, s2 / seeds - mean * mean) / (seeds - 1));
    std::printf("variant %d %s W %d spp %d seeds %d wl %d radius %g: mean %.6f +- %.6f\n", variant, integrators[integ],
                W, spp, seeds, env_int("WL", 8), env_f("RADIUS", 0.f), mean, se);
  }
}
