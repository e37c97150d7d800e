#pragma once
// A triangle of a textured emitter, sampled in proportion to the light it emits: the triangle is
// cut into k² equal sub-triangles (k rows of the regular subdivision, each about a texel of the
// emission texture), each chosen with probability in proportion to the emitted luminance over it
// (its texels, times the alpha coverage), and a point uniform within the one chosen. A bright
// detail in a dark texture is then found by every light sample rather than by chance. Its
// density is a multiple of the uniform one (1 / area), given at any point for MIS.

#include <array>
#include <span>
#include <vector>

#include "core/base/distribution.h"
#include "core/base/vec.h"
#include "core/scene/scene.h"

namespace prism {

class TexturedEmission {
 public:
  // How many texels of its emission texture triangle `prim` of the mesh covers (0 without
  // texture coordinates).
  static float footprint(const Mesh& mesh, uint32_t prim, const Material& material);
  // The emitted luminance over each of the k² sub-triangles of triangle `prim`, relative to the
  // material's untextured emission: its texture and alpha coverage averaged over four points.
  static std::vector<float> weights(const Mesh& mesh, uint32_t prim, const Material& material, int k);

  // `k` rows; weight[i] the emitted luminance over sub-triangle i (in sub_triangle's order).
  TexturedEmission(int k, std::span<const float> weight) : k_(k), distribution_(weight) {}

  // The sub-triangles' number i of k², and their corners in the triangle's barycentric
  // coordinates (b1, b2): row r (from the b1 = 0 edge) holds k − r upright triangles and k − r − 1
  // inverted ones between them.
  static int count(int k) { return k * k; }
  static std::array<Vec2f, 3> corners(int k, int i);

  struct Sample {
    Vec3f b;        // barycentrics of the point
    float density;  // relative to uniform over the triangle
  };
  Sample sample(Vec2f u) const;
  // The density relative to uniform at barycentrics b.
  float density(const Vec3f& b) const;

 private:
  int k_;
  PiecewiseConstant1D distribution_;  // over the sub-triangles; its pdf is the relative density
};

}  // namespace prism
