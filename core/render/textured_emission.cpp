#include "core/render/textured_emission.h"

#include <algorithm>
#include <cmath>

#include "core/base/warp.h"

namespace prism {

namespace {

// The offset of row r in the numbering: the rows before it hold 2(k − r') − 1 sub-triangles each.
int row_offset(int k, int r) { return r * (2 * k - r); }

}  // namespace

std::array<Vec2f, 3> TexturedEmission::corners(int k, int i) {
  // The row r with row_offset(r) ≤ i < row_offset(r + 1): r = k − √(k² − i), then rounding undone.
  int r = std::clamp(int(float(k) - std::sqrt(float(k * k - i))), 0, k - 1);
  while (r + 1 < k && row_offset(k, r + 1) <= i) ++r;
  while (r > 0 && row_offset(k, r) > i) --r;
  const int j = i - row_offset(k, r);
  const float s = float(r), t = float(j / 2), inv = 1.f / float(k);
  if (j % 2 == 0) return {Vec2f(s, t) * inv, Vec2f(s + 1, t) * inv, Vec2f(s, t + 1) * inv};  // upright
  return {Vec2f(s + 1, t + 1) * inv, Vec2f(s, t + 1) * inv, Vec2f(s + 1, t) * inv};          // inverted
}

float TexturedEmission::footprint(const Mesh& mesh, uint32_t prim, const Material& material) {
  const Texture& texture = *material.emission_texture;
  const auto& uv = mesh.uv[size_t(texture.texcoord)];
  if (uv.empty()) return 0;
  const Vec2f a = uv[mesh.indices[3 * prim]], b = uv[mesh.indices[3 * prim + 1]], c = uv[mesh.indices[3 * prim + 2]];
  const Vec2f e1 = b - a, e2 = c - a;
  const float texels =
      0.5f * std::abs(e1.x * e2.y - e1.y * e2.x) * float(texture.image->width()) * float(texture.image->height());
  return std::isfinite(texels) ? texels : 0.f;
}

std::vector<float> TexturedEmission::weights(const Mesh& mesh, uint32_t prim, const Material& material, int k) {
  std::vector<float> w(size_t(count(k)));
  for (int i = 0; i < count(k); ++i) {
    const auto c = corners(k, i);
    const Vec2f centre = (c[0] + c[1] + c[2]) * (1.f / 3);
    const Vec2f points[4] = {centre, (centre + c[0]) * 0.5f, (centre + c[1]) * 0.5f, (centre + c[2]) * 0.5f};
    float sum = 0;
    for (const Vec2f& st : points) {
      const float b[3] = {1 - st.x - st.y, st.x, st.y};
      const SurfacePoint at = mesh.attributes_at(prim, b);
      sum += material.emission_scale(at) * material.coverage(at);
    }
    w[size_t(i)] = std::isfinite(sum) ? std::max(sum / 4, 0.f) : 0.f;
  }
  return w;
}

TexturedEmission::Sample TexturedEmission::sample(Vec2f u) const {
  const auto chosen = distribution_.sample(u.x);
  const auto c = corners(k_, chosen.bucket);
  const Vec3f w = sample_uniform_triangle({std::min(chosen.within, 0x1.fffffep-1f), u.y});
  const Vec2f st = c[0] * w.x + c[1] * w.y + c[2] * w.z;
  return {{1 - st.x - st.y, st.x, st.y}, chosen.pdf};
}

float TexturedEmission::density(const Vec3f& b) const {
  // The cell (r, j) of the k × k grid over (b1, b2), and which of its two halves.
  const float s = std::clamp(b.y, 0.f, 1.f) * float(k_), t = std::clamp(b.z, 0.f, 1.f) * float(k_);
  const int r = std::min(int(s), k_ - 1), j = std::min(int(t), k_ - 1 - r);
  const bool inverted = (s - float(r)) + (t - float(j)) > 1 && r + j < k_ - 1;
  return distribution_.pdf(row_offset(k_, r) + 2 * j + (inverted ? 1 : 0));
}

}  // namespace prism
