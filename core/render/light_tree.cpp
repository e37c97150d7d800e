#include "core/render/light_tree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "core/base/error.h"

namespace prism {

namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// cos(max(0, a − b)) and sin(max(0, a − b)) for angles a, b in [0, π] given by their sines and cosines.
float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 1.f : cos_a * cos_b + sin_a * sin_b;
}
float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 0.f : sin_a * cos_b - cos_a * sin_b;
}

// The solid-angle measure of a cone of normals within θ_o, each emitting within θ_e about itself
// (Conty Estevez & Kulla 2018, eq. 1): the orientation term of the split cost.
float orientation_measure(const LightBounds& b) {
  const float theta_o = safe_acos(b.cos_theta_o), theta_e = safe_acos(b.cos_theta_e);
  const float theta_w = std::min(theta_o + theta_e, kPi);
  const float sin_o = safe_sqrt(1 - b.cos_theta_o * b.cos_theta_o);
  return 2 * kPi * (1 - b.cos_theta_o) +
         kPi / 2 * (2 * theta_w * sin_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_o + b.cos_theta_o);
}

float surface_area(const Bounds3f& b) {
  const Vec3f d = b.diagonal();
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The cost of a child with bounds b when its parent, of box `parent`, splits along `axis`: power
// times orientation measure times area, with long thin boxes split across their length preferred
// (the regularisation factor K_r of Conty Estevez & Kulla 2018, §4.4).
float split_cost(const LightBounds& b, const Bounds3f& parent, int axis) {
  if (b.phi == 0) return 0;
  const Vec3f d = parent.diagonal();
  const float kr = std::max({d.x, d.y, d.z}) / d[axis];
  return kr * b.phi * orientation_measure(b) * surface_area(b.bounds);
}

}  // namespace

LightTree::Node LightTree::Node::make(const LightBounds& b, uint32_t index, bool leaf) {
  Node n;
  n.centre = b.bounds.centroid();
  // The box's circumsphere, widened by the rounding of the centre.
  const Vec3f far = max(abs(b.bounds.lo), abs(b.bounds.hi));
  n.radius = next_float_up(0.5f * length(b.bounds.diagonal()) + 1e-6f * std::max({far.x, far.y, far.z}));
  n.phi = b.phi;
  n.w = b.w;
  // A margin for the rounding of merge's trigonometry: the cone only widens.
  const float theta_o = safe_acos(b.cos_theta_o) + 1e-4f;
  n.cos_theta_o = theta_o >= kPi ? -1.f : std::cos(theta_o);
  n.cos_theta_e = b.cos_theta_e;
  n.index = index;
  n.leaf = leaf;
  n.two_sided = b.two_sided;
  return n;
}

float LightTree::Node::importance(const ShadingPoint& at) const {
  const Vec3f d = at.p - centre;
  const float d2_centre = length_squared(d), r2 = radius * radius;
  // θ_b: the half-angle of the cone from the point that holds the sphere (inside it: all directions).
  // Near or inside the sphere the distance is taken as its radius: the bound stays finite.
  float cos_b = -1, sin_b = 0, d2 = r2;
  Vec3f wi = w;  // from the lights to the point
  if (d2_centre > r2) {
    const float inv_d = 1 / std::sqrt(d2_centre);
    wi = d * inv_d;
    sin_b = radius * inv_d, cos_b = safe_sqrt(1 - sin_b * sin_b), d2 = d2_centre;
  }
  if (!(d2 > 0)) d2 = 1e-30f;
  float cos_w = dot(w, wi);
  if (two_sided) cos_w = std::abs(cos_w);
  const float sin_w = safe_sqrt(1 - cos_w * cos_w);
  const float sin_o = safe_sqrt(1 - cos_theta_o * cos_theta_o);
  // θ' = max(0, θ_w − θ_o − θ_b)
  const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_theta_o);
  const float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_theta_o);
  const float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_p < cos_theta_e) return 0;  // (equal: a hard-edged spot light's inside)
  float importance = phi * cos_p / d2;
  if (at.n != Vec3f(0.f, 0.f, 0.f)) {
    const float cos_i = at.hemisphere ? -dot(wi, at.n) : std::abs(dot(wi, at.n));
    importance *= std::max(cos_sub_clamped(safe_sqrt(1 - cos_i * cos_i), cos_i, sin_b, cos_b), 0.f);
  }
  return std::max(importance, 0.f);
}

LightTree::LightTree(std::span<const std::optional<LightBounds>> bounds, std::span<const float> power) {
  trail_.assign(bounds.size(), kOutside);
  std::vector<float> top_power{0.f};
  std::vector<Item> items;
  for (uint32_t i = 0; i < bounds.size(); ++i) {
    if (!bounds[i]) {
      trail_[i] = kOutside | top_power.size();
      infinite_.push_back(i);
      top_power.push_back(power[i]);
    } else if (bounds[i]->phi > 0) {
      items.push_back({i, *bounds[i]});
      top_power[0] += power[i];
    }
  }
  if (items.size() >= (1u << 30)) fail("more than 2^30 lights");
  top_ = PowerLightSampler(top_power);
  if (items.empty()) return;
  nodes_.reserve(2 * items.size() - 1);
  // Split by cost while the depth leaves room for balanced splits below (trails of 64 bits).
  const int log2_n = int(std::bit_width(items.size() - 1));
  build(items, 0, items.size(), 0, 0, 63 - log2_n);
}

LightBounds LightTree::build(std::vector<Item>& items, size_t begin, size_t end, uint64_t trail, int depth,
                             int sah_depth) {
  const uint32_t index = uint32_t(nodes_.size());
  if (end - begin == 1) {
    trail_[items[begin].light] = trail;
    nodes_.push_back(Node::make(items[begin].bounds, items[begin].light, true));
    return items[begin].bounds;
  }
  Bounds3f box, centroids;
  for (size_t i = begin; i < end; ++i) {
    box.extend(items[i].bounds.bounds);
    centroids.extend(items[i].bounds.bounds.centroid());
  }
  // The split of least cost between 12 buckets along an axis, by the lights' centroids.
  constexpr int kBuckets = 12;
  float best_cost = kInfinity;
  int best_axis = -1, best_bucket = -1;
  const auto bucket_of = [&](const Item& item, int axis) {
    const float extent = centroids.hi[axis] - centroids.lo[axis];
    const int b = int(kBuckets * ((item.bounds.bounds.centroid()[axis] - centroids.lo[axis]) / extent));
    return std::clamp(b, 0, kBuckets - 1);
  };
  for (int axis = 0; axis < 3 && depth < sah_depth; ++axis) {
    if (!(centroids.hi[axis] > centroids.lo[axis])) continue;
    std::array<LightBounds, kBuckets> bucket{};
    for (size_t i = begin; i < end; ++i) {
      LightBounds& b = bucket[bucket_of(items[i], axis)];
      b = merge(b, items[i].bounds);
    }
    std::array<LightBounds, kBuckets> below{};  // buckets [0, i]
    below[0] = bucket[0];
    for (int i = 1; i < kBuckets; ++i) below[i] = merge(below[i - 1], bucket[i]);
    LightBounds above;  // buckets (i, kBuckets)
    for (int i = kBuckets - 2; i >= 0; --i) {
      above = merge(above, bucket[i + 1]);
      if (below[i].phi == 0 || above.phi == 0) continue;
      const float cost = split_cost(below[i], box, axis) + split_cost(above, box, axis);
      if (cost < best_cost) best_cost = cost, best_axis = axis, best_bucket = i;
    }
  }
  size_t mid = (begin + end) / 2;
  if (best_axis >= 0) {
    mid = size_t(std::partition(items.begin() + ptrdiff_t(begin), items.begin() + ptrdiff_t(end),
                                [&](const Item& item) { return bucket_of(item, best_axis) <= best_bucket; }) -
                 items.begin());
  }
  if (best_axis < 0 || mid == begin || mid == end) {
    // Equal centroids, or too deep for cost splits: halves by count, along the widest axis.
    const Vec3f d = centroids.diagonal();
    const int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
    mid = (begin + end) / 2;
    std::nth_element(items.begin() + ptrdiff_t(begin), items.begin() + ptrdiff_t(mid), items.begin() + ptrdiff_t(end),
                     [&](const Item& a, const Item& b) {
                       return a.bounds.bounds.centroid()[axis] < b.bounds.bounds.centroid()[axis];
                     });
  }
  nodes_.emplace_back();  // filled once its children are
  const LightBounds first = build(items, begin, mid, trail, depth + 1, sah_depth);
  const uint32_t second_index = uint32_t(nodes_.size());
  const LightBounds second = build(items, mid, end, trail | uint64_t(1) << depth, depth + 1, sah_depth);
  const LightBounds all = merge(first, second);
  nodes_[index] = Node::make(all, second_index, false);
  return all;
}

std::optional<SampledLight> LightTree::sample(const ShadingPoint& at, float u) const {
  if (top_.empty()) return std::nullopt;
  const uint32_t slot = top_.sample_reusing(u);
  float pmf = top_.pmf(slot);
  if (slot > 0) return SampledLight{infinite_[slot - 1], pmf};
  if (nodes_.empty() || pmf == 0) return std::nullopt;
  for (uint32_t i = 0;;) {
    const Node& node = nodes_[i];
    if (node.leaf) {
      if (i == 0 && !(node.importance(at) > 0)) return std::nullopt;
      return SampledLight{node.index, pmf};
    }
    const float c0 = nodes_[i + 1].importance(at), c1 = nodes_[node.index].importance(at);
    if (!(c0 + c1 > 0)) return std::nullopt;
    const float p0 = c0 / (c0 + c1);
    if (u < p0) {
      i = i + 1, pmf *= p0, u = std::min(u / p0, kOneMinusEpsilon);
    } else {
      i = node.index, pmf *= 1 - p0, u = std::min((u - p0) / (1 - p0), kOneMinusEpsilon);
    }
  }
}

float LightTree::pmf(const ShadingPoint& at, uint32_t light) const {
  uint64_t trail = trail_[light];
  if (trail & kOutside) return trail == kOutside ? 0.f : top_.pmf(uint32_t(trail & ~kOutside));
  float pmf = top_.pmf(0);
  for (uint32_t i = 0;;) {
    const Node& node = nodes_[i];
    if (node.leaf) return i > 0 || node.importance(at) > 0 ? pmf : 0.f;
    const float c0 = nodes_[i + 1].importance(at), c1 = nodes_[node.index].importance(at);
    if (!(c0 + c1 > 0)) return 0;
    const float p0 = c0 / (c0 + c1);
    if (trail & 1)
      i = node.index, pmf *= 1 - p0;
    else
      i = i + 1, pmf *= p0;
    trail >>= 1;
  }
}

}  // namespace prism
