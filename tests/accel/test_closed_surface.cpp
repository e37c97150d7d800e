// enclosed_side: which meshes are closed, and on which side of their normals the volume lies.

#include <algorithm>
#include <catch2/catch.hpp>

#include "accel/closed_surface.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

int side_of(const Mesh& m) { return enclosed_side(m.positions, m.indices); }

Mesh joined(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const uint32_t offset = uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (uint32_t i : b.indices) m.indices.push_back(i + offset);
  return m;
}

Mesh reversed(Mesh m) {
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
  return m;
}

// A unit cube of six quads, each with its own four vertices (split as a texture's seams split
// them), its faces' fronts outwards.
Mesh cube() {
  const Vec3f x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1}, o{0, 0, 0};
  Mesh m;
  for (const Mesh& face : {test::make_quad(o, y, x, 0), test::make_quad(z, x, y, 0), test::make_quad(o, x, z, 0),
                           test::make_quad(y, z, x, 0), test::make_quad(o, z, y, 0), test::make_quad(x, y, z, 0)})
    m = joined(m, face);
  return m;
}

}  // namespace

TEST_CASE("enclosed_side: closed meshes, and on which side of their normals the volume lies") {
  const Mesh sphere = test::make_icosphere({0.3f, -2, 5}, 1.5f, 2, 0);
  CHECK(side_of(sphere) == -1);  // counter-clockwise seen from outside: the normals point out
  CHECK(side_of(reversed(sphere)) == 1);
  CHECK(side_of(cube()) == -1);  // its faces' split vertices joined by position
  // −0 and +0 are one position.
  Mesh signed_zero = cube();
  for (size_t v = 0; v < 4; ++v)
    for (int a = 0; a < 3; ++a)
      if (signed_zero.positions[v][a] == 0) signed_zero.positions[v][a] = -0.f;
  CHECK(side_of(signed_zero) == -1);
  // Separate closed parts, wound alike; and wound differently (a hollow shell's inner wall faces
  // its cavity, but so does an inside-out sphere: left out).
  CHECK(side_of(joined(sphere, test::make_icosphere({5, 0, 0}, 1, 1, 0))) == -1);
  CHECK(side_of(joined(sphere, reversed(test::make_icosphere({5, 0, 0}, 1, 1, 0)))) == 0);
  // A triangle with two vertices at one position cancels itself.
  Mesh degenerate = sphere;
  degenerate.indices.insert(degenerate.indices.end(), {0, 0, 1});
  CHECK(side_of(degenerate) == -1);
}

TEST_CASE("enclosed_side: open, non-manifold, inconsistent and flat meshes are not closed") {
  const Mesh sphere = test::make_icosphere({0, 0, 0}, 1, 2, 0);
  Mesh open = sphere;
  open.indices.resize(open.indices.size() - 3);  // one triangle missing
  CHECK(side_of(open) == 0);
  Mesh fin = sphere;  // a third triangle on one edge
  fin.positions.push_back({3, 3, 3});
  fin.indices.insert(fin.indices.end(), {sphere.indices[0], sphere.indices[1], uint32_t(fin.positions.size() - 1)});
  CHECK(side_of(fin) == 0);
  Mesh flipped = sphere;  // one triangle wound against its neighbours
  std::swap(flipped.indices[1], flipped.indices[2]);
  CHECK(side_of(flipped) == 0);
  Mesh seam = sphere;  // a vertex split into two a rounding apart: the surface has a crack
  seam.positions.push_back(seam.positions[seam.indices[0]] * (1 + 0x1p-23f));
  seam.indices[0] = uint32_t(seam.positions.size() - 1);
  CHECK(side_of(seam) == 0);
  // A sheet's two faces back to back: every edge paired, no volume.
  const Mesh sheet = test::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  CHECK(side_of(joined(sheet, reversed(sheet))) == 0);
  CHECK(side_of(sheet) == 0);
  CHECK(side_of(Mesh{}) == 0);
}
