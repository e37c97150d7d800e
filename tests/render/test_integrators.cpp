// The table of integrators (core/render/integrators.h) and --integrator auto's choice.

#include <catch2/catch.hpp>
#include <set>

#include "core/render/integrators.h"

using namespace prism;

TEST_CASE("the table of integrators: one row each, in IntegratorKind order, found by name") {
  std::set<std::string_view> names;
  size_t row = 0;
  for (const Integrator& i : integrators()) {
    INFO(i.name);
    CHECK(size_t(i.kind) == row++);
    CHECK(names.insert(i.name).second);
    CHECK(&integrator(i.kind) == &i);
    CHECK(find_integrator(i.name) == &i);
    CHECK(!i.description.empty());
    // What runs per pixel supports what per-pixel estimates need; light tracing alone and VCM's
    // photon iterations trace light paths.
    CHECK(i.per_pixel() == !i.light_paths);
    if (i.light_tracing_only || i.photon_iterations) CHECK(i.light_paths);
  }
  CHECK(find_integrator("auto") == nullptr);  // a choice of the CLI, not an integrator
  CHECK(find_integrator("mlt") == nullptr);
  CHECK(integrator_names() == "path, whitted, bdpt, vcm, light");
}

TEST_CASE("auto: vcm for closed dielectrics lit by lights inside the scene, else path") {
  SceneFeatures glass_lit;
  glass_lit.dielectric_volumes = true;
  glass_lit.emissive_triangles = true;
  CHECK(choose_integrator(glass_lit, false).kind == IntegratorKind::vcm);
  for (bool SceneFeatures::*light :
       {&SceneFeatures::point_lights, &SceneFeatures::spot_lights, &SceneFeatures::directional_lights}) {
    SceneFeatures f;
    f.dielectric_volumes = true;
    f.*light = true;
    f.environment = true;  // a sky as well does not change it
    CHECK(choose_integrator(f, false).kind == IntegratorKind::vcm);
  }
  // Per-pixel estimates (a noise threshold, spectral bins) need the path tracer.
  const IntegratorChoice per_pixel = choose_integrator(glass_lit, true);
  CHECK(per_pixel.kind == IntegratorKind::path);
  CHECK(per_pixel.reason.find("per-pixel") != std::string::npos);
  // Glass under the sky alone, lights without glass, thin walls: no caustics worth VCM's cost.
  SceneFeatures sky_glass;
  sky_glass.dielectric_volumes = true;
  sky_glass.environment = sky_glass.environment_map = true;
  CHECK(choose_integrator(sky_glass, false).kind == IntegratorKind::path);
  SceneFeatures lamps;
  lamps.emissive_triangles = lamps.point_lights = true;
  lamps.dispersion = true;  // a thin dispersive wall makes no closed volume
  CHECK(choose_integrator(lamps, false).kind == IntegratorKind::path);
  CHECK(!choose_integrator(lamps, false).reason.empty());
}
