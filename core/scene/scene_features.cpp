#include "core/scene/scene_features.h"

namespace prism {

SceneFeatures analyze_features(const Scene& scene) {
  SceneFeatures f;
  for (const Instance& inst : scene.instances) {
    const Material& m = scene.materials[scene.meshes[inst.mesh].material];
    f.emissive_triangles |= m.emission.has_value();
    if (const auto* d = m.dielectric()) {
      f.dielectric_volumes |= !d->thin_walled;
      f.dispersion |= d->dispersive;
      f.absorption |= d->interior.absorbs() && !d->thin_walled;
      f.scattering |= d->interior.scatters() && !d->thin_walled;
    }
    f.textures |= m.normal_texture || m.emission_texture;
    if (const auto* p = std::get_if<PbrMaterial>(&m.kind)) {
      f.measured_metals |= p->metal && p->metallic > 0;
      f.textures |= p->textured() || (p->clearcoat && p->clearcoat->normal_texture);
      f.layers |= p->layered();
    }
    f.alpha |= m.alpha_mode != AlphaMode::opaque;
  }
  f.point_lights = !scene.point_lights.empty();
  f.spot_lights = !scene.spot_lights.empty();
  f.directional_lights = !scene.directional_lights.empty();
  f.environment = scene.environment.has_value();
  f.environment_map = scene.environment_map.has_value();
  f.scene_medium = scene.medium && !scene.medium->empty();
  f.scattering |= scene.medium && scene.medium->scatters();
  return f;
}

std::string SceneFeatures::to_string() const {
  std::string s;
  const auto add = [&s](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += ' ';
    s += name;
  };
  add(emissive_triangles, "emissive_triangles");
  add(point_lights, "point_lights");
  add(spot_lights, "spot_lights");
  add(directional_lights, "directional_lights");
  add(environment, "environment");
  add(environment_map, "environment_map");
  add(dielectric_volumes, "dielectric_volumes");
  add(dispersion, "dispersion");
  add(absorption, "absorption");
  add(scattering, "scattering");
  add(scene_medium, "scene_medium");
  add(measured_metals, "measured_metals");
  add(textures, "textures");
  add(alpha, "alpha");
  add(layers, "layers");
  return s.empty() ? "none" : s;
}

}  // namespace prism
