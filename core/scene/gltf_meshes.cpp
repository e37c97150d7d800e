// glTF mesh primitives to Scene meshes: attributes read through gltf_accessor, checked against
// the vertex count, one Mesh per triangle primitive; strips and fans become triangle lists.
// Meshes that morph or are skinned get a copy per node, re-posed when their inputs change.

#include <cmath>

#include "core/base/log.h"
#include "core/scene/gltf_accessor.h"
#include "core/scene/gltf_import.h"
#include "core/scene/gltf_variants.h"

namespace prism {

namespace {

// The triangles of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive's vertex sequence, in
// the winding glTF 2.0 §3.7.2.1 gives them: strip triangle i is (v_i, v_{i+1+i%2}, v_{i+2−i%2}),
// fan triangle i is (v_{i+1}, v_{i+2}, v_0).
std::vector<uint32_t> triangle_list(std::vector<uint32_t> v, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    v.resize(v.size() - v.size() % 3);
    return v;
  }
  std::vector<uint32_t> list;
  for (size_t i = 0; i + 2 < v.size(); ++i)
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
      list.insert(list.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    else
      list.insert(list.end(), {v[i + 1], v[i + 2], v[0]});
  return list;
}

}  // namespace

// Scene meshes (one per triangle primitive) of glTF mesh `index`, converted on first use.
const std::vector<uint32_t>& GltfLoader::mesh(int index) {
  if (mesh_loaded_[index]) return meshes_[index];
  mesh_loaded_[index] = true;
  const tinygltf::Mesh& m = model_.meshes[index];
  for (size_t p = 0; p < m.primitives.size(); ++p) {
    const std::string context = fmt::format("{}: mesh {} '{}' primitive {}", file_, index, m.name, p);
    if (auto converted = convert_primitive(m.primitives[p], context)) {
      converted->name = m.name.empty() ? fmt::format("mesh{}", index) : m.name;
      meshes_[index].push_back(uint32_t(scene_.meshes.size()));
      scene_.meshes.push_back(std::move(*converted));
    }
  }
  return meshes_[index];
}

std::optional<Mesh> GltfLoader::convert_primitive(const tinygltf::Primitive& prim, const std::string& context) {
  if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
    warn_once("points and lines are not rendered (Prism renders surfaces)");
    return std::nullopt;
  }
  if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
    fail("{}: unknown primitive mode {}", context, prim.mode);
  const auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) {
    warn_once("skipping primitives without POSITION data");
    return std::nullopt;
  }
  if (pos->second >= 0 && size_t(pos->second) < model_.accessors.size()) {
    // Compressed meshes (Draco, meshopt) keep their positions elsewhere and their accessors
    // hold no data. Reading them as zeros would give never-hit triangles that still take
    // triangle ids, unlike raybench, whose global numbering `prism bench rays` follows.
    const tinygltf::Accessor& acc = model_.accessors[pos->second];
    if (acc.bufferView < 0 && !acc.sparse.isSparse) {
      warn_once("skipping primitives whose POSITION accessor has no data (no bufferView and no sparse values)");
      return std::nullopt;
    }
  }
  Mesh mesh;
  const auto p = read_accessor_floats(model_, pos->second, 3, context + " POSITION");
  mesh.positions.resize(p.size() / 3);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    mesh.positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    if (!is_finite(mesh.positions[i])) fail("{} POSITION: vertex {} is not finite", context, i);
  }
  if (const auto nrm = prim.attributes.find("NORMAL"); nrm != prim.attributes.end()) {
    const auto n = read_accessor_floats(model_, nrm->second, 3, context + " NORMAL");
    if (n.size() != p.size()) fail("{} NORMAL: {} normals for {} vertices", context, n.size() / 3, p.size() / 3);
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
      const Vec3f v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
      const float len = length(v);
      mesh.normals[i] = len > 0 && std::isfinite(len) ? v / len : Vec3f(0, 0, 0);  // 0: use the face normal
    }
  }
  for (int set = 0; set < 2; ++set)
    if (const auto uv = prim.attributes.find("TEXCOORD_" + std::to_string(set)); uv != prim.attributes.end()) {
      const auto t = read_accessor_floats(model_, uv->second, 2, fmt::format("{} TEXCOORD_{}", context, set));
      if (t.size() / 2 != mesh.positions.size())
        fail("{} TEXCOORD_{}: {} entries for {} vertices", context, set, t.size() / 2, mesh.positions.size());
      for (size_t i = 0; i < t.size(); i += 2) mesh.uv[set].push_back({t[i], t[i + 1]});
    }
  if (const auto col = prim.attributes.find("COLOR_0"); col != prim.attributes.end()) {
    const int components = accessor_components(model_, col->second, context + " COLOR_0");
    if (components != 3 && components != 4) fail("{} COLOR_0: must be VEC3 or VEC4", context);
    const auto c = read_accessor_floats(model_, col->second, components, context + " COLOR_0");
    if (c.size() / components != mesh.positions.size())
      fail("{} COLOR_0: {} colours for {} vertices", context, c.size() / components, mesh.positions.size());
    // Colours are factors in [0, 1] (glTF §3.7.2.1): others, NaN included (read as 1), are clamped.
    bool clamped = false;
    const auto factor = [&](float v) {
      const float f = std::isnan(v) ? 1.f : std::clamp(v, 0.f, 1.f);
      clamped |= f != v;
      return f;
    };
    for (size_t i = 0; i < c.size(); i += components)
      mesh.colors.push_back(
          {factor(c[i]), factor(c[i + 1]), factor(c[i + 2]), components == 4 ? factor(c[i + 3]) : 1.f});
    if (clamped) warn_once("COLOR_0 values outside [0, 1] or NaN clamped to [0, 1]");
  }
  if (const auto tan = prim.attributes.find("TANGENT"); tan != prim.attributes.end()) {
    const auto t = read_accessor_floats(model_, tan->second, 4, context + " TANGENT");
    if (t.size() / 4 != mesh.positions.size())
      fail("{} TANGENT: {} tangents for {} vertices", context, t.size() / 4, mesh.positions.size());
    for (size_t i = 0; i < t.size(); i += 4)
      mesh.tangents.push_back({t[i], t[i + 1], t[i + 2], t[i + 3] < 0 ? -1.f : 1.f});
  }
  std::vector<uint32_t> vertices;
  if (prim.indices < -1)  // tinygltf's -1 is "none"; any other negative index names no accessor
    fail("{} indices: accessor {} does not exist", context, prim.indices);
  if (prim.indices >= 0) {
    vertices = read_accessor_indices(model_, prim.indices, context + " indices");
    for (uint32_t i : vertices)
      if (i >= mesh.positions.size())
        fail("{} indices: index {} out of range ({} vertices)", context, i, mesh.positions.size());
  } else {
    vertices.resize(mesh.positions.size());
    for (uint32_t i = 0; i < vertices.size(); ++i) vertices[i] = i;
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && vertices.size() % 3 != 0)
    warn_once("dropping a trailing partial triangle");
  mesh.indices = triangle_list(std::move(vertices), prim.mode);
  mesh.material = material_index(variant_material(prim, variant_), context);
  const Material& material = scene_.materials[mesh.material];
  const auto* pbr = std::get_if<PbrMaterial>(&material.kind);
  if (mesh.tangents.empty()) {  // normal maps and anisotropy need the tangent frame
    if (material.normal_texture)
      generate_tangents(mesh, material.normal_texture->texcoord);
    else if (pbr && pbr->anisotropic())
      generate_tangents(mesh, pbr->anisotropy_texture ? pbr->anisotropy_texture->texcoord : 0);
  }
  return mesh;
}

bool GltfLoader::deforms(const tinygltf::Node& node) const {
  if (node.skin >= 0) return true;
  const auto& prims = model_.meshes[node.mesh].primitives;
  return std::any_of(prims.begin(), prims.end(), [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
}

// The base attributes, morph targets and skin weights of glTF mesh `index`'s primitives, read once.
const std::vector<GltfLoader::Deformable>& GltfLoader::deformable(int index) {
  auto [it, inserted] = deformables_.try_emplace(index);
  if (!inserted) return it->second;
  const tinygltf::Mesh& m = model_.meshes[index];
  for (size_t p = 0; p < m.primitives.size(); ++p) {
    const std::string context = fmt::format("{}: mesh {} '{}' primitive {}", file_, index, m.name, p);
    const tinygltf::Primitive& prim = m.primitives[p];
    auto converted = convert_primitive(prim, context);
    if (!converted) continue;
    Deformable d;
    d.base = std::move(*converted);
    d.base.name = m.name.empty() ? fmt::format("mesh{}", index) : m.name;
    d.targets = read_morph_targets(model_, prim, d.base.positions.size(), context);
    d.skin = read_skin_weights(model_, prim, d.base.positions.size(), context);
    d.generated_tangents = !d.base.tangents.empty() && !prim.attributes.count("TANGENT");
    it->second.push_back(std::move(d));
  }
  return it->second;
}

// A node's morphed or skinned mesh: its own copy of each primitive, deformed again only when the
// morph weights or joint matrices it was posed with change. A skinned primitive lands in world
// space by its joints alone; the node's transform is ignored (glTF 2.0 §3.7.3.3).
void GltfLoader::add_deformed(int index, const Transform& world) {
  const tinygltf::Node& node = model_.nodes[index];
  const std::string context = fmt::format("{}: node {} '{}'", file_, index, node.name);
  const std::vector<Deformable>& sources = deformable(node.mesh);
  std::vector<Transform> joints;
  if (node.skin >= 0) {
    check_index(node.skin, model_.skins, "skin", context);
    joints =
        joint_matrices(model_, model_.skins[node.skin], node_world_, fmt::format("{} skin {}", context, node.skin));
  }
  std::vector<double> inputs = pose_[index].weights;
  for (const Transform& j : joints)
    for (const auto& row : j.m) inputs.insert(inputs.end(), row.begin(), row.end());
  Deformed& d = deformed_[index];
  const bool first = d.meshes.empty();
  if (first)
    for (const Deformable& source : sources) {
      d.meshes.push_back(uint32_t(scene_.meshes.size()));
      scene_.meshes.push_back(source.base);
    }
  if (first || inputs != d.inputs) {
    for (size_t k = 0; k < sources.size(); ++k) {
      const Deformable& source = sources[k];
      Mesh& mesh = scene_.meshes[d.meshes[k]];
      mesh.positions = source.base.positions;
      mesh.normals = source.base.normals;
      mesh.tangents = source.base.tangents;
      apply_morph(source.targets, pose_[index].weights, mesh);
      if (!joints.empty() && !source.skin.empty()) apply_skin(source.skin, joints, mesh, context);
      if (source.generated_tangents) {
        mesh.tangents.clear();
        generate_tangents(mesh, scene_.materials[mesh.material].normal_texture->texcoord);
      }
    }
    d.inputs = std::move(inputs);
  }
  for (size_t k = 0; k < sources.size(); ++k) {
    const bool skinned = !joints.empty() && !sources[k].skin.empty();
    scene_.instances.push_back({d.meshes[k], skinned ? Transform{} : world});
  }
}

}  // namespace prism
