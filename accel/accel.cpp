#include "accel/accel.h"

#include "accel/triangle.h"

namespace prism {

Accel::Accel(std::span<const AccelMesh> meshes, std::span<const AccelInstance> instances) {
  // Flatten every instance into world space (vertices transformed in double, rounded once).
  std::vector<Triangle> tris;
  first_prim_.reserve(instances.size());
  for (uint32_t i = 0; i < instances.size(); ++i) {
    first_prim_.push_back(uint32_t(tris.size()));
    const AccelMesh& mesh = meshes[instances[i].mesh];
    const Transform& m = instances[i].to_world;
    for (uint32_t p = 0; p < mesh.indices.size() / 3; ++p) {
      Vec3f v[3];
      for (int k = 0; k < 3; ++k) v[k] = Vec3f(m.point(Vec3d(mesh.positions[mesh.indices[3 * p + k]])));
      tris.push_back({v[0], v[1], v[2], i, p});
    }
  }
  std::vector<Bounds3f> bounds(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    bounds[i].extend(tris[i].v0);
    bounds[i].extend(tris[i].v1);
    bounds[i].extend(tris[i].v2);
    // A triangle with zero area can never be hit; leave it out of the tree.
    if (triangle_area(tris[i].v0, tris[i].v1, tris[i].v2) == 0.f) bounds[i] = Bounds3f{};
  }
  bvh_ = Bvh::build(bounds);
  triangles_.reserve(bvh_.prim_order().size());
  for (uint32_t p : bvh_.prim_order()) triangles_.push_back(tris[p]);
}

bool Accel::intersect(const Ray& ray, AccelHit& hit) const {
  const WatertightRay wr(ray);
  float tmax = ray.tmax;
  return bvh_.traverse<false>(ray, tmax, [&](uint32_t i, float& t) {
    const Triangle& tri = triangles_[i];
    TriangleHit th;
    if (!intersect_triangle(wr, tri.v0, tri.v1, tri.v2, t, th)) return false;
    t = th.t;
    hit = {th.t, th.b0, th.b1, th.b2, tri.instance, tri.prim};
    return true;
  });
}

bool Accel::occluded(const Ray& ray) const {
  const WatertightRay wr(ray);
  float tmax = ray.tmax;
  return bvh_.traverse<true>(ray, tmax, [&](uint32_t i, float& t) {
    const Triangle& tri = triangles_[i];
    TriangleHit th;
    return intersect_triangle(wr, tri.v0, tri.v1, tri.v2, t, th);
  });
}

size_t Accel::memory_bytes() const {
  return bvh_.nodes().size() * sizeof(BvhNode) + triangles_.size() * sizeof(Triangle) +
         bvh_.prim_order().size() * sizeof(uint32_t) + first_prim_.size() * sizeof(uint32_t);
}

}  // namespace prism
