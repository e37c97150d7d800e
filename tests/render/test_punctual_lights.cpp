// Punctual lights against their analytic irradiance on a Lambertian plane, whose radiance is
// ρ E / π: point E = I cos θ / d², spot the same times glTF's cone attenuation, directional
// E = E⊥ cos θ. Direct light only (max depth 1), through both integrators. And the lamp
// (as in Khronos' LightsPunctualLamp): a point light centimetres from a Lambertian plane, and behind
// a rough thin-walled pane, whose transmitted radiance is written out below from the glTF
// definition, independently of the renderer's lobes.

#include <catch2/catch.hpp>
#include <functional>

#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

constexpr float kAlbedo = 0.5f;

Scene plane_scene() {
  Scene scene;
  scene.materials.push_back(test::diffuse({kAlbedo, kAlbedo, kAlbedo}));
  test::add_mesh(scene, test::make_quad({-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, 0));  // front = +Y
  return scene;
}

// The square [x0, x0 + size] × [z0, z0 + size] of the plane y = 0, seen straight down by an
// orthographic camera in n × n pixels: pixel (i, j) covers x0 + [i, i + 1]·size/n, z0 + [j, j + 1]·size/n.
struct Square {
  float x0, z0, size;

  test::TestRender render(const Scene& scene, IntegratorKind integrator, int n, int spp) const {
    CameraDesc c;
    c.projection = CameraDesc::Projection::orthographic;
    c.xmag = c.ymag = size / 2;
    const Vec3f eye(x0 + size / 2, 10.f, z0 + size / 2), right(1, 0, 0), up(0, 0, -1), back(0, 1, 0);
    for (int r = 0; r < 3; ++r) {
      c.to_world.m[r][0] = right[r];
      c.to_world.m[r][1] = up[r];
      c.to_world.m[r][2] = back[r];
      c.to_world.m[r][3] = eye[r];
    }
    return test::render_rgb(scene, c, n, n, spp, 1, 1, 0, integrator);
  }
};

// Checks that the radiance seen over the square is `radiance` within 1%: the render divided pixel
// by pixel by it (averaged over the pixel on sub × sub points) must average 1.
void check_radiance(const Scene& scene, IntegratorKind integrator, const Square& square,
                    const std::function<double(const Vec3f&)>& radiance, int sub = 8) {
  constexpr int n = 16;
  test::TestRender r = square.render(scene, integrator, n, 512);
  CHECK(r.stats.invalid_samples == 0);
  const float pixel = square.size / n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double expected = 0;
      for (int i = 0; i < sub; ++i)
        for (int j = 0; j < sub; ++j)
          expected +=
              radiance({square.x0 + (x + (i + 0.5f) / sub) * pixel, 0, square.z0 + (y + (j + 0.5f) / sub) * pixel});
      expected /= sub * sub;
      for (int c = 0; c < 3; ++c) r.rgb[(size_t(y) * n + x) * 3 + c] /= float(expected);
    }
  test::check_mean(r, 0, 0, n, n, 1.0, 0.01);
}

// The Lambertian plane's radiance ρ E / π under irradiance E.
void check_irradiance(const Scene& scene, IntegratorKind integrator, const Square& square,
                      const std::function<double(const Vec3f&)>& irradiance) {
  check_radiance(scene, integrator, square, [&](const Vec3f& p) { return kAlbedo * irradiance(p) / kPi; });
}

// Checks that the plane is exactly black over the square.
void check_dark(const Scene& scene, IntegratorKind integrator, const Square& square) {
  test::check_mean(square.render(scene, integrator, 8, 16), 0, 0, 8, 8, 0.0, 1e-9);
}

// A point on the plane y = 0 lit from `light`: cos θ / d².
double inverse_square_cosine(const Vec3f& light, const Vec3f& p) {
  const Vec3d d = Vec3d(light - p);
  return d.y / (length(d) * length_squared(d));
}

const IntegratorKind kIntegrators[] = {IntegratorKind::path, IntegratorKind::whitted};

}  // namespace

TEST_CASE("point light: irradiance on a plane is I cos(theta) / d^2") {
  Scene scene = plane_scene();
  const Vec3f position(0.3f, 1.5f, -0.2f);
  const float I = 20;
  scene.point_lights.push_back({"lamp", position, RgbIlluminantSpectrum(Rgb{I, I, I})});
  const auto E = [&](const Vec3f& p) { return I * inverse_square_cosine(position, p); };
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    check_irradiance(scene, integrator, {-2, -2, 4}, E);
    check_irradiance(scene, integrator, {-0.2f, -0.7f, 1}, E);  // under the light
    check_irradiance(scene, integrator, {-2, 1, 1}, E);         // a far corner, light arriving at 60°-70°
  }
}

TEST_CASE("spot light: irradiance follows glTF's cone attenuation inside, across and outside the cone") {
  // Above the origin, tilted 30° from straight down towards +X, cones of 20° and 40°: along the
  // x axis the angle from the spot's axis is |atan x − 30°|.
  Scene scene = plane_scene();
  const float inner = radians(20.f), outer = radians(40.f), tilt = radians(30.f), I = 10;
  const Vec3f position(0, 1, 0), axis(std::sin(tilt), -std::cos(tilt), 0);
  scene.spot_lights.push_back({"spot", position, axis, inner, outer, RgbIlluminantSpectrum(Rgb{I, I, I})});
  // KHR_lights_punctual's reference implementation, written out independently of the renderer.
  const auto attenuation = [&](const Vec3f& p) {
    const double cos_theta = dot(Vec3d(axis), normalize(Vec3d(p - position)));
    const double scale = 1 / std::max(1e-3, std::cos(double(inner)) - std::cos(double(outer)));
    const double offset = -std::cos(double(outer)) * scale;
    return sqr(std::clamp(cos_theta * scale + offset, 0.0, 1.0));
  };
  const auto E = [&](const Vec3f& p) { return I * attenuation(p) * inverse_square_cosine(position, p); };
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    check_irradiance(scene, integrator, {0.4f, -0.2f, 0.4f}, E);   // inside the inner cone: at most 13° off the axis
    check_irradiance(scene, integrator, {1.5f, -0.2f, 0.4f}, E);   // in the falloff: 26°–33°
    check_irradiance(scene, integrator, {-0.1f, -0.1f, 0.2f}, E);  // in the falloff on the other side: 24°–37°
    check_dark(scene, integrator, {3.f, -0.2f, 0.4f});             // beyond the outer cone: over 41°
    check_dark(scene, integrator, {-0.7f, -0.2f, 0.4f});
  }
}

TEST_CASE("directional light: irradiance on a plane is E cos(theta), with shadows from far away") {
  Scene scene = plane_scene();
  const Vec3f direction = normalize(Vec3f(1, -2, 0.5f));
  const float E = 3;
  scene.directional_lights.push_back({"sun", direction, RgbIlluminantSpectrum(Rgb{E, E, E})});
  // A 0.6 × 0.6 square 100 units up the light's direction shadows the square under it.
  scene.materials.push_back(test::diffuse({1, 1, 1}, "cloud"));
  test::add_mesh(scene, test::make_quad(Vec3f(-0.3f, 0, -0.3f) - direction * 100, {0, 0, 0.6f}, {0.6f, 0, 0}, 1));
  const double cos_theta = -direction.y;
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    check_irradiance(scene, integrator, {0.4f, 0.4f, 1}, [&](const Vec3f&) { return E * cos_theta; });
    check_irradiance(scene, integrator, {-3, -3, 2}, [&](const Vec3f&) { return E * cos_theta; });
    check_dark(scene, integrator, {-0.2f, -0.2f, 0.4f});
  }
}

TEST_CASE("lamp: a point light centimetres from a Lambertian plane gives I cos(theta) / d^2") {
  // LightsPunctualLamp's bulb sits a few centimetres from its stand and shade: 3 cm over the
  // plane, the irradiance under it is 37 times that at the square's corners.
  Scene scene = plane_scene();
  const Vec3f position(0.01f, 0.03f, -0.02f);
  const float I = 0.5f;
  scene.point_lights.push_back({"bulb", position, RgbIlluminantSpectrum(Rgb{I, I, I})});
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    check_irradiance(scene, integrator, {-0.1f, -0.1f, 0.2f},
                     [&](const Vec3f& p) { return I * inverse_square_cosine(position, p); });
  }
}

namespace {

// glTF's thin-walled transmission (KHR_materials_transmission without KHR_materials_volume),
// written out in double from its definition: the reflection lobe mirrored through the surface
// (the light refracts only at the microfacets, so the walls' two refractions cancel), GGX with
// the height-correlated Smith term, and the sheet's two faces' Fresnel inter-reflections for each
// polarisation, T = ½ Σ (1 − R_x)/(1 + R_x), x = s, p (the extension's own sketch takes one face, 1 − R):
//   f_t(wo, wi) = T(wo·m) D(m) G(wo, wi') / (4 |cos θ_o| |cos θ_i|),  wi' = wi mirrored, m ∝ wo + wi'.
double thin_pane_btdf(const Vec3d& wo, const Vec3d& wi, double roughness, double eta) {
  const double a2 = sqr(sqr(roughness));
  const Vec3d mirrored(wi.x, wi.y, -wi.z), m = normalize(wo + mirrored);
  const double D = a2 / (kPi * sqr(m.z * m.z * (a2 - 1) + 1));
  const auto lambda = [&](const Vec3d& w) { return (std::sqrt(1 + a2 * (1 - w.z * w.z) / (w.z * w.z)) - 1) / 2; };
  const double G = 1 / (1 + lambda(wo) + lambda(mirrored));
  const double c = dot(wo, m), cos_t = std::sqrt(1 - (1 - c * c) / (eta * eta));
  const double Rs = sqr((c - eta * cos_t) / (c + eta * cos_t)), Rp = sqr((eta * c - cos_t) / (eta * c + cos_t));
  const double T = ((1 - Rs) / (1 + Rs) + (1 - Rp) / (1 + Rp)) / 2;
  return T * D * G / (4 * std::abs(wo.z * wi.z));
}

}  // namespace

TEST_CASE("lamp: a point light behind a rough thin-walled pane shows the transmitted lobe of the glTF definition") {
  // LightsPunctualLamp's shade is an open sheet of roughness 0.6 with transmission 1 and no
  // volume: glTF's thin wall. A point light 5 cm behind such a pane, seen through it straight on:
  // radiance f_t(wo, wi) I |cos θ_i| / d². (Blender 3.4's Cycles reads the sheet as the surface of
  // solid glass, refracting into index 1.5 without the 1/η² of leaving it: 16.6 times this at
  // the centre, and the lamp 15% to 40% brighter; tools/lamp_pane.py measures it.)
  constexpr double kRoughness = 0.6, kEta = 1.5, kDepth = 0.05;
  Scene scene;
  PbrMaterial pane = PbrMaterial::glass(Dielectric(ConstantIor{float(kEta)}, {}, true), float(kRoughness));
  pane.energy_compensation = false;  // the single-scattering lobe the definition gives
  scene.materials.push_back(Material{.name = "pane", .kind = pane});
  test::add_mesh(scene, test::make_quad({-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, 0));  // front = +Y, to the camera
  const Vec3f position(0, -float(kDepth), 0);
  const float I = 0.2f;
  scene.point_lights.push_back({"bulb", position, RgbIlluminantSpectrum(Rgb{I, I, I})});
  const auto radiance = [&](const Vec3f& p) {  // in the pane's frame (normal +z): y → z
    const Vec3d d = Vec3d(position - p), wi = normalize(Vec3d(d.x, d.z, d.y)), wo(0, 0, 1);
    return thin_pane_btdf(wo, wi, kRoughness, kEta) * I * std::abs(wi.z) / length_squared(d);
  };
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    check_radiance(scene, integrator, {-0.1f, -0.1f, 0.2f}, radiance, 16);  // the lobe's peak and its tails
    check_radiance(scene, integrator, {0.1f, -0.05f, 0.1f}, radiance);      // light arriving at 63°-73°
  }
}
