#pragma once
// The scene made ready to render: the acceleration structure over its instances, the lights
// (one AreaLight per emissive triangle, point lights, environment) with their power sampler,
// and the surface queries the integrators call.

#include <optional>
#include <vector>

#include "accel/accel.h"
#include "render/interaction.h"
#include "render/light_sampler.h"
#include "render/lights.h"
#include "scene/scene.h"
#include "scene/scene_features.h"

namespace prism {

// The acceleration structure over the scene's instances, as World uses it.
Accel build_accel(const Scene& scene, const AccelOptions& options = {});

class World {
 public:
  explicit World(const Scene& scene, const AccelOptions& accel = {});

  std::optional<SurfaceInteraction> intersect(const Ray& ray) const;
  bool occluded(const Ray& ray) const { return accel_.occluded(ray); }

  const Scene& scene() const { return scene_; }
  const SceneFeatures& features() const { return features_; }
  const Accel& accel() const { return accel_; }
  const std::vector<Light>& lights() const { return lights_; }
  const PowerLightSampler& light_sampler() const { return light_sampler_; }

  // The area light of an emissive triangle, or -1.
  int area_light(uint32_t instance, uint32_t prim) const {
    const int base = instance_light_base_[instance];
    return base < 0 ? -1 : base + int(prim);
  }
  int environment_light() const { return environment_light_; }
  const EnvironmentLight* environment() const {
    return environment_light_ < 0 ? nullptr : &std::get<EnvironmentLight>(lights_[environment_light_]);
  }

 private:
  struct InstanceData {
    const Mesh* mesh;
    const Transform* to_world;
    float normal_matrix[3][3];  // inverse transpose of the linear part
    bool mirrored;              // negative determinant: winding (and so the front side) flips
  };
  std::array<Vec3f, 3> world_vertices(const InstanceData& inst, uint32_t prim) const;
  void add_lights();

  const Scene& scene_;
  SceneFeatures features_;
  std::vector<InstanceData> instances_;
  Accel accel_;
  std::vector<Light> lights_;
  std::vector<int> instance_light_base_;
  int environment_light_ = -1;
  PowerLightSampler light_sampler_;
};

}  // namespace prism
