#pragma once
// The ray-scene queries of Prism: closest hit and any hit against triangle meshes placed by
// instances. Knows nothing of materials or spectra.

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh.h"
#include "base/transform.h"

namespace prism {

struct AccelMesh {
  std::span<const Vec3f> positions;    // object space
  std::span<const uint32_t> indices;   // three per triangle
};

struct AccelInstance {
  uint32_t mesh;
  Transform to_world;
};

struct AccelHit {
  float t;
  float b0, b1, b2;   // barycentrics of the triangle's three vertices
  uint32_t instance;  // index into the instances given at build time
  uint32_t prim;      // triangle index within the instance's mesh
};

class Accel {
 public:
  Accel() = default;
  Accel(std::span<const AccelMesh> meshes, std::span<const AccelInstance> instances);

  bool intersect(const Ray& ray, AccelHit& hit) const;  // closest hit with t < ray.tmax
  bool occluded(const Ray& ray) const;                  // any hit with t < ray.tmax

  // Triangles numbered instance by instance, each instance's triangles in mesh order.
  uint32_t global_prim(const AccelHit& hit) const { return first_prim_[hit.instance] + hit.prim; }
  size_t triangle_count() const { return triangles_.size(); }
  size_t memory_bytes() const;
  Bounds3f bounds() const { return bvh_.bounds(); }

 private:
  struct Triangle {
    Vec3f v0, v1, v2;  // world space
    uint32_t instance, prim;
  };
  Bvh bvh_;
  std::vector<Triangle> triangles_;  // in BVH leaf order
  std::vector<uint32_t> first_prim_;
};

}  // namespace prism
