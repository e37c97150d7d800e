#pragma once
// The ray-scene queries of Prism: closest hit and any hit against triangle meshes placed by
// instances. Knows nothing of materials or spectra.
//
// Two levels where they pay: the instances of a mesh that no other instance uses are copied
// into one world-space BVH (the fastest to trace); a large mesh shared by several instances (or by
// copies of it: the same positions and indices bit for bit, under other materials) gets one BVH
// in its own space, and each of its instances enters the world BVH as a leaf of its own, which
// the ray crosses into the mesh's space through the instance's inverse transform (computed once
// where that costs little beside the trees, else on entry, so that millions of instances stay
// small; the instances' own array is read while tracing). Queries are
// exact functions of the geometry: the closest hit is the one with the smallest t, and among
// equally close ones the smallest global_prim, whatever the trees' shapes or visiting order. A
// ray's skip_instance, which it cannot meet (hull), is not entered; a ray that leaves the whole
// scene's convex hull (kEveryInstance) is not traced.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "accel/bvh.h"
#include "accel/triangle.h"
#include "core/base/instance.h"

namespace prism {

struct AccelMesh {
  std::span<const Vec3f> positions;   // object space
  std::span<const uint32_t> indices;  // three per triangle
};

using AccelInstance = Instance;

struct AccelOptions {
  bool flatten_instances = false;  // copy shared meshes into the world-space BVH too
  // A mesh used by several instances (or copies of it) gets a tree of its own where flattening them
  // would add at least this many triangles to the world tree: many copies of a large mesh then take
  // a fraction of the memory, and trace faster instanced. Below it a flat tree traces faster and
  // costs little memory.
  uint64_t instance_from = 1 << 16;
  // Test every triangle for every query, without the trees: the reference the tests hold the
  // BVH to, bit for bit (same triangles in the same spaces, same triangle test).
  bool brute_force = false;
};

struct AccelHit {
  float t;
  float b0, b1, b2;   // barycentrics of the triangle's three vertices
  uint32_t instance;  // index into the instances given at build time
  uint32_t prim;      // triangle index within the instance's mesh
  // The triangle's vertices in world space, as the accel tested them: a flattened triangle's as
  // it stored them, a shared mesh's transformed by its instance exactly as flattening does (in
  // double, rounded once). From the leaf block the ray just tested, so the shading point costs
  // no further look-up in the mesh's index and position buffers.
  std::array<Vec3f, 3> v;
};

class Accel {
 public:
  // Which triangles lie on the convex hull of a set of points (`on`, one per triangle; empty when
  // none do), and the points' centroid.
  struct Hull {
    Vec3f centroid;
    std::vector<uint8_t> on;
  };
  // A triangle on a convex hull, seen from where a ray leaves it: the hull's centroid in world space
  // (on the hull's side of the triangle's plane), and what a ray leaving the triangle to the other
  // side cannot meet (Ray::skip_instance).
  struct HullSide {
    Vec3f centroid;
    uint32_t skip;
  };

  Accel() = default;
  // `instances` must outlive the Accel: tracing reads the transforms of shared meshes' instances.
  Accel(std::span<const AccelMesh> meshes, std::span<const AccelInstance> instances, const AccelOptions& options = {});

  bool intersect(const Ray& ray, AccelHit& hit) const;  // closest hit with 0 < t < ray.tmax
  bool occluded(const Ray& ray) const;                  // any hit with 0 < t < ray.tmax
  // Whether a ray inside the region may hit anything: false only if every triangle (in the world
  // tree, or in a shared mesh's tree seen through each instance) lies outside one of the region's
  // planes, by more than its margin.
  bool may_meet(const Frustum& region) const;

  // Triangles numbered instance by instance, each instance's triangles in mesh order.
  uint32_t global_prim(const AccelHit& hit) const { return first_prim_[hit.instance] + hit.prim; }
  size_t triangle_count() const { return triangle_count_; }
  size_t memory_bytes() const;
  Bounds3f bounds() const { return world_.bvh.bounds(); }
  // Whether a triangle lies on a convex hull a ray leaving it outwards cannot meet again: that of
  // its instance's mesh, for an instance with a tree of its own (the ray skips the instance), or
  // that of the whole scene, for a triangle of the world tree (the ray meets nothing:
  // kEveryInstance).
  std::optional<HullSide> hull(uint32_t instance, uint32_t prim) const {
    const int tree = tree_of_mesh_[instances_[instance].mesh];
    if (tree < 0) {
      if (world_hull_.on.empty() || !world_hull_.on[world_first_[instance] + prim]) return std::nullopt;
      return HullSide{world_hull_.centroid, kEveryInstance};
    }
    if (hulls_[tree].on.empty() || !hulls_[tree].on[prim]) return std::nullopt;
    return HullSide{instances_[instance].to_world.point_rounded(hulls_[tree].centroid), instance};
  }

 private:
  static constexpr uint32_t kWorld = 0xFFFFFFFF;  // "instance" of triangles in the world tree
  // A BVH whose leaves are blocks of triangles; `id`s are global triangle numbers in the world
  // tree and triangle numbers within the mesh in a mesh's tree. The world tree's solo leaves
  // are its instances of shared meshes, numbered as the instances.
  struct TriangleTree {
    Bvh bvh;
    std::vector<TriangleBlock, HugePageAllocator<TriangleBlock>> blocks;
    TriangleTree() = default;
    // `bounds`: one box per triangle (filled here), then the solo leaves' boxes (the caller's).
    TriangleTree(const std::vector<std::array<Vec3f, 3>>& triangles, std::span<const uint32_t> ids,
                 std::vector<Bounds3f> bounds = {});
    size_t memory_bytes() const { return bvh.memory_bytes() + blocks.size() * sizeof(TriangleBlock); }
  };
  struct Closest;
  template <bool AnyHit>
  bool trace(const Ray& ray, Closest& closest) const;
  template <bool AnyHit>
  bool test_blocks(const TriangleTree& tree, uint32_t first, uint32_t count, uint32_t instance,
                   const WatertightRay& ray, Closest& closest) const;

  TriangleTree world_;
  std::vector<TriangleTree> mesh_trees_;
  std::vector<Hull> hulls_;            // per mesh tree, in the mesh's space
  Hull world_hull_;                    // the whole scene's, over the world tree's triangles (world space)
  std::vector<uint32_t> world_first_;  // per instance, its first triangle in world_hull_ (kept with it)
  std::span<const Instance> instances_;
  // Per instance, the inverse of its transform if its mesh is shared (all zeros when singular);
  // empty without shared meshes, or when the inverses would cost more than an eighth of the trees
  // (a forest of instances: Accel::trace then inverts on entering an instance).
  std::vector<Transform> to_object_;
  std::vector<int> tree_of_mesh_;  // into mesh_trees_, or −1 for a mesh flattened into world_
  std::vector<uint32_t> first_prim_;
  size_t triangle_count_ = 0;
  float t_slack_ = 0;  // how far beyond the closest hit so far a box is still entered (Bvh::traverse)
  bool brute_force_ = false;
};

}  // namespace prism
