#include "render/world.h"

#include "accel/triangle.h"
#include "spectral/cie.h"

namespace prism {

Accel build_accel(const Scene& scene, const AccelOptions& options) {
  std::vector<AccelMesh> meshes;
  for (const Mesh& m : scene.meshes) meshes.push_back({m.positions, m.indices});
  std::vector<AccelInstance> instances;
  for (const Instance& inst : scene.instances) instances.push_back({inst.mesh, inst.to_world});
  return Accel(meshes, instances, options);
}

World::World(const Scene& scene, const AccelOptions& accel)
    : scene_(scene), features_(analyze_features(scene)), accel_(build_accel(scene, accel)) {
  for (const Instance& inst : scene.instances) {
    InstanceData d{&scene.meshes[inst.mesh], &inst.to_world, {}, determinant3x3(inst.to_world) < 0};
    const Transform inv_t = transpose(inverse(inst.to_world));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) d.normal_matrix[r][c] = float(inv_t.m[r][c]);
    instances_.push_back(d);
  }
  add_lights();
}

// Transformed exactly as the accel transforms the triangles it flattens into world space, so the
// shading point lies on the very triangle the ray hit. (A hit on an instanced mesh is found in
// the mesh's space; its barycentrics carry over, as the transform is affine.)
std::array<Vec3f, 3> World::world_vertices(const InstanceData& inst, uint32_t prim) const {
  const Mesh& m = *inst.mesh;
  std::array<Vec3f, 3> v;
  for (int k = 0; k < 3; ++k) v[k] = Vec3f(inst.to_world->point(Vec3d(m.positions[m.indices[3 * prim + k]])));
  return v;
}

void World::add_lights() {
  std::vector<float> powers;
  instance_light_base_.assign(instances_.size(), -1);
  for (uint32_t i = 0; i < instances_.size(); ++i) {
    const Material& material = scene_.materials[instances_[i].mesh->material];
    if (!material.emission) continue;
    const float luminance = spectrum_to_xyz(*material.emission).y;
    instance_light_base_[i] = int(lights_.size());
    for (uint32_t p = 0; p < instances_[i].mesh->indices.size() / 3; ++p) {
      const auto v = world_vertices(instances_[i], p);
      const float area = triangle_area(v[0], v[1], v[2]);
      const Vec3f n = triangle_normal(v[0], v[1], v[2]) * (instances_[i].mirrored ? -1.f : 1.f);
      lights_.push_back(AreaLight{v[0], v[1], v[2], n, area, &*material.emission, material.double_sided});
      // Φ = π · A · L for a one-sided Lambertian emitter; luminance stands in for L.
      powers.push_back(area > 0 ? kPi * area * luminance * (material.double_sided ? 2.f : 1.f) : 0.f);
    }
  }
  for (const PointLight& pl : scene_.point_lights) {
    lights_.push_back(PointLightSource{pl.position, &pl.intensity});
    powers.push_back(4 * kPi * spectrum_to_xyz(pl.intensity).y);  // Φ = 4π I
  }
  if (scene_.environment) {
    environment_light_ = int(lights_.size());
    lights_.push_back(EnvironmentLight{&*scene_.environment});
    // Φ = π r² · 4π · L: the power a sphere bounding the scene receives (pbrt-v4 §12.5.1).
    const Bounds3f b = accel_.bounds();
    const float r = b.empty() ? 1.f : 0.5f * length(b.diagonal());
    powers.push_back(4 * kPi * kPi * r * r * spectrum_to_xyz(*scene_.environment).y);
  }
  light_sampler_ = PowerLightSampler(powers);
}

std::optional<SurfaceInteraction> World::intersect(const Ray& ray) const {
  AccelHit hit;
  if (!accel_.intersect(ray, hit)) return std::nullopt;
  const InstanceData& inst = instances_[hit.instance];
  const auto v = world_vertices(inst, hit.prim);
  SurfaceInteraction si;
  si.p = v[0] * hit.b0 + v[1] * hit.b1 + v[2] * hit.b2;
  si.p_error = (abs(v[0] * hit.b0) + abs(v[1] * hit.b1) + abs(v[2] * hit.b2)) * gamma(7);
  si.n = triangle_normal(v[0], v[1], v[2]) * (inst.mirrored ? -1.f : 1.f);
  si.ns = si.n;
  const Mesh& m = *inst.mesh;
  if (!m.normals.empty()) {
    Vec3f ns_obj(0, 0, 0);
    const float b[3] = {hit.b0, hit.b1, hit.b2};
    for (int k = 0; k < 3; ++k) ns_obj += m.normals[m.indices[3 * hit.prim + k]] * b[k];
    const auto& nm = inst.normal_matrix;
    const Vec3f ns(nm[0][0] * ns_obj.x + nm[0][1] * ns_obj.y + nm[0][2] * ns_obj.z,
                   nm[1][0] * ns_obj.x + nm[1][1] * ns_obj.y + nm[1][2] * ns_obj.z,
                   nm[2][0] * ns_obj.x + nm[2][1] * ns_obj.y + nm[2][2] * ns_obj.z);
    const float len = length(ns);
    // The shading normal is taken on the geometric normal's side; a zero one falls back to it.
    if (len > 0 && std::isfinite(len)) si.ns = face_forward(ns / len, si.n);
  }
  si.wo = -ray.d;
  si.t = hit.t;
  si.material = &scene_.materials[m.material];
  si.instance = hit.instance;
  si.prim = hit.prim;
  return si;
}

}  // namespace prism
