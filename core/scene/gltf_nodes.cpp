// The glTF node hierarchy in the current pose: world transforms, mesh instances, cameras and
// KHR_lights_punctual.

#include <cmath>

#include "base/log.h"
#include "scene/gltf_import.h"

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
    if (++visits > model_.nodes.size()) break;  // a node with two parents; visit() reports it if the scene uses it
    node_world_[index] = parent * pose_[index].local();
    for (int c : model_.nodes[index].children)
      if (c >= 0 && size_t(c) < model_.nodes.size()) stack.push_back({c, node_world_[index]});
  }
}

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
  std::vector<bool> on_path(model_.nodes.size(), false);
  for (int root : roots) {
    check_index(root, model_.nodes, "node", "the scene");
    visit(root, Transform{}, on_path);
  }
}

void GltfLoader::visit(int index, const Transform& parent, std::vector<bool>& on_path) {
  if (on_path[index]) fail("{}: node {} is its own ancestor (cycle in the node hierarchy)", file_, index);
  on_path[index] = true;
  const tinygltf::Node& node = model_.nodes[index];
  const std::string context = fmt::format("{}: node {} '{}'", file_, index, node.name);
  const Transform world = parent * pose_[index].local();
  if (node.mesh >= 0) {
    check_index(node.mesh, model_.meshes, "mesh", context);
    if (deforms(node))
      add_deformed(index, world);
    else
      for (uint32_t m : mesh(node.mesh)) scene_.instances.push_back({m, world});
  }
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
  for (int child : node.children) {
    check_index(child, model_.nodes, "child node", context);
    visit(child, world, on_path);
  }
  on_path[index] = false;
}

void GltfLoader::add_camera(const tinygltf::Camera& cam, const Transform& world, const std::string& context) {
  CameraDesc c;
  c.name = cam.name;
  c.to_world = world;
  if (cam.type == "perspective") {
    c.yfov = float(cam.perspective.yfov);
    if (!(c.yfov > 0 && c.yfov < kPi))
      fail("{}: camera '{}' has yfov {} (needs 0 < yfov < π)", context, cam.name, c.yfov);
    if (cam.perspective.aspectRatio > 0) c.aspect = float(cam.perspective.aspectRatio);
  } else if (cam.type == "orthographic") {
    c.projection = CameraDesc::Projection::orthographic;
    c.xmag = float(std::abs(cam.orthographic.xmag));
    c.ymag = float(std::abs(cam.orthographic.ymag));
    if (!(c.xmag > 0 && c.ymag > 0))
      fail("{}: orthographic camera '{}' needs non-zero xmag and ymag", context, cam.name);
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
  Rgb color{1, 1, 1};
  if (!light.color.empty()) {
    if (light.color.size() != 3 || !all_finite(light.color)) fail("{}: light color must be 3 finite numbers", context);
    color = {float(light.color[0]), float(light.color[1]), float(light.color[2])};
  }
  if (!std::isfinite(light.intensity) || light.intensity < 0)
    fail("{}: light '{}' has invalid intensity {}", context, light.name, light.intensity);
  if (light.range > 0) warn_once("light range is ignored: lights fall off with the inverse square of distance");
  const Spectrum emission = RgbIlluminantSpectrum(color * float(light.intensity));
  const Vec3f position(world.point({0, 0, 0}));
  const Vec3f direction(normalize(world.vector({0, 0, -1})));
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
