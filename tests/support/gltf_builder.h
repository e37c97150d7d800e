#pragma once
// Small glTF files built in code for the tests: binary data packed into one embedded buffer, one
// bufferView per accessor, and the rest of the JSON written by the test.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/test_scenes.h"  // base64

namespace prism::test {

struct GltfBuilder {
  // Accessors of floats ("SCALAR", "VEC3", "VEC4", "MAT4", ...) and of u16 indices or joints;
  // each returns the accessor's index.
  int floats(const std::vector<float>& values, const std::string& type);
  int u16(const std::vector<uint16_t>& values, const std::string& type = "SCALAR");
  // A sparse float accessor: `count` zeros but for the elements at `indices`.
  int sparse(int count, const std::string& type, const std::vector<uint16_t>& indices,
             const std::vector<float>& values);
  // The whole file: `body` holds the other top-level members (scenes, nodes, meshes, ...).
  std::string json(const std::string& body) const;

 private:
  int view(const void* data, size_t size);
  std::vector<unsigned char> bytes_;
  std::vector<std::string> views_, accessors_;
};

// DIR/animated.gltf: one triangle (0,0,0), (1,0,0), (0,1,0) with a morph target lifting it by +z, on
// a node animated by one sampler of each interpolation, keys at t = 0 and 2: "step" (STEP
// translation (1,2,3) -> (5,6,7)), "linear" (rotation 0 -> 90 degrees about +y, morph weight
// 0 -> 1), "cubic" (CUBICSPLINE scale (0,0,0) -> (7,8,9), tangents (1,2,3) and (4,5,6)).
std::filesystem::path write_animated_triangle(const std::filesystem::path& dir);

// DIR/NAME.gltf: a quad [−1, 1]² in the plane z = 0 facing +z, of the material `material` (its
// JSON), seen head-on from (0, 0, 2) by a camera it fills; with `light` (a KHR_lights_punctual
// light's JSON), that light on a node at (0, 0, 1), shining down −z onto the quad. Files the
// material names can be written beside it.
std::filesystem::path write_quad_scene(const std::filesystem::path& dir, const std::string& name,
                                       const std::string& material, const std::string& light = "");

}  // namespace prism::test
