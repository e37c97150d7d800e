#pragma once
// glTF morph targets (glTF 2.0 §3.7.2.2): a primitive's POSITION, NORMAL and TANGENT moved by the
// weighted sum of its targets' displacements, p = p₀ + Σ_k w_k Δp_k.

#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace prism {

// Each target's displacements, one per vertex; an attribute a target lacks is empty.
struct MorphTarget {
  std::vector<Vec3f> positions, normals, tangents;
};

// The primitive's targets, checked against its `vertices` (sparse accessors included).
std::vector<MorphTarget> read_morph_targets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                            size_t vertices, const std::string& context);

// `mesh` holds the base attributes; adds the weighted displacements and renormalises the
// normals and tangents. Targets beyond `weights` count as weight 0.
void apply_morph(const std::vector<MorphTarget>& targets, const std::vector<double>& weights, Mesh& mesh);

}  // namespace prism
