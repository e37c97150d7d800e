#include "scene/scene.h"

namespace prism {

Bounds3f Scene::world_bounds() const {
  Bounds3f b;
  for (const Instance& inst : instances)
    for (const Vec3f& p : meshes[inst.mesh].positions) b.extend(Vec3f(inst.to_world.point(Vec3d(p))));
  for (const PointLight& l : point_lights) b.extend(l.position);
  for (const SpotLight& l : spot_lights) b.extend(l.position);
  return b;
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Instance& inst : instances) n += meshes[inst.mesh].indices.size() / 3;
  return n;
}

}  // namespace prism
