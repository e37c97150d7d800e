#pragma once
// The scene as loaded: meshes in object space placed by instances, materials, lights, cameras,
// environment. Plain data; rendering structures are built from it by core/render.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "base/bounds.h"
#include "base/transform.h"
#include "materials/material.h"
#include "spectral/spectrum.h"

namespace prism {

// One glTF primitive: an indexed triangle list with one material. Optional per-vertex
// attributes are empty when absent.
struct Mesh {
  std::string name;
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;                  // empty: flat shading
  std::array<std::vector<Vec2f>, 2> uv;        // TEXCOORD_0, TEXCOORD_1
  std::vector<std::array<float, 4>> colors;    // COLOR_0, RGBA
  std::vector<std::array<float, 4>> tangents;  // xyz and the bitangent's sign (TANGENT, or generated)
  std::vector<uint32_t> indices;
  uint32_t material = 0;
};

// Per-vertex tangents from the texture coordinates (Lengyel 2001, "Computing Tangent Space
// Basis Vectors for an Arbitrary Mesh"), for normal maps on meshes that bring none.
void generate_tangents(Mesh& mesh, int uv_set);

struct Instance {
  uint32_t mesh;
  Transform to_world;
};

struct CameraDesc {
  enum class Projection { perspective, orthographic };
  std::string name;
  Projection projection = Projection::perspective;
  Transform to_world;              // looks down local −z, +y up (glTF convention)
  float yfov = 0.f;                // perspective: vertical field of view [radians]
  std::optional<float> aspect;     // width / height, if the file gives one
  float xmag = 1.f, ymag = 1.f;    // orthographic half extents
};

// Isotropic point source. Intensity: spectral radiant intensity in Prism's units (see README:
// luminance Y = 1 ↔ 1 cd/m² for radiance, 1 cd for intensity).
struct PointLight {
  std::string name;
  Vec3f position;
  Spectrum intensity;
};

struct Scene {
  std::filesystem::path source;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;
  std::vector<PointLight> point_lights;
  std::vector<CameraDesc> cameras;     // in scene traversal order
  std::optional<Spectrum> environment; // constant radiance from every direction

  Bounds3f world_bounds() const;
  size_t triangle_count() const;       // over all instances
};

}  // namespace prism
