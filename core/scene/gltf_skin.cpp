#include "core/scene/gltf_skin.h"

#include <cmath>

#include "core/base/error.h"
#include "core/scene/gltf_accessor.h"

namespace prism {

SkinWeights read_skin_weights(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertices,
                              const std::string& context) {
  SkinWeights skin;
  for (int set = 0; set < 2; ++set) {
    const auto j = prim.attributes.find("JOINTS_" + std::to_string(set));
    const auto w = prim.attributes.find("WEIGHTS_" + std::to_string(set));
    if (j == prim.attributes.end() && w == prim.attributes.end()) break;
    if (j == prim.attributes.end() || w == prim.attributes.end())
      fail("{}: JOINTS_{} and WEIGHTS_{} come in pairs", context, set, set);
    const auto joints = read_accessor_floats(model, j->second, 4, fmt::format("{} JOINTS_{}", context, set));
    const auto weights = read_accessor_floats(model, w->second, 4, fmt::format("{} WEIGHTS_{}", context, set));
    if (joints.size() != 4 * vertices || weights.size() != 4 * vertices)
      fail("{}: JOINTS_{} / WEIGHTS_{} have {} / {} entries for {} vertices", context, set, set, joints.size() / 4,
           weights.size() / 4, vertices);
    skin.joints.resize(vertices, {});
    skin.weights.resize(vertices, {});
    for (size_t i = 0; i < vertices; ++i)
      for (int c = 0; c < 4; ++c) {
        const float weight = weights[4 * i + c];
        if (!(weight >= 0 && weight < INFINITY)) fail("{}: WEIGHTS_{} of vertex {} is {}", context, set, i, weight);
        skin.joints[i][4 * set + c] = uint32_t(joints[4 * i + c]);
        skin.weights[i][4 * set + c] = weight;
      }
  }
  for (auto& w : skin.weights) {
    float sum = 0;
    for (float x : w) sum += x;
    if (sum > 0)
      for (float& x : w) x /= sum;
  }
  return skin;
}

std::vector<Transform> joint_matrices(const tinygltf::Model& model, const tinygltf::Skin& skin,
                                      const std::vector<Transform>& node_world, const std::string& context) {
  std::vector<float> inverse_bind;
  if (skin.inverseBindMatrices >= 0) {
    inverse_bind = read_accessor_floats(model, skin.inverseBindMatrices, 16, context + " inverseBindMatrices");
    if (inverse_bind.size() != 16 * skin.joints.size())
      fail("{} inverseBindMatrices: {} matrices for {} joints", context, inverse_bind.size() / 16, skin.joints.size());
  }
  std::vector<Transform> joints;
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    if (node < 0 || size_t(node) >= node_world.size())
      fail("{}: joint {} is node {}, which does not exist", context, j, node);
    Transform bind;
    if (!inverse_bind.empty()) {
      double m[16];
      for (int k = 0; k < 16; ++k) m[k] = inverse_bind[16 * j + k];
      bind = Transform::from_column_major(m);
    }
    joints.push_back(node_world[node] * bind);
  }
  return joints;
}

void apply_skin(const SkinWeights& skin, const std::vector<Transform>& joints, Mesh& mesh, const std::string& context) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (skin.weights[i] == std::array<float, SkinWeights::kInfluences>{}) continue;  // no joint moves it
    Transform m;
    m.m = {};
    for (int k = 0; k < SkinWeights::kInfluences; ++k) {
      const float w = skin.weights[i][k];
      if (w == 0) continue;
      if (skin.joints[i][k] >= joints.size())
        fail("{}: vertex {} names joint {} of a skin with {}", context, i, skin.joints[i][k], joints.size());
      const Transform& j = joints[skin.joints[i][k]];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) m.m[r][c] += w * j.m[r][c];
    }
    m.m[3] = {0, 0, 0, 1};  // affine, whatever the weights' rounding
    mesh.positions[i] = Vec3f(m.point(Vec3d(mesh.positions[i])));
    if (!mesh.normals.empty()) {
      // The inverse transpose of the linear part A is cof(A) / det(A); the cofactor matrix's
      // columns are a1×a2, a2×a0, a0×a1 for A's columns a_j, and only det's sign matters here.
      const Vec3d a0(m.m[0][0], m.m[1][0], m.m[2][0]), a1(m.m[0][1], m.m[1][1], m.m[2][1]),
          a2(m.m[0][2], m.m[1][2], m.m[2][2]);
      const Vec3d n0(mesh.normals[i]);
      const Vec3d n = (cross(a1, a2) * n0.x + cross(a2, a0) * n0.y + cross(a0, a1) * n0.z) *
                      (dot(a0, cross(a1, a2)) < 0 ? -1.0 : 1.0);
      mesh.normals[i] = length(n) > 0 && std::isfinite(length(n)) ? Vec3f(normalize(n)) : Vec3f(0, 0, 0);
    }
    if (!mesh.tangents.empty()) {
      auto& t = mesh.tangents[i];
      const Vec3d v = m.vector({t[0], t[1], t[2]});
      if (length(v) > 0 && std::isfinite(length(v))) {
        const Vec3d u = normalize(v);
        t = {float(u.x), float(u.y), float(u.z), t[3]};
      }
    }
  }
}

}  // namespace prism
