// glTF mesh primitives to Scene meshes: attributes read through gltf_accessor, checked against
// the vertex count, one Mesh per triangle primitive.

#include "base/log.h"
#include "scene/gltf_accessor.h"
#include "scene/gltf_import.h"

namespace prism {

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
  if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
    warn_once(fmt::format("skipping primitives of mode {} (only triangles are rendered)", prim.mode));
    return std::nullopt;
  }
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
      warn_once("skipping primitives whose POSITION accessor has no data (compressed meshes are not supported)");
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
    for (size_t i = 0; i < c.size(); i += components)
      mesh.colors.push_back({c[i], c[i + 1], c[i + 2], components == 4 ? c[i + 3] : 1.f});
  }
  if (const auto tan = prim.attributes.find("TANGENT"); tan != prim.attributes.end()) {
    const auto t = read_accessor_floats(model_, tan->second, 4, context + " TANGENT");
    if (t.size() / 4 != mesh.positions.size())
      fail("{} TANGENT: {} tangents for {} vertices", context, t.size() / 4, mesh.positions.size());
    for (size_t i = 0; i < t.size(); i += 4)
      mesh.tangents.push_back({t[i], t[i + 1], t[i + 2], t[i + 3] < 0 ? -1.f : 1.f});
  }
  if (prim.indices >= 0) {
    mesh.indices = read_accessor_indices(model_, prim.indices, context + " indices");
    for (uint32_t i : mesh.indices)
      if (i >= mesh.positions.size())
        fail("{} indices: index {} out of range ({} vertices)", context, i, mesh.positions.size());
  } else {
    mesh.indices.resize(mesh.positions.size());
    for (uint32_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = i;
  }
  if (mesh.indices.size() % 3 != 0) {
    warn_once("dropping a trailing partial triangle");
    mesh.indices.resize(mesh.indices.size() - mesh.indices.size() % 3);
  }
  mesh.material = material_index(prim.material, context);
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

}  // namespace prism
