#pragma once
// How a light is chosen for next-event estimation at a point (--light-sampler): the ways,
// registered in the table kLightSamplers below, behind one interface the integrators call.
//   power: in proportion to the light's power, wherever the point is (PowerLightSampler);
//   tree:  by a light tree's estimate of what each light brings to the point (LightTree);
//   auto:  the tree where the scene has three finite lights or more. With one or two (a single
//          emissive quad is two) it has little to choose between and only costs time
//          (docs/performance.md, "Light sampling").
// Light paths (BDPT, VCM, light tracing) start from a light chosen by power alone (by_power): an
// emission has no point to choose for.

#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "core/render/light_tree.h"
#include "core/render/lights.h"
#include "core/render/power_light_sampler.h"

namespace prism {

enum class LightSamplerKind { automatic, tree, power };

struct LightSamplerInfo {
  LightSamplerKind kind;
  std::string_view name;         // --light-sampler NAME, prism.lightSampler
  std::string_view description;  // one line, for --help
};

inline constexpr std::array kLightSamplers{
    LightSamplerInfo{LightSamplerKind::automatic, "auto", "tree for scenes of three finite lights or more, else power"},
    LightSamplerInfo{LightSamplerKind::tree, "tree",
                     "a light tree: lights chosen by what they may bring to the point (position, power, orientation)"},
    LightSamplerInfo{LightSamplerKind::power, "power", "lights chosen by their power alone"},
};
inline constexpr LightSamplerKind kDefaultLightSampler = LightSamplerKind::automatic;

// The row of kLightSamplers named `name`, or null.
inline const LightSamplerInfo* find_light_sampler(std::string_view name) {
  for (const LightSamplerInfo& l : kLightSamplers)
    if (l.name == name) return &l;
  return nullptr;
}
inline std::string_view light_sampler_name(LightSamplerKind kind) {
  for (const LightSamplerInfo& l : kLightSamplers)
    if (l.kind == kind) return l.name;
  return "?";
}

class LightSampler {
 public:
  LightSampler() = default;
  // Light i's power[i] and, for a finite light, its bounds[i]. A tree is built only where it has a
  // choice to make: for two finite lights or more (three for auto).
  LightSampler(LightSamplerKind kind, std::span<const std::optional<LightBounds>> bounds, std::span<const float> power)
      : power_(std::vector<float>(power.begin(), power.end())) {
    size_t finite = 0;
    for (const auto& b : bounds) finite += b.has_value();
    if ((kind == LightSamplerKind::tree && finite >= 2) || (kind == LightSamplerKind::automatic && finite >= 3))
      tree_.emplace(bounds, power);
  }

  bool empty() const { return power_.empty(); }
  // A light for the point of ctx, with the probability of choosing it there.
  std::optional<SampledLight> sample(const LightSampleContext& ctx, float u) const {
    if (tree_) return tree_->sample(shading_point(ctx), u);
    if (power_.empty()) return std::nullopt;
    const uint32_t light = power_.sample(u);
    return SampledLight{light, power_.pmf(light)};
  }
  // The probability that sample(ctx, ·) chooses `light`.
  float pmf(const LightSampleContext& ctx, uint32_t light) const {
    return tree_ ? tree_->pmf(shading_point(ctx), light) : power_.pmf(light);
  }
  // The light a light path starts from, chosen by power.
  const PowerLightSampler& by_power() const { return power_; }
  const LightTree* tree() const { return tree_ ? &*tree_ : nullptr; }

 private:
  // An opaque surface receives light on its reflection side only; otherwise either side counts.
  static ShadingPoint shading_point(const LightSampleContext& ctx) {
    const bool hemisphere = ctx.reflect_axis != Vec3f(0.f, 0.f, 0.f);
    return {ctx.p, hemisphere ? ctx.reflect_axis : ctx.n, hemisphere};
  }

  PowerLightSampler power_;
  std::optional<LightTree> tree_;
};

}  // namespace prism
