#pragma once
// A light tree (Conty Estevez & Kulla, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting", HPG 2018; built as pbrt-v4's BVHLightSampler, §12.6.3): a bounding volume hierarchy
// over the lights whose nodes bound their lights' positions, power and emission cones
// (LightBounds). The light for a shading point is found by descending from the root, each child
// taken with probability in proportion to its importance at the point; a light's probability at
// any point is the product along its path from the root, so MIS with BSDF sampling stays exact.
// The binary tree the cost model builds is collapsed to nodes of eight children, whose
// importances are computed together (one vector pass per level, a third of the levels).
// Infinite lights (directional, environment) stay outside the tree: the tree and each of them are
// chosen first by power, as PowerLightSampler chooses.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/render/light_bounds.h"
#include "core/render/power_light_sampler.h"

namespace prism {

struct SampledLight {
  uint32_t light;
  float pmf;
};

// The point a light is chosen for: its position and, if given (else zero), the normal that
// bounds the cosine there; `hemisphere` when only the side n faces receives light.
struct ShadingPoint {
  Vec3f p, n;
  bool hemisphere = false;
};

class LightTree {
 public:
  static constexpr int kWidth = 8;

  LightTree() = default;
  // bounds[i] of light i, or none for an infinite light; power[i] as PowerLightSampler's. Lights
  // of zero power are left out: never chosen.
  LightTree(std::span<const std::optional<LightBounds>> bounds, std::span<const float> power);

  std::optional<SampledLight> sample(const ShadingPoint& at, float u) const;
  // The probability that sample(at, ·) chooses `light`.
  float pmf(const ShadingPoint& at, uint32_t light) const;

  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const {
    return nodes_.size() * (sizeof(Node) + sizeof(uint32_t)) + place_.size() * sizeof(uint32_t);
  }

 private:
  // Eight children's bounds, lane by lane, as the importance reads them: each child's bounding
  // sphere, power (negative for two-sided emitters), cone and emission angle (352 bytes). An
  // empty lane has no power.
  struct alignas(32) Node {
    std::array<float, kWidth> cx, cy, cz, radius, phi, wx, wy, wz, cos_o, cos_e;
    std::array<uint32_t, kWidth> child;  // kLeaf | light, or a node

    void set(int lane, const LightBounds& b, uint32_t child);
    // Each lane's bound, up to a factor common to all nodes, of the light its emitters can bring
    // to the point: phi · cos θ' / d², with θ' the least angle between an emitter's cone and the
    // direction to the point over the sphere, times the cosine at the point likewise bounded when
    // a normal is given (Conty Estevez & Kulla 2018, eq. 3; pbrt-v4 §12.6.3).
    std::array<float, kWidth> importance(const ShadingPoint& at) const;
  };
  static constexpr uint32_t kLeaf = 1u << 31;

  struct Binary;  // the tree as built, before collapsing
  void collapse(const std::vector<Binary>& binary, uint32_t root, uint32_t parent_lane);

  PowerLightSampler top_;           // slot 0: the tree; then the infinite lights
  std::vector<uint32_t> infinite_;  // the light in top_'s slot 1 + i
  std::vector<Node> nodes_;         // nodes_[0]: the root
  std::vector<uint32_t> parent_;    // per node, the lane it is (node · kWidth + lane; the root: 0)
  // Per light in the tree, its node and lane (node · kWidth + lane); kOutside plus their top_ slot
  // for the others (0 for a light left out).
  std::vector<uint32_t> place_;
  static constexpr uint32_t kOutside = 1u << 31;
};

}  // namespace prism
