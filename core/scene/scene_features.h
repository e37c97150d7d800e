#pragma once
// What a scene actually uses, found once after loading. The renderer builds and runs only what
// these features require; the set is logged and written into the EXR metadata.

#include <string>

#include "scene/scene.h"

namespace prism {

struct SceneFeatures {
  bool emissive_triangles = false;
  bool point_lights = false;
  bool environment = false;

  std::string to_string() const;  // e.g. "emissive_triangles point_lights"
};

SceneFeatures analyze_features(const Scene& scene);

}  // namespace prism
