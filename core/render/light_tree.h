#pragma once
// A light tree (Conty Estevez & Kulla, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting", HPG 2018; built and walked as pbrt-v4's BVHLightSampler, §12.6.3): a bounding volume
// hierarchy over the lights whose nodes bound their lights' positions, power and emission cones
// (LightBounds). The light for a shading point is found by descending from the root, each child
// taken with probability in proportion to its importance at the point; a light's probability at
// any point is the product along its path from the root, so MIS with BSDF sampling stays exact.
// Infinite lights (directional, environment) stay outside the tree: the tree and each of them are
// chosen first by power, as PowerLightSampler chooses.

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
  LightTree() = default;
  // bounds[i] of light i, or none for an infinite light; power[i] as PowerLightSampler's. Lights
  // of zero power are left out: never chosen.
  LightTree(std::span<const std::optional<LightBounds>> bounds, std::span<const float> power);

  std::optional<SampledLight> sample(const ShadingPoint& at, float u) const;
  // The probability that sample(at, ·) chooses `light`.
  float pmf(const ShadingPoint& at, uint32_t light) const;

  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const { return nodes_.size() * sizeof(Node) + trail_.size() * sizeof(uint64_t); }

 private:
  // A node's bounds as the importance reads them: the box's bounding sphere (44 bytes).
  struct Node {
    Vec3f centre;
    float radius;
    float phi;
    Vec3f w;
    float cos_theta_o, cos_theta_e;
    uint32_t index : 30;  // a leaf's light, or an inner node's second child (its first follows it)
    uint32_t leaf : 1, two_sided : 1;

    static Node make(const LightBounds& b, uint32_t index, bool leaf);
    // An upper bound, up to a factor common to all nodes, of the light the node's emitters can
    // bring to the point: phi · cos θ' / d², with θ' the least angle between an emitter's cone
    // and the direction to the point over the sphere, times the cosine at the point likewise
    // bounded when a normal is given (Conty Estevez & Kulla 2018, eq. 3; pbrt-v4 §12.6.3).
    float importance(const ShadingPoint& at) const;
  };
  struct Item {
    uint32_t light;
    LightBounds bounds;
  };
  // Nodes for items[begin, end) from nodes_.size() on: the first child follows its parent at once.
  // `trail` holds the child taken at each depth so far, depth 0 in bit 0.
  LightBounds build(std::vector<Item>& items, size_t begin, size_t end, uint64_t trail, int depth, int sah_depth);

  PowerLightSampler top_;          // slot 0: the tree; then the infinite lights
  std::vector<uint32_t> infinite_;  // the light in top_'s slot 1 + i
  std::vector<Node> nodes_;
  // Per light in the tree, its path from the root as in build; for the others kOutside plus their
  // top_ slot (0 for a light left out).
  std::vector<uint64_t> trail_;
  static constexpr uint64_t kOutside = uint64_t(1) << 63;  // no trail is that deep
};

}  // namespace prism
