#include "scene/scene_features.h"

namespace prism {

SceneFeatures analyze_features(const Scene& scene) {
  SceneFeatures f;
  for (const Instance& inst : scene.instances)
    if (scene.materials[scene.meshes[inst.mesh].material].emission) f.emissive_triangles = true;
  f.point_lights = !scene.point_lights.empty();
  f.environment = scene.environment.has_value();
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
  add(environment, "environment");
  return s.empty() ? "none" : s;
}

}  // namespace prism
