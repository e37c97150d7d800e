// The glTF node hierarchy in the current pose: world transforms, mesh instances, cameras and
// KHR_lights_punctual.

#include <cmath>

#include "core/base/log.h"
#include "core/scene/gltf_import.h"

namespace prism {

// Every node's world transform in the current pose (skins need their joints' wherever they are).
void GltfLoader::compute_node_world() {
  node_world_.assign(model_.nodes.size(), Transform{});
  std::vector<bool> is_child(model_.nodes.size(), false);
  for (const auto& n : model_.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < is_child.size()) is_child[c] = true;
  std::vector<std::pair<int, Transform>> stack;
  for (size_t i = 0; i < model_.nodes.size(); ++i)
    if (!is_child[i]) stack.push_back({int(i), Transform{}});
  size_t visits = 0;
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (++visits > model_.nodes.size()) break;  // a node with two parents; traverse_scene() reports it if used
    node_world_[index] = parent * pose_[index].local();
    for (int c : model_.nodes[index].children)
      if (c >= 0 && size_t(c) < model_.nodes.size()) stack.push_back({c, node_world_[index]});
  }
}

namespace {

// Finite once rounded to float, as the renderer stores world coordinates.
bool float_finite(const Vec3d& v) { return is_finite(Vec3f(v)); }

uint64_t saturating_add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
uint64_t saturating_mul(uint64_t a, uint64_t b) { return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b; }

}  // namespace

void GltfLoader::traverse_scene() {
  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    check_index(scene_index_, model_.scenes, "scene", "the default scene");
    roots = model_.scenes[scene_index_].nodes;
  } else {
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const auto& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < is_child.size()) is_child[c] = true;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(int(i));
  }
  for (int root : roots) check_index(root, model_.nodes, "node", "the scene");
  const uint64_t instances = count_instances(roots);
  if (instances > max_instances_)
    fail(
        "{}: the node hierarchy makes {} node visits and mesh instances, more than the {} that fit in memory (see "
        "--max-memory)",
        file_, instances, max_instances_);

  // Depth-first, parents before children, without recursion: hierarchies may be any depth.
  struct Pending {
    int node;
    Transform parent;
  };
  std::vector<Pending> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, Transform{}});
  std::set<std::pair<uint32_t, decltype(Transform::m)>> placed;
  size_t coincident = 0;
  while (!stack.empty()) {
    const Pending next = std::move(stack.back());
    stack.pop_back();
    const tinygltf::Node& node = model_.nodes[next.node];
    const std::string context = fmt::format("{}: node {} '{}'", file_, next.node, node.name);
    const Transform world = next.parent * pose_[next.node].local();
    const bool gpu_instanced = node.extensions.count("EXT_mesh_gpu_instancing") > 0;
    const auto first_instance = uint32_t(scene_.instances.size());
    if (node.mesh >= 0 && deforms(node)) {
      if (gpu_instanced) warn_once("EXT_mesh_gpu_instancing on a morphed or skinned mesh: drawn once");
      add_deformed(next.node, world);
    } else if (node.mesh >= 0 && gpu_instanced) {
      add_gpu_instances(node, mesh(node.mesh), world, context);
    } else if (node.mesh >= 0)
      for (uint32_t m : mesh(node.mesh)) {
        if (!placed.insert({m, world.m}).second) {
          ++coincident;  // the same mesh in the same place again: invisible, only slower
          continue;
        }
        check_world_bounds(m, world, context);
        scene_.instances.push_back({m, world});
      }
    if (!node.name.empty() && scene_.instances.size() > first_instance)
      scene_.named_nodes.push_back({node.name, first_instance, uint32_t(scene_.instances.size())});
    if (!node.name.empty()) scene_.node_origins.emplace_back(node.name, Vec3f(world.point({0, 0, 0})));
    if (node.camera >= 0) {
      check_index(node.camera, model_.cameras, "camera", context);
      add_camera(model_.cameras[node.camera], world, context);
    }
    if (const auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const auto& light = it->second.Get("light");
      if (!light.IsInt()) fail("{}: KHR_lights_punctual without a light index", context);
      check_index(light.GetNumberAsInt(), model_.lights, "light", context);
      add_light(model_.lights[light.GetNumberAsInt()], world, context);
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, world});
  }
  if (coincident > 0)
    log::warn("{}: skipped {} mesh instances that coincide with another of the same mesh", file_, coincident);
}

// Node visits plus mesh instances (one per primitive) under `roots`, counted on the node graph
// (memoised, saturating) before any is made, so that a DAG reaching a node 2^63 times is
// refused at once, whether or not it holds a mesh. Also finds cycles and checks child indices.
uint64_t GltfLoader::count_instances(const std::vector<int>& roots) const {
  enum : uint8_t { unseen, open, done };
  std::vector<uint8_t> state(model_.nodes.size(), unseen);
  std::vector<uint64_t> count(model_.nodes.size(), 0);
  std::vector<std::pair<int, size_t>> stack;  // node, next child to look at
  uint64_t total = 0;
  for (int root : roots) {
    if (state[root] == unseen) {
      state[root] = open;
      stack.push_back({root, 0});
    }
    while (!stack.empty()) {
      const int index = stack.back().first;
      const tinygltf::Node& node = model_.nodes[index];
      if (stack.back().second < node.children.size()) {
        const int child = node.children[stack.back().second++];
        check_index(child, model_.nodes, "child node", fmt::format("{}: node {} '{}'", file_, index, node.name));
        if (state[child] == open) fail("{}: node {} is its own ancestor (cycle in the node hierarchy)", file_, child);
        if (state[child] == unseen) {
          state[child] = open;
          stack.push_back({child, 0});
        }
        continue;
      }
      uint64_t n = 1;
      if (node.mesh >= 0) {
        check_index(node.mesh, model_.meshes, "mesh", fmt::format("{}: node {} '{}'", file_, index, node.name));
        n = saturating_add(n, saturating_mul(model_.meshes[node.mesh].primitives.size(), gpu_instance_count(node)));
      }
      for (int child : node.children) n = saturating_add(n, count[child]);
      count[index] = n;
      state[index] = done;
      stack.pop_back();
    }
    total = saturating_add(total, count[root]);
  }
  return total;
}

// Geometry finite in local space can overflow float in world space (a huge scale or offset).
void GltfLoader::check_world_bounds(uint32_t mesh, const Transform& world, const std::string& context) {
  if (mesh_bounds_.size() <= mesh) mesh_bounds_.resize(scene_.meshes.size());
  if (!mesh_bounds_[mesh]) {
    Vec3d lo(kInfinity, kInfinity, kInfinity), hi = -lo;
    for (const Vec3f& p : scene_.meshes[mesh].positions) lo = min(lo, Vec3d(p)), hi = max(hi, Vec3d(p));
    mesh_bounds_[mesh] = {lo, hi};
  }
  const auto& [lo, hi] = *mesh_bounds_[mesh];
  for (int corner = 0; corner < 8 && lo.x <= hi.x; ++corner)
    if (!float_finite(world.point({corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z})))
      fail("{}: mesh '{}' lies beyond float range once transformed to world space", context, scene_.meshes[mesh].name);
}

void GltfLoader::add_camera(const tinygltf::Camera& cam, const Transform& world, const std::string& context) {
  const Vec3d forward = world.vector({0, 0, -1});
  if (!float_finite(world.point({0, 0, 0})) || !is_finite(Vec3f(normalize(forward))) ||
      !is_finite(Vec3f(normalize(cross(forward, world.vector({0, 1, 0}))))))
    fail("{}: camera '{}' has a degenerate or overflowing transform", context, cam.name);
  CameraDesc c;
  c.name = cam.name;
  c.to_world = world;
  c.lens = camera_lens(cam, context);
  if (cam.type == "perspective") {
    c.yfov = float(cam.perspective.yfov);
    if (!(c.yfov > 0 && c.yfov < kPi))
      fail("{}: camera '{}' has yfov {} (needs 0 < yfov < π)", context, cam.name, c.yfov);
    if (cam.perspective.aspectRatio > 0) c.aspect = float(cam.perspective.aspectRatio);
  } else if (cam.type == "orthographic") {
    c.projection = CameraDesc::Projection::orthographic;
    c.xmag = float(std::abs(cam.orthographic.xmag));
    c.ymag = float(std::abs(cam.orthographic.ymag));
    if (!(c.xmag > 0 && c.ymag > 0 && std::isfinite(c.xmag) && std::isfinite(c.ymag)))
      fail("{}: orthographic camera '{}' needs non-zero xmag and ymag that are finite in single precision (got {}, {})",
           context, cam.name, cam.orthographic.xmag, cam.orthographic.ymag);
    c.aspect = c.xmag / c.ymag;
  } else {
    fail("{}: camera '{}' has unknown type '{}'", context, cam.name, cam.type);
  }
  scene_.cameras.push_back(c);
}

// KHR_lights_punctual: intensity in candela (point, spot) or lux (directional), times the
// linear colour, upsampled as an illuminant like emission (see the README's units). A spot or
// directional light shines down its node's local −Z.
void GltfLoader::add_light(const tinygltf::Light& light, const Transform& world, const std::string& context) {
  std::array<double, 3> color{1, 1, 1};
  if (!light.color.empty()) {
    if (light.color.size() != 3 || !all_finite(light.color) ||
        *std::min_element(light.color.begin(), light.color.end()) < 0)
      fail("{}: light '{}': color must be 3 finite numbers ≥ 0", context, light.name);
    color = {light.color[0], light.color[1], light.color[2]};
  }
  if (!std::isfinite(light.intensity) || light.intensity < 0)
    fail("{}: light '{}' has invalid intensity {}", context, light.name, light.intensity);
  if (light.range > 0) warn_once("light range is ignored: lights fall off with the inverse square of distance");
  const Spectrum emission = light_emission(
      light,
      clamp_emission({color[0] * light.intensity, color[1] * light.intensity, color[2] * light.intensity}, context),
      context);
  const Vec3f position(world.point({0, 0, 0}));
  const Vec3f direction(normalize(world.vector({0, 0, -1})));
  if (!float_finite(world.point({0, 0, 0})))
    fail("{}: light '{}' lies beyond float range in world space", context, light.name);
  if (light.type != "point" && !is_finite(direction))
    fail("{}: light '{}' has a degenerate direction (zero scale?)", context, light.name);
  if (light.type == "point") {
    scene_.point_lights.push_back({light.name, position, emission});
  } else if (light.type == "spot") {
    const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
    if (!(inner >= 0 && inner <= outer && outer <= kPi / 2 + 1e-6))
      fail("{}: spot light '{}' needs 0 ≤ innerConeAngle ≤ outerConeAngle ≤ π/2 (got {} and {})", context, light.name,
           inner, outer);
    scene_.spot_lights.push_back({light.name, position, direction, float(inner), float(outer), emission});
  } else if (light.type == "directional") {
    scene_.directional_lights.push_back({light.name, direction, emission});
  } else {
    warn_once(fmt::format("ignoring lights of unknown type '{}'", light.type));
  }
}

}  // namespace prism
