#pragma once
// The scene made ready to render: the acceleration structure over its instances, the lights
// (one AreaLight per emissive triangle, punctual lights, environment) with the sampler that
// chooses among them, and the surface queries the integrators call.

#include <memory>
#include <optional>
#include <vector>

#include "accel/accel.h"
#include "core/render/interaction.h"
#include "core/render/light_sampler.h"
#include "core/render/lights.h"
#include "core/render/power_light_sampler.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"

namespace prism {

// The acceleration structure over the scene's instances, as World uses it.
Accel build_accel(const Scene& scene, const AccelOptions& options = {});

class World {
 public:
  explicit World(const Scene& scene, const AccelOptions& accel = {},
                 LightSamplerKind light_sampler = kDefaultLightSampler);

  // The first surface along the ray that is not cut away by its material's alpha (glTF MASK
  // and BLEND; BLEND decided stochastically by a hash of the ray, pbrt-v4 style). With
  // `keep_blend`, BLEND surfaces are returned whole: the caller weighs them by Material::blend_opacity.
  std::optional<SurfaceInteraction> intersect(const Ray& ray, bool keep_blend = false) const;
  // Moves `ray` on past the surface it hit at si (the same line, from just beyond that surface);
  // returns how far its origin moved.
  static float step_beyond(const SurfaceInteraction& si, Ray& ray);
  bool occluded(const Ray& ray) const { return features_.alpha ? intersect(ray).has_value() : accel_.occluded(ray); }
  // The fraction of light that gets through along `ray`: 0 if an opaque surface blocks it, else the
  // product of 1 − alpha of the BLEND surfaces it crosses (MASK cut-outs pass it whole). The
  // expectation of `occluded`'s stochastic answer, for shadow rays (Cycles' transparent shadows).
  float transmittance(const Ray& ray) const;
  // Whether a ray leaving si surely meets si's own surface again: the mesh is closed and light
  // passes through it (enclosed_side, accel/closed_surface.h), the ray leaves into the volume it
  // encloses (by more than the margin SurfaceInteraction::skip_towards keeps), and it ends beyond
  // the instance's bounds, so it leaves that volume on the way (infinitely far: always). A shadow
  // ray into a closed translucent object, towards a light outside it, is blocked without being traced.
  bool meets_own_surface(const SurfaceInteraction& si, const Ray& ray) const {
    if (enclosures_.empty()) return false;
    const Enclosure& e = enclosures_[si.instance];
    // (Side 0 answered before the ray is read: it is mostly the light sample just made.)
    return e.side != 0 && dot(ray.d, si.n) * e.side > 1e-4f && !e.bounds.inside(ray.o + ray.d * ray.tmax);
  }

  const Scene& scene() const { return scene_; }
  const SceneFeatures& features() const { return features_; }
  const Accel& accel() const { return accel_; }
  const std::vector<Light>& lights() const { return lights_; }
  const LightSampler& light_sampler() const { return light_sampler_; }
  // Delta (point, spot, directional) lights, and a power sampler over the other lights (for
  // Whitted-style direct light).
  const std::vector<uint32_t>& delta_lights() const { return delta_lights_; }
  const std::vector<uint32_t>& area_lights() const { return area_lights_; }
  const PowerLightSampler& area_light_sampler() const { return area_light_sampler_; }

  // The area light of an emissive triangle, or -1.
  int area_light(uint32_t instance, uint32_t prim) const {
    const int base = instance_light_base_[instance];
    return base < 0 ? -1 : base + int(prim);
  }
  // The environment (an EnvironmentLight or EnvironmentMapLight; see environment_Le), or null.
  int environment_light() const { return environment_light_; }
  const Light* environment() const { return environment_light_ < 0 ? nullptr : &lights_[environment_light_]; }
  // The medium around the closed dielectrics (the scene's fog), or null for vacuum.
  const Medium* scene_medium() const { return scene_.medium ? &*scene_.medium : nullptr; }

 private:
  std::array<Vec3f, 3> world_vertices(const Instance& inst, uint32_t prim) const;
  // A hit's point, geometric normal, material and texture coordinates (what alpha needs), then its
  // shading normal and tangent (interpolated, normal-mapped): only for the surfaces not cut away.
  // Both fill `si` in place (see intersect), surface_point a freshly made one.
  void surface_point(const Ray& ray, const AccelHit& hit, SurfaceInteraction& si) const;
  void shade(SurfaceInteraction& si, const AccelHit& hit) const;
  bool cut_away(const SurfaceInteraction& si, const Ray& ray, bool keep_blend) const;
  void add_enclosures();
  std::vector<std::vector<float>> add_texels();
  void add_lights(LightSamplerKind light_sampler);

  const Scene& scene_;
  SceneFeatures features_;
  Accel accel_;
  std::vector<Light> lights_;
  std::vector<int> instance_light_base_;
  // Per instance, what every hit on it needs of its transform: whether it mirrors (flipping the
  // winding, and so the front side), and the cofactor matrix that carries normals.
  struct InstanceNormals {
    bool mirrored;
    std::array<Vec3f, 3> cofactor;
  };
  std::vector<InstanceNormals> instance_normals_;
  // Per instance, for meets_own_surface: the side of its triangles' normals on which its mesh's
  // volume lies (−1 or +1; 0 for a mesh that is not closed, or that light does not pass) and its
  // world-space bounds. Empty where no instance has such a mesh.
  struct Enclosure {
    Bounds3f bounds;
    float side = 0;
  };
  std::vector<Enclosure> enclosures_;
  // Per mesh, the mesh a hit on it reads indices and vertex attributes from: the first with the very
  // same ones. glTF primitives that share accessors but not materials load as copies (a grid of
  // spheres that differ only in material); shading them from one copy keeps what a hit reads in
  // cache.
  std::vector<const Mesh*> attribute_mesh_;
  int environment_light_ = -1;
  std::unique_ptr<const EnvironmentMap> environment_map_;
  std::unique_ptr<const Spectrum> environment_radiance_;  // the constant environment, tabulated per nm
  std::vector<std::optional<ConstantSpectra>> spectra_;   // per material (SurfacePoint)
  // Per mesh of a textured emitter, per triangle: the distribution of its points by their light,
  // or null (add_texels).
  std::vector<std::vector<std::unique_ptr<const TexturedEmission>>> texels_;
  LightSampler light_sampler_;
  std::vector<uint32_t> delta_lights_, area_lights_;
  PowerLightSampler area_light_sampler_;
};

}  // namespace prism
