#pragma once
// glTF node poses and animations: the local transform and morph weights of every node, as the
// file gives them and as its animation channels set them at a chosen time (glTF 2.0 §3.11 and
// Appendix C: STEP, LINEAR with slerp for rotations, CUBICSPLINE Hermite).

#include <tiny_gltf.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/base/transform.h"

namespace prism {

// One node's local transform (TRS, or the matrix a file gives instead) and morph weights.
struct NodePose {
  std::array<double, 3> translation{0, 0, 0};
  std::array<double, 4> rotation{0, 0, 0, 1};  // unit quaternion (x, y, z, w)
  std::array<double, 3> scale{1, 1, 1};
  std::optional<Transform> matrix;  // node.matrix; animation never targets such a node
  std::vector<double> weights;      // node.weights, else its mesh's weights, else zeros

  Transform local() const;  // T · R · S, or the matrix
  bool operator==(const NodePose&) const = default;
};

// Every node's pose as the file gives it, checked (`file` names it in errors).
std::vector<NodePose> rest_pose(const tinygltf::Model& model, const std::string& file);

enum class Interpolation { step, linear, cubic_spline };

// Keyframes: times, and `width` values per key (three per key for CUBICSPLINE: in-tangent,
// value, out-tangent).
struct AnimationSampler {
  std::vector<float> times;
  std::vector<float> values;
  int width = 0;
  Interpolation interpolation = Interpolation::linear;
};

struct AnimationChannel {
  enum class Path { translation, rotation, scale, weights };
  int node = 0;
  Path path = Path::translation;
  int sampler = 0;
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  double start = 0, end = 0;  // first and last key time [s]
};

// The file's animations, read and checked once. Channels of paths Prism does not know (from
// extensions such as KHR_animation_pointer) are left out with a warning.
std::vector<Animation> read_animations(const tinygltf::Model& model, const std::string& file);

// Index of the animation named `name_or_index` (a name, else a 0-based index); fails listing
// the file's animations when there is none such.
int find_animation(const std::vector<Animation>& animations, const std::string& name_or_index, const std::string& file);

// The sampler's `width` values at `time`: the first key's before it, the last key's after it.
// `quaternion`: rotations are slerped (LINEAR) and normalised (CUBICSPLINE).
std::vector<double> sample(const AnimationSampler& sampler, double time, bool quaternion);

// Warns when channels of different animations set the same property of a node: played together,
// the later animation's value wins, which is rarely what the file means (a walk and a run of one
// skeleton).
void warn_of_shared_targets(const std::vector<Animation>& animations, const tinygltf::Model& model,
                            const std::string& file);

// Sets every channel of `animation` at `time` in `pose`.
void animate(const Animation& animation, double time, std::vector<NodePose>& pose);

}  // namespace prism
