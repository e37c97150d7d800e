#include "core/render/light_tree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/base/error.h"
#include "materials/bsdf_sample.h"

#ifdef __AVX__
#include <immintrin.h>
#endif

namespace prism {

namespace {

// The solid-angle measure of a cone of normals within θ_o, each emitting within θ_e about itself
// (Conty Estevez & Kulla 2018, eq. 1): the orientation term of the split cost.
float orientation_measure(const LightBounds& b) {
  // The two ends in closed form (most cones of a build are one or the other): every direction,
  // and a single one (π sin² θ_e).
  if (b.cos_theta_o <= -1) return 4 * kPi;
  if (b.cos_theta_o >= 1) return kPi * std::max(0.f, 1 - b.cos_theta_e * b.cos_theta_e);
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

void LightTree::Node::set(int lane, const LightBounds& b, uint32_t to) {
  const Vec3f c = b.bounds.centroid();
  cx[lane] = c.x, cy[lane] = c.y, cz[lane] = c.z;
  // The box's circumsphere, widened by the rounding of the centre.
  const Vec3f far = max(abs(b.bounds.lo), abs(b.bounds.hi));
  radius[lane] = next_float_up(0.5f * length(b.bounds.diagonal()) + 1e-6f * std::max({far.x, far.y, far.z}));
  phi[lane] = b.two_sided ? -b.phi : b.phi;
  wx[lane] = b.w.x, wy[lane] = b.w.y, wz[lane] = b.w.z;
  // A margin for the rounding of merge's trigonometry: the cone only widens.
  const float theta_o = safe_acos(b.cos_theta_o) + 1e-4f;
  cos_o[lane] = theta_o >= kPi ? -1.f : std::cos(theta_o);
  cos_e[lane] = b.cos_theta_e;
  child[lane] = to;
}

namespace {

// Eight floats computed together (GCC's vector extension: AVX where the build has it, else two
// SSE halves); comparisons give lane masks that ?: selects by. (Without AVX, GCC warns that such
// values are returned differently than with it: these functions are internal, so it is no matter.)
#pragma GCC diagnostic ignored "-Wpsabi"
using Lanes = float __attribute__((vector_size(32)));
static_assert(LightTree::kWidth == 8);

Lanes load(const std::array<float, 8>& a) {
  Lanes v;
  std::memcpy(&v, a.data(), sizeof v);
  return v;
}
Lanes splat(float x) { return Lanes{x, x, x, x, x, x, x, x}; }
Lanes max(const Lanes& a, const Lanes& b) { return a > b ? a : b; }
Lanes abs(const Lanes& a) { return a < 0 ? -a : a; }
Lanes sqrt(const Lanes& a) {
#ifdef __AVX__
  return _mm256_sqrt_ps(a);
#else
  Lanes r;
  for (int j = 0; j < 8; ++j) r[j] = std::sqrt(a[j]);
  return r;
#endif
}

}  // namespace

std::array<float, LightTree::kWidth> LightTree::Node::importance(const ShadingPoint& at) const {
  const Lanes zero = splat(0.f), one = splat(1.f);
  const Lanes dx = splat(at.p.x) - load(cx), dy = splat(at.p.y) - load(cy), dz = splat(at.p.z) - load(cz);
  const Lanes r = load(radius), w_x = load(wx), w_y = load(wy), w_z = load(wz);
  const Lanes d2_centre = dx * dx + dy * dy + dz * dz;
  // θ_b: the half-angle of the cone from the point that holds the sphere (inside it: all
  // directions). Near or inside the sphere the distance is taken as its radius: the bound stays finite.
  const auto outside = d2_centre > r * r;
  const Lanes inv_d = one / sqrt(max(d2_centre, splat(1e-30f)));
  // From the lights to the point.
  const Lanes wix = outside ? dx * inv_d : w_x, wiy = outside ? dy * inv_d : w_y, wiz = outside ? dz * inv_d : w_z;
  const Lanes sin_b = outside ? r * inv_d : zero;
  const Lanes cos_b = outside ? sqrt(max(zero, one - sin_b * sin_b)) : -one;
  const Lanes d2 = max(outside ? d2_centre : r * r, splat(1e-30f));
  const Lanes power = load(phi);
  const Lanes cos_w_signed = w_x * wix + w_y * wiy + w_z * wiz;
  const Lanes cos_w = power < 0 ? abs(cos_w_signed) : cos_w_signed;  // two-sided
  const Lanes sin_w = sqrt(max(zero, one - cos_w * cos_w));
  // θ' = max(0, θ_w − θ_o − θ_b), as cos(max(0, a − b)) = 1 if a < b, else cos a cos b + sin a sin b.
  const Lanes co = load(cos_o), so = sqrt(max(zero, one - co * co));
  const auto within = cos_w > co;
  const Lanes cos_x = within ? one : cos_w * co + sin_w * so, sin_x = within ? zero : sin_w * co - cos_w * so;
  const Lanes cos_p = cos_x > cos_b ? one : cos_x * cos_b + sin_x * sin_b;
  Lanes importance = abs(power) * cos_p / d2;
  if (at.n != Vec3f(0.f, 0.f, 0.f)) {  // the cosine at the point, bounded likewise
    const Lanes dot_n = wix * at.n.x + wiy * at.n.y + wiz * at.n.z;
    const Lanes cos_i = at.hemisphere ? -dot_n : abs(dot_n);
    const Lanes sin_i = sqrt(max(zero, one - cos_i * cos_i));
    importance *= max(cos_i > cos_b ? one : cos_i * cos_b + sin_i * sin_b, zero);
  }
  // (cos_p = cos θ_e: a hard-edged spot light's inside.)
  importance = cos_p < load(cos_e) ? zero : max(importance, zero);
  std::array<float, kWidth> out;
  std::memcpy(out.data(), &importance, sizeof importance);
  return out;
}

namespace {

// The sum of a node's importances, added in one order wherever it is taken (sample and pmf agree
// to the last bit).
float total(const std::array<float, LightTree::kWidth>& importance) {
  float sum = 0;
  for (float i : importance) sum += i;
  return sum;
}

}  // namespace

struct LightTree::Binary {
  LightBounds bounds;
  uint32_t first = 0, second = 0;  // children (an inner node)
  uint32_t light = 0;              // a leaf's
  uint32_t lights = 1;             // below it
};

namespace {

struct Item {
  uint32_t light;
  Vec3f centroid;  // of its box: where the splits place it
  LightBounds bounds;
};

// Each bucket's bounds, for the split cost: the box, power and widest emission angle of its lights,
// and a cone about their mean normal that holds every light's cone. Not always the smallest cone,
// which pairwise merges come nearer to at the price of arc cosines per light: the buckets only
// steer the split, and each node's own bounds are merged exactly from its children.
template <int kBuckets, class BucketOf>
std::array<LightBounds, kBuckets> bucket_bounds(const std::vector<Item>& items, size_t begin, size_t end,
                                                const BucketOf& bucket_of) {
  std::array<LightBounds, kBuckets> bucket{};
  std::array<Vec3f, kBuckets> normal_sum{};
  for (size_t i = begin; i < end; ++i) {
    const LightBounds& light = items[i].bounds;
    const size_t b = size_t(bucket_of(items[i]));
    LightBounds& k = bucket[b];
    k.cos_theta_e = k.phi == 0 ? light.cos_theta_e : std::min(k.cos_theta_e, light.cos_theta_e);
    k.bounds.extend(light.bounds);
    k.phi += light.phi;
    k.two_sided = k.two_sided || light.two_sided;
    normal_sum[b] += light.w * light.phi;
  }
  for (size_t b = 0; b < kBuckets; ++b) {
    const float length2 = length_squared(normal_sum[b]);
    bucket[b].w = length2 > 0 ? normal_sum[b] / std::sqrt(length2) : Vec3f(0.f, 0.f, 1.f);
  }
  // cos(θ_d + θ_o), the widest angle from the bucket's axis to a light's normals (every direction
  // once the sum passes π: cos θ_d + cos θ_o ≤ 0).
  for (size_t i = begin; i < end; ++i) {
    const LightBounds& light = items[i].bounds;
    LightBounds& k = bucket[size_t(bucket_of(items[i]))];
    const float cos_d = clamp(dot(k.w, light.w), -1.f, 1.f), cos_o = light.cos_theta_o;
    const float cos_sum =
        cos_d + cos_o <= 0 ? -1.f : cos_d * cos_o - std::sqrt((1 - cos_d * cos_d) * std::max(0.f, 1 - cos_o * cos_o));
    k.cos_theta_o = std::min(k.cos_theta_o, cos_sum);
  }
  return bucket;
}

// The binary tree over items[begin, end) in nodes[base, base + 2 (end − begin) − 1): its root at
// base, then its first child's subtree, then its second's, so that subtrees are built apart, the
// large ones in parallel, always alike. Below depth kSahDepth the splits halve by count, which
// bounds the depth (and the recursion).
template <class Binary>
void build_binary(std::vector<Item>& items, size_t begin, size_t end, size_t base, int depth,
                  std::vector<Binary>& nodes) {
  constexpr int kSahDepth = 64;
  Binary& node = nodes[base];
  node.lights = uint32_t(end - begin);
  if (end - begin == 1) {
    node.bounds = items[begin].bounds;
    node.light = items[begin].light;
    return;
  }
  Bounds3f box, centroids;
  for (size_t i = begin; i < end; ++i) {
    box.extend(items[i].bounds.bounds);
    centroids.extend(items[i].centroid);
  }
  // The split of least cost between 12 buckets along an axis, by the lights' centroids.
  constexpr int kBuckets = 12;
  float best_cost = kInfinity;
  int best_axis = -1, best_bucket = -1;
  const auto bucket_of = [&](const Item& item, int axis) {
    const float extent = centroids.hi[axis] - centroids.lo[axis];
    const int b = int(kBuckets * ((item.centroid[axis] - centroids.lo[axis]) / extent));
    return std::clamp(b, 0, kBuckets - 1);
  };
  // Each axis's best split (its cost and bucket), the axes of a large range in parallel.
  std::array<std::pair<float, int>, 3> split;
  const auto best_along = [&](int axis) {
    split[size_t(axis)] = {kInfinity, -1};
    if (!(centroids.hi[axis] > centroids.lo[axis]) || depth >= kSahDepth || end - begin == 2) return;
    std::array<LightBounds, kBuckets> bucket =
        bucket_bounds<kBuckets>(items, begin, end, [&](const Item& item) { return bucket_of(item, axis); });
    std::array<LightBounds, kBuckets> below{};  // buckets [0, i]
    below[0] = bucket[0];
    for (size_t i = 1; i < kBuckets; ++i) below[i] = merge(below[i - 1], bucket[i]);
    LightBounds above;  // buckets (i, kBuckets)
    for (int i = kBuckets - 2; i >= 0; --i) {
      above = merge(above, bucket[size_t(i) + 1]);
      // (After an empty bucket, the split is the one before it.)
      if (bucket[size_t(i)].phi == 0 || below[size_t(i)].phi == 0 || above.phi == 0) continue;
      const float cost = split_cost(below[size_t(i)], box, axis) + split_cost(above, box, axis);
      if (cost < split[size_t(axis)].first) split[size_t(axis)] = {cost, i};
    }
  };
  if (end - begin > 65536)
    tbb::parallel_invoke([&] { best_along(0); }, [&] { best_along(1); }, [&] { best_along(2); });
  else
    for (int axis = 0; axis < 3; ++axis) best_along(axis);
  for (int axis = 0; axis < 3; ++axis)
    if (split[size_t(axis)].first < best_cost)
      best_cost = split[size_t(axis)].first, best_axis = axis, best_bucket = split[size_t(axis)].second;
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
                     [&](const Item& a, const Item& b) { return a.centroid[axis] < b.centroid[axis]; });
  }
  const size_t first = base + 1, second = base + 2 * (mid - begin);
  const auto build_first = [&] { build_binary(items, begin, mid, first, depth + 1, nodes); };
  const auto build_second = [&] { build_binary(items, mid, end, second, depth + 1, nodes); };
  if (end - begin > 4096)
    tbb::parallel_invoke(build_first, build_second);
  else
    build_first(), build_second();
  node.first = uint32_t(first), node.second = uint32_t(second);
  node.bounds = merge(nodes[first].bounds, nodes[second].bounds);
}

}  // namespace

LightTree::LightTree(std::span<const std::optional<LightBounds>> bounds, std::span<const float> power) {
  place_.assign(bounds.size(), kOutside);
  std::vector<float> top_power{0.f};
  std::vector<Item> items;
  items.reserve(bounds.size());
  for (uint32_t i = 0; i < bounds.size(); ++i) {
    if (!bounds[i]) {
      place_[i] = kOutside | uint32_t(top_power.size());
      infinite_.push_back(i);
      top_power.push_back(power[i]);
    } else if (bounds[i]->phi > 0) {
      items.push_back({i, bounds[i]->bounds.centroid(), *bounds[i]});
      top_power[0] += power[i];
    }
  }
  top_ = PowerLightSampler(top_power);
  if (items.empty()) return;
  if (items.size() >= (1u << 27)) fail("more than 2^27 emitters for the light tree");
  std::vector<Binary> binary(2 * items.size() - 1);
  build_binary(items, 0, items.size(), 0, 0, binary);
  items = {};
  collapse(binary, 0, 0);
}

// The node whose lanes are the binary tree's nodes below `root`, up to eight: the one with the most
// lights below it opened while there is room. So each choice is among eight groups as alike as the
// tree allows; cuts that pack the nodes fuller put uneven groups side by side, and cost more noise
// than the memory they save. Lanes that stay empty have no power and an emission angle no point
// is within (cos θ_e = 2).
void LightTree::collapse(const std::vector<Binary>& binary, uint32_t root, uint32_t parent_lane) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  parent_.push_back(parent_lane);
  const LightBounds empty{Bounds3f{{0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}}, {0.f, 0.f, 1.f}, 0.f, 1.f, 2.f};
  for (int lane = 0; lane < kWidth; ++lane) nodes_[index].set(lane, empty, kLeaf);
  std::vector<uint32_t> lanes{root};
  while (lanes.size() < size_t(kWidth)) {
    size_t fullest = 0;
    for (size_t i = 1; i < lanes.size(); ++i)
      if (binary[lanes[i]].lights > binary[lanes[fullest]].lights) fullest = i;
    const Binary& open = binary[lanes[fullest]];
    if (open.lights == 1) break;
    lanes[fullest] = open.first;
    lanes.push_back(open.second);
  }
  for (int lane = 0; lane < int(lanes.size()); ++lane) {
    const Binary& b = binary[lanes[size_t(lane)]];
    if (b.lights == 1) {
      nodes_[index].set(lane, b.bounds, kLeaf | b.light);
      place_[b.light] = index * kWidth + uint32_t(lane);
    } else {
      nodes_[index].set(lane, b.bounds, uint32_t(nodes_.size()));
      collapse(binary, lanes[size_t(lane)], index * kWidth + uint32_t(lane));
    }
  }
}

std::optional<SampledLight> LightTree::sample(const ShadingPoint& at, float u) const {
  if (top_.empty()) return std::nullopt;
  const uint32_t slot = top_.sample_reusing(u);
  float pmf = top_.pmf(slot);
  if (slot > 0) return SampledLight{infinite_[slot - 1], pmf};
  if (nodes_.empty() || pmf == 0) return std::nullopt;
  for (uint32_t node = 0;;) {
    const std::array<float, kWidth> importance = nodes_[node].importance(at);
    const float sum = total(importance);
    if (!(sum > 0)) return std::nullopt;
    // The lane whose share of [0, sum) holds u · sum (the last that can be chosen, if rounding
    // leaves u · sum beyond them all).
    const float target = u * sum;
    int lane = kWidth - 1;
    while (!(importance[size_t(lane)] > 0)) --lane;
    float below = 0;
    for (int j = 0; j < lane; ++j) {
      if (!(importance[size_t(j)] > 0)) continue;
      if (target < below + importance[size_t(j)]) {
        lane = j;
        break;
      }
      below += importance[size_t(j)];
    }
    const float chosen = importance[size_t(lane)];
    pmf *= chosen / sum;
    u = within_lobe(target, below, chosen);
    const uint32_t child = nodes_[node].child[size_t(lane)];
    if (child & kLeaf) return SampledLight{child & ~kLeaf, pmf};
    node = child;
  }
}

float LightTree::pmf(const ShadingPoint& at, uint32_t light) const {
  const uint32_t place = place_[light];
  if (place & kOutside) return place == kOutside ? 0.f : top_.pmf(place & ~kOutside);
  // The lanes from the light up to the root, then their probabilities multiplied from the root
  // down, as sample multiplies them.
  std::array<uint32_t, 256> path;
  int depth = 0;
  for (uint32_t node = place / kWidth, lane = place % kWidth;; ++depth) {
    path[size_t(depth)] = node * kWidth + lane;
    if (node == 0) break;
    lane = parent_[node] % kWidth, node = parent_[node] / kWidth;
  }
  float pmf = top_.pmf(0);
  for (; depth >= 0; --depth) {
    const uint32_t node = path[size_t(depth)] / kWidth, lane = path[size_t(depth)] % kWidth;
    const std::array<float, kWidth> importance = nodes_[node].importance(at);
    const float sum = total(importance);
    if (!(sum > 0) || !(importance[lane] > 0)) return 0;
    pmf *= importance[lane] / sum;
  }
  return pmf;
}

}  // namespace prism
