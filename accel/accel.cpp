#include "accel/accel.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>

#include "accel/bvh_traverse.h"
#include "core/base/first_equal.h"

namespace prism {

namespace {

using Triangle = std::array<Vec3f, 3>;

// A triangle with zero area, or beyond float range, can never be hit; it stays out of the trees.
bool hittable(const Triangle& v) {
  const float area = triangle_area(v[0], v[1], v[2]);
  return area > 0.f && std::isfinite(area);
}

// Which triangles lie on the boundary of the points' convex hull: every point on one side of the
// triangle's plane or on it (within 10⁻¹² of the points' extent, this test's own rounding), so that
// a ray leaving the triangle to the other side cannot meet any of them; and the points' centroid,
// on their side of each. `vertex(t, k)` is vertex k of triangle t. Empty where none does, and
// unchecked where triangles × points exceed kHullWork (a few tenths of a second for a convex body;
// a triangle that is not on the hull mostly stops at the first block of points, the extreme ones).
constexpr double kHullWork = 0x1p28;
template <typename Vertex>
Accel::Hull hull_of(std::span<const Vec3f> points, size_t triangles, const Vertex& vertex) {
  const size_t count = points.size();
  if (triangles == 0 || double(triangles) * double(count) > kHullWork) return {};
  Bounds3f box;
  Vec3d sum(0, 0, 0);
  std::vector<double> x(count), y(count), z(count);  // apart, so that the test below runs as vector code
  for (size_t i = 0; i < count; ++i) {
    const Vec3f& v = points[i];
    box.extend(v), sum += Vec3d(v);
    x[i] = v.x, y[i] = v.y, z[i] = v.z;
  }
  // The extreme points along the 26 directions of a cube's faces, edges and corners first: most
  // triangles that are not on the hull have one of them in front.
  size_t front_count = 0;
  for (int d = 0; d < 27; ++d) {
    if (d == 13) continue;  // (0, 0, 0)
    const Vec3d dir(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
    size_t best = front_count;
    for (size_t i = front_count; i < count; ++i)
      if (x[i] * dir.x + y[i] * dir.y + z[i] * dir.z > x[best] * dir.x + y[best] * dir.y + z[best] * dir.z) best = i;
    if (best < count)
      std::swap(x[front_count], x[best]), std::swap(y[front_count], y[best]), std::swap(z[front_count], z[best]),
          ++front_count;
  }
  const double tolerance = 1e-12 * length(Vec3d(box.hi - box.lo));
  if (!std::isfinite(tolerance)) return {};  // points rounded to infinity (a huge transform): no side is sure
  Accel::Hull hull{Vec3f(sum / double(count)), std::vector<uint8_t>(triangles, 0)};
  const double *px = x.data(), *py = y.data(), *pz = z.data();
  tbb::parallel_for(size_t(0), triangles, [&](size_t t) {
    const Vec3d a(vertex(t, 0)), b(vertex(t, 1)), c(vertex(t, 2));
    const Vec3d normal = cross(b - a, c - a);
    const double area2 = length(normal);
    if (!(area2 > 0) || !std::isfinite(area2)) return;  // a degenerate triangle: never hit
    const Vec3d n = normal / area2;
    int front = 0, behind = 0;  // (ints, not a min and a max: GCC makes vector code of these alone)
    for (size_t first = 0, end = std::min<size_t>(32, count); first < count && !(front && behind);
         first = end, end = std::min(end + 1024, count))
      for (size_t i = first; i < end; ++i) {
        const double side = (px[i] - a.x) * n.x + (py[i] - a.y) * n.y + (pz[i] - a.z) * n.z;
        front |= side > tolerance, behind |= side < -tolerance;
      }
    hull.on[t] = !(front && behind);
  });
  return std::ranges::any_of(hull.on, [](uint8_t on) { return on != 0; }) ? hull : Accel::Hull{};
}

Accel::Hull hull_of(const AccelMesh& mesh) {
  return hull_of(mesh.positions, mesh.indices.size() / 3,
                 [&](size_t t, int k) { return mesh.positions[mesh.indices[3 * t + k]]; });
}

// A ray's watertight triangle set-up (three divisions), made when it first meets a leaf: most rays
// of an instanced scene meet none in the world tree, and the camera rays of a small scene mostly
// miss it.
class LazyWatertightRay {
 public:
  explicit LazyWatertightRay(const Ray& ray) : ray_(ray) {}
  const WatertightRay& operator*() {
    if (!set_up_) set_up_.emplace(ray_);
    return *set_up_;
  }

 private:
  const Ray& ray_;
  std::optional<WatertightRay> set_up_;
};

// Bit l: lane l holds a triangle whose vertices are not all outside one of the region's planes.
uint32_t triangles_meeting(const TriangleBlock& block, const BvhFrustum& region) {
  const auto& v = block.v;
  uint32_t mask = simd::bits(v[0][0] == v[0][0]);  // the lanes in use (the others are NaN)
  for (int i = 0; i < region.count; ++i) {
    const auto outside = [&](int k) {
      return region.n[i][0] * v[k][0] + region.n[i][1] * v[k][1] + region.n[i][2] * v[k][2] > region.limit[i];
    };
    mask &= ~simd::bits(outside(0) & outside(1) & outside(2));
  }
  return mask;
}

}  // namespace

Accel::TriangleTree::TriangleTree(const std::vector<Triangle>& triangles, std::span<const uint32_t> ids,
                                  std::vector<Bounds3f> bounds) {
  if (bounds.empty()) bounds.resize(triangles.size());
  tbb::parallel_for(size_t(0), triangles.size(), [&](size_t i) {
    if (!hittable(triangles[i])) return;
    for (const Vec3f& v : triangles[i]) bounds[i].extend(v);
  });
  std::vector<uint32_t> slots;
  bvh = Bvh::build(bounds, {.block_size = TriangleBlock::kLanes, .first_solo = uint32_t(triangles.size())}, slots);
  blocks.resize(slots.size() / TriangleBlock::kLanes);
  tbb::parallel_for(size_t(0), blocks.size(), [&](size_t b) {
    for (int lane = 0; lane < TriangleBlock::kLanes; ++lane) {
      const uint32_t s = slots[b * TriangleBlock::kLanes + lane];
      if (s != Bvh::kEmptySlot) blocks[b].set(lane, triangles[s][0], triangles[s][1], triangles[s][2], ids[s]);
    }
  });
}

Accel::Accel(std::span<const AccelMesh> meshes, std::span<const AccelInstance> instances, const AccelOptions& options)
    : instances_(instances), brute_force_(options.brute_force) {
  const auto triangles_of = [&](uint32_t mesh) { return uint32_t(meshes[mesh].indices.size() / 3); };
  // A mesh and its copies (the same positions and indices bit for bit, under other materials: a
  // glTF mesh per material over the same accessors) are one geometry, counted at its first mesh.
  // It gets a tree of its own where its instances would add options.instance_from triangles or
  // more to the world tree (see AccelOptions); otherwise they are flattened.
  const std::vector<uint32_t> geometry = first_equal(
      uint32_t(meshes.size()), [&](uint32_t m) { return hash_bytes(meshes[m].positions, meshes[m].indices); },
      [&](uint32_t a, uint32_t b) {
        return same_bytes(meshes[a].positions, meshes[b].positions) && same_bytes(meshes[a].indices, meshes[b].indices);
      });
  std::vector<uint32_t> users(meshes.size(), 0);
  for (const AccelInstance& inst : instances) ++users[geometry[inst.mesh]];
  const auto own_tree = [&](uint32_t g) {
    return !options.flatten_instances && users[g] > 1 &&
           uint64_t(triangles_of(g)) * (users[g] - 1) >= options.instance_from;
  };
  const auto shared = [&](const AccelInstance& inst) { return own_tree(geometry[inst.mesh]); };

  // Every vertex and triangle of the unshared instances, in world space, triangles numbered globally.
  // Vertices are transformed in double and rounded once (as World computes hit points from them);
  // they are also the scene hull's points, below.
  std::vector<uint32_t> world_first(instances.size());
  std::vector<size_t> point_first(instances.size());
  size_t world_count = 0, point_count = 0;
  for (uint32_t i = 0; i < instances.size(); ++i) {
    first_prim_.push_back(uint32_t(triangle_count_));
    triangle_count_ += triangles_of(instances[i].mesh);
    world_first[i] = uint32_t(world_count), point_first[i] = point_count;
    if (!shared(instances[i]))
      world_count += triangles_of(instances[i].mesh), point_count += meshes[instances[i].mesh].positions.size();
  }
  std::vector<Vec3f> world_points(point_count);
  std::vector<Triangle> world_triangles(world_count);
  std::vector<uint32_t> world_ids(world_count);
  tbb::parallel_for(size_t(0), instances.size(), [&](size_t i) {
    if (shared(instances[i])) return;
    const AccelMesh& mesh = meshes[instances[i].mesh];
    Vec3f* points = world_points.data() + point_first[i];
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      points[v] = instances[i].to_world.point_rounded(mesh.positions[v]);
    for (uint32_t p = 0; p < triangles_of(instances[i].mesh); ++p) {
      for (int k = 0; k < 3; ++k) world_triangles[world_first[i] + p][k] = points[mesh.indices[3 * p + k]];
      world_ids[world_first[i] + p] = first_prim_[i] + p;
    }
  });

  // One tree per shared mesh, in object space; each instance of it a solo leaf of the world tree,
  // numbered as the instance.
  tree_of_mesh_.assign(meshes.size(), -1);
  std::vector<Bounds3f> bounds(world_count + instances.size());  // the world tree's triangles, then solos
  for (uint32_t mesh = 0; mesh < meshes.size(); ++mesh) {
    if (!own_tree(geometry[mesh])) continue;
    if (geometry[mesh] != mesh) {  // a copy: its first mesh's tree
      tree_of_mesh_[mesh] = tree_of_mesh_[geometry[mesh]];
      continue;
    }
    tree_of_mesh_[mesh] = int(mesh_trees_.size());
    std::vector<Triangle> triangles(triangles_of(mesh));
    std::vector<uint32_t> ids(triangles.size());
    for (uint32_t p = 0; p < triangles.size(); ++p) {
      for (int k = 0; k < 3; ++k) triangles[p][k] = meshes[mesh].positions[meshes[mesh].indices[3 * p + k]];
      ids[p] = p;
    }
    mesh_trees_.emplace_back(triangles, ids);
    hulls_.push_back(hull_of(meshes[mesh]));
  }
  tbb::parallel_for(size_t(0), instances.size(), [&](size_t i) {
    if (!shared(instances[i])) return;
    const Bvh& tree = mesh_trees_[tree_of_mesh_[instances[i].mesh]].bvh;
    if (!tree.empty()) bounds[world_count + i] = transform_bounds(instances[i].to_world, tree.bounds());
  });
  // The whole scene's convex hull, for the world tree's triangles: the points are their vertices and
  // the corners of the shared meshes' instances' boxes. A ray leaving a triangle on it outwards meets nothing.
  const size_t shared_count = size_t(std::ranges::count_if(instances, shared));
  if (double(world_count) * double(point_count + 8 * shared_count) <= kHullWork) {
    for (uint32_t i = 0; i < instances.size(); ++i)
      if (const Bounds3f& box = bounds[world_count + i]; shared(instances[i]) && !box.empty())
        for (int c = 0; c < 8; ++c) world_points.push_back(box.corner(c));
    world_hull_ = hull_of(world_points, world_count, [&](size_t t, int k) { return world_triangles[t][k]; });
    if (!world_hull_.on.empty()) world_first_ = std::move(world_first);
  }
  world_points = std::vector<Vec3f>();  // freed before the world tree's build, the peak of memory
  world_ = TriangleTree(world_triangles, world_ids, std::move(bounds));
  // The watertight test's t is off by a few ulps of the coordinates it subtracts (Woop et al. 2013,
  // §4), at most the scene's largest: a margin of 2⁻¹⁸ of that covers it several times over.
  if (!world_.bvh.empty()) {
    const Bounds3f b = world_.bvh.bounds();
    t_slack_ = 0x1p-18f * std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x),
                                    std::abs(b.hi.y), std::abs(b.hi.z)});
  }

  // The instances' inverse transforms, kept where they cost at most an eighth of the trees (a
  // vase's flowers); a forest of a million instances of one tree inverts each on entry instead.
  size_t tree_bytes = world_.memory_bytes();
  for (const TriangleTree& t : mesh_trees_) tree_bytes += t.memory_bytes();
  if (mesh_trees_.empty() || instances.size() * sizeof(Transform) > tree_bytes / 8) return;
  to_object_.resize(instances.size());
  tbb::parallel_for(size_t(0), instances.size(), [&](size_t i) {
    if (shared(instances[i])) to_object_[i] = instances[i].to_world.inverse();
  });
}

struct Accel::Closest {
  float t;          // the closest hit so far (ray.tmax before any)
  uint32_t id = 0;  // its global triangle number: 0 before any, so that t = tmax never wins
  uint32_t instance = kWorld;
  TriangleHit hit{};
  const TriangleBlock* block = nullptr;  // where its vertices are, in lane `lane`
  int lane = 0;
};

template <bool AnyHit>
[[gnu::always_inline]] inline bool Accel::test_blocks(const TriangleTree& tree, uint32_t first, uint32_t count,
                                                      uint32_t instance, const WatertightRay& ray,
                                                      Closest& closest) const {
  const uint32_t base = instance == kWorld ? 0 : first_prim_[instance];
  bool found = false;
  for (uint32_t b = first; b < first + count; ++b) {
    const TriangleBlock& block = tree.blocks[b];
    const BlockHits hits = intersect_triangles(ray, block, closest.t);
    for (uint32_t m = hits.mask; m; m &= m - 1) {
      const int lane = std::countr_zero(m);
      const uint32_t id = base + block.id[lane];
      // The order of (t, id) decides, so that ties go the same way whatever the traversal order.
      if (hits.t[lane] < closest.t || (hits.t[lane] == closest.t && id < closest.id)) {
        if constexpr (AnyHit) return true;
        closest = {hits.t[lane], id, instance, hits.lane(lane), &block, lane};
        found = true;
      }
    }
  }
  return found;
}

template <bool AnyHit>
bool Accel::trace(const Ray& ray, Closest& closest) const {
  if (ray.skip_instance == kEveryInstance) return false;  // it leaves the whole scene's convex hull
  // The world tree's leaves, and its solo leaves: the instances of shared meshes.
  LazyWatertightRay world_ray(ray);
  const auto leaf = [&](uint32_t first, uint32_t count) __attribute__((always_inline)) {
    return test_blocks<AnyHit>(world_, first, count, kWorld, *world_ray, closest);
  };
  const auto enter_with = [&](uint32_t instance, const Transform& to_object) {
    if (to_object.m[3][3] == 0) return false;  // singular: a flat instance nothing hits
    const TriangleTree& tree = mesh_trees_[tree_of_mesh_[instances_[instance].mesh]];
    // In the mesh's space the direction is not unit length, so t stays the world-space distance.
    const Ray object_ray{Vec3f(to_object.point(Vec3d(ray.o))), Vec3f(to_object.vector(Vec3d(ray.d))), ray.tmax};
    LazyWatertightRay wr(object_ray);
    const auto mesh_leaf = [&](uint32_t first, uint32_t count) {
      return test_blocks<AnyHit>(tree, first, count, instance, *wr, closest);
    };
    if (brute_force_) return mesh_leaf(0, uint32_t(tree.blocks.size()));
    return tree.bvh.traverse<AnyHit>(object_ray, closest.t, t_slack_, tree.blocks.data(), mesh_leaf,
                                     [](uint32_t) { return false; });  // mesh trees have no solo leaves
  };
  // The inverse kept, or made here; read in place (copying its 128 bytes showed in the profile).
  const auto enter = [&](uint32_t instance) {
    if (instance == ray.skip_instance) return false;
    if (!to_object_.empty()) return enter_with(instance, to_object_[instance]);
    return enter_with(instance, instances_[instance].to_world.inverse());
  };
  if (brute_force_) {
    bool found = leaf(0, uint32_t(world_.blocks.size()));
    for (uint32_t i = 0; i < instances_.size(); ++i) {
      if (tree_of_mesh_[instances_[i].mesh] < 0) continue;
      if constexpr (AnyHit)
        if (found) return true;
      found |= enter(i);
    }
    return found;
  }
  return world_.bvh.traverse<AnyHit>(ray, closest.t, t_slack_, world_.blocks.data(), leaf, enter);
}

bool Accel::intersect(const Ray& ray, AccelHit& hit) const {
  Closest closest{ray.tmax};
  if (!trace<false>(ray, closest)) return false;
  uint32_t instance = closest.instance;
  if (instance == kWorld) {
    // The last instance whose first triangle is at most id: a binary search whose steps are
    // selects, not branches (std::upper_bound's mispredict about every other step).
    const uint32_t* first = first_prim_.data();
    for (size_t n = first_prim_.size(); n > 1; n -= n / 2) first = first[n / 2] <= closest.id ? first + n / 2 : first;
    instance = uint32_t(first - first_prim_.data());
  }
  const TriangleHit& h = closest.hit;
  hit = {h.t, h.b0, h.b1, h.b2, instance, closest.id - first_prim_[instance], {}};
  for (int k = 0; k < 3; ++k) {
    const simd::f8* v = closest.block->v[k];
    hit.v[k] = {v[0][closest.lane], v[1][closest.lane], v[2][closest.lane]};
    // A shared mesh's triangle, in its own space: to world space as the flattened ones were.
    if (closest.instance != kWorld) hit.v[k] = instances_[instance].to_world.point_rounded(hit.v[k]);
  }
  return true;
}

bool Accel::occluded(const Ray& ray) const {
  Closest closest{ray.tmax};
  return trace<true>(ray, closest);
}

bool Accel::may_meet(const Frustum& region) const {
  if (brute_force_) return true;
  // A tree's leaves of triangles, the region given in the tree's space.
  const auto triangles_meet = [](const TriangleTree& tree, const BvhFrustum& f) {
    return [&tree, &f](uint32_t first, uint32_t count) {
      for (uint32_t b = first; b < first + count; ++b)
        if (triangles_meeting(tree.blocks[b], f)) return true;
      return false;
    };
  };
  // An instance of a shared mesh: its tree, with the region carried into the mesh's space.
  const auto instance_meets = [&](uint32_t instance) {
    const Instance& inst = instances_[instance];
    const Transform to_object = to_object_.empty() ? inst.to_world.inverse() : to_object_[instance];
    if (to_object.m[3][3] == 0) return false;  // singular: a flat instance nothing hits (as trace)
    const TriangleTree& tree = mesh_trees_[tree_of_mesh_[inst.mesh]];
    const BvhFrustum local(region.in_space_of(inst.to_world, to_object), tree.bvh.bounds());
    return tree.bvh.any_leaf_meets(local, triangles_meet(tree, local), [](uint32_t) { return false; });
  };
  const BvhFrustum world(region, world_.bvh.bounds());
  return world_.bvh.any_leaf_meets(world, triangles_meet(world_, world), instance_meets);
}

size_t Accel::memory_bytes() const {
  size_t bytes = world_.memory_bytes() + first_prim_.size() * sizeof(uint32_t) + tree_of_mesh_.size() * sizeof(int) +
                 to_object_.size() * sizeof(Transform);
  for (const TriangleTree& t : mesh_trees_) bytes += t.memory_bytes();
  for (const Hull& h : hulls_) bytes += sizeof(Hull) + h.on.size();
  bytes += world_hull_.on.size() + world_first_.size() * sizeof(uint32_t);
  return bytes;
}

}  // namespace prism
