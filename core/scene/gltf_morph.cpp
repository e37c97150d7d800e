#include "core/scene/gltf_morph.h"

#include "core/base/error.h"
#include "core/scene/gltf_accessor.h"

namespace prism {

std::vector<MorphTarget> read_morph_targets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                            size_t vertices, const std::string& context) {
  std::vector<MorphTarget> targets(prim.targets.size());
  for (size_t k = 0; k < prim.targets.size(); ++k)
    for (const auto& [name, accessor] : prim.targets[k]) {
      std::vector<Vec3f>* out = name == "POSITION"  ? &targets[k].positions
                                : name == "NORMAL"  ? &targets[k].normals
                                : name == "TANGENT" ? &targets[k].tangents
                                                    : nullptr;
      if (!out) continue;  // TEXCOORD_n and COLOR_n targets: not rendered differently
      const std::string what = fmt::format("{} morph target {} {}", context, k, name);
      const auto d = read_accessor_floats(model, accessor, 3, what);
      if (d.size() != 3 * vertices) fail("{}: {} displacements for {} vertices", what, d.size() / 3, vertices);
      out->resize(vertices);
      for (size_t i = 0; i < vertices; ++i) {
        (*out)[i] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
        if (!is_finite((*out)[i])) fail("{}: displacement {} is not finite", what, i);
      }
    }
  return targets;
}

void apply_morph(const std::vector<MorphTarget>& targets, const std::vector<double>& weights, Mesh& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<Vec3d> p(n), nrm(mesh.normals.size()), tan(mesh.tangents.size());
  for (size_t i = 0; i < n; ++i) p[i] = Vec3d(mesh.positions[i]);
  for (size_t i = 0; i < nrm.size(); ++i) nrm[i] = Vec3d(mesh.normals[i]);
  for (size_t i = 0; i < tan.size(); ++i) tan[i] = {mesh.tangents[i][0], mesh.tangents[i][1], mesh.tangents[i][2]};
  const auto add = [](std::vector<Vec3d>& to, const std::vector<Vec3f>& d, double w) {
    if (d.size() == to.size())
      for (size_t i = 0; i < to.size(); ++i) to[i] += Vec3d(d[i]) * w;
  };
  for (size_t k = 0; k < std::min(targets.size(), weights.size()); ++k) {
    if (weights[k] == 0) continue;
    add(p, targets[k].positions, weights[k]);
    add(nrm, targets[k].normals, weights[k]);
    add(tan, targets[k].tangents, weights[k]);
  }
  for (size_t i = 0; i < n; ++i) mesh.positions[i] = Vec3f(p[i]);
  for (size_t i = 0; i < nrm.size(); ++i)
    mesh.normals[i] = length(nrm[i]) > 0 ? Vec3f(normalize(nrm[i])) : Vec3f(0, 0, 0);
  for (size_t i = 0; i < tan.size(); ++i)
    if (length(tan[i]) > 0) {
      const Vec3d t = normalize(tan[i]);
      mesh.tangents[i] = {float(t.x), float(t.y), float(t.z), mesh.tangents[i][3]};
    }
}

}  // namespace prism
