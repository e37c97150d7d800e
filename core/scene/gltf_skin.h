#pragma once
// glTF skins (glTF 2.0 §3.7.3): linear blend skinning. Each vertex moves by the weighted sum of
// its joints' matrices, M = Σ_i w_i · world(joint_i) · inverseBind(joint_i), and lands in world
// space: the skinned mesh's own node transform is ignored, as the spec requires.

#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/transform.h"
#include "core/scene/scene.h"

namespace prism {

// Up to eight influences per vertex (JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1); unused ones
// have weight 0. Weights are normalised to sum to 1.
struct SkinWeights {
  static constexpr int kInfluences = 8;
  std::vector<std::array<uint32_t, kInfluences>> joints;
  std::vector<std::array<float, kInfluences>> weights;
  bool empty() const { return joints.empty(); }
};

// The primitive's JOINTS_n / WEIGHTS_n, or none when it has no JOINTS_0.
SkinWeights read_skin_weights(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertices,
                              const std::string& context);

// world(joint_j) · inverseBind_j for every joint of `skin`, given every node's world transform.
std::vector<Transform> joint_matrices(const tinygltf::Model& model, const tinygltf::Skin& skin,
                                      const std::vector<Transform>& node_world, const std::string& context);

// Moves `mesh`'s positions, normals (by the inverse transpose) and tangents into world space.
void apply_skin(const SkinWeights& skin, const std::vector<Transform>& joints, Mesh& mesh, const std::string& context);

}  // namespace prism
