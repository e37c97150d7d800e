#pragma once
// What a scene actually uses, found once after loading. The renderer builds and runs only what
// these features require; the set is logged and written into the EXR metadata.

#include <string>

#include "core/scene/scene.h"

namespace prism {

struct SceneFeatures {
  bool emissive_triangles = false;
  bool point_lights = false;
  bool spot_lights = false;
  bool directional_lights = false;
  bool environment = false;         // constant radiance
  bool environment_map = false;     // an equirectangular image
  bool dielectric_volumes = false;  // closed transmissive dielectrics: paths enter and leave them
  bool dispersion = false;          // a dielectric whose index varies with wavelength
  bool absorption = false;          // a closed dielectric volume with Beer–Lambert absorption
  bool scattering = false;          // a medium that scatters light (in a closed dielectric or around them all)
  bool scene_medium = false;        // a medium around the closed dielectrics (fog)
  bool measured_metals = false;     // a metal with catalogue n, k tables
  bool textures = false;            // a material reads an image
  bool alpha = false;               // a material is cut away by alpha (MASK or BLEND)
  bool layers =
      false;  // clearcoat, sheen, thin film, diffuse transmission or specular colour (LayeredBsdf, per-lane F)

  std::string to_string() const;  // e.g. "emissive_triangles point_lights"
};

SceneFeatures analyze_features(const Scene& scene);

}  // namespace prism
