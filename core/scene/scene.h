#pragma once
// The scene as loaded: meshes in object space placed by instances, materials, lights, cameras,
// environment. Plain data; rendering structures are built from it by core/render.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/bounds.h"
#include "core/base/instance.h"
#include "core/base/transform.h"
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

  // Barycentric interpolation of a per-vertex attribute over triangle `prim`.
  template <typename T>
  T interpolate(const std::vector<T>& values, uint32_t prim, const float b[3]) const {
    T r{};
    for (int k = 0; k < 3; ++k) {
      const T& v = values[indices[3 * prim + k]];
      if constexpr (std::is_same_v<T, std::array<float, 4>>) {
        for (int c = 0; c < 4; ++c) r[c] += v[c] * b[k];
      } else {
        r = r + v * b[k];
      }
    }
    return r;
  }
  // What materials read at barycentrics b of triangle `prim`: texture coordinates, vertex colour.
  SurfacePoint attributes_at(uint32_t prim, const float b[3]) const;
};

// Per-vertex tangents from the texture coordinates (Lengyel 2001, "Computing Tangent Space
// Basis Vectors for an Arbitrary Mesh"), for normal maps on meshes that bring none.
void generate_tangents(Mesh& mesh, int uv_set);

// A thin lens for depth of field, as a camera's extras give it (README, "Depth of field"); the
// command line's options replace it field by field. None set: a pinhole.
struct LensDesc {
  std::optional<float> f_number;          // the aperture as an f-number, of the focal length the
  std::optional<float> sensor_width;      // field of view makes on a film this wide [mm] (default 36),
  std::optional<float> radius;            // or the lens radius [scene units]
  std::optional<float> focus_distance;    // the plane in focus, this far along the view axis [scene units],
  std::optional<std::string> focus_node;  // or through this node's origin
  std::optional<int> blades;              // a polygonal aperture of this many blades (0: round)
  std::optional<float> blade_rotation;    // [degrees]
};

struct CameraDesc {
  enum class Projection { perspective, orthographic };
  std::string name;
  Projection projection = Projection::perspective;
  Transform to_world;            // looks down local −z, +y up (glTF convention)
  float yfov = 0.f;              // perspective: vertical field of view [radians]
  std::optional<float> aspect;   // width / height, if the file gives one
  float xmag = 1.f, ymag = 1.f;  // orthographic half extents
  LensDesc lens;
};

// Punctual lights (KHR_lights_punctual). Units as in the README: luminance Y = 1 ↔ 1 cd/m² for
// radiance, 1 cd for intensity, 1 lux for illuminance.

// Isotropic point source; intensity is spectral radiant intensity.
struct PointLight {
  std::string name;
  Vec3f position;
  Spectrum intensity;
};

// A point source shining into a cone about `direction`, full within the inner cone angle, none
// beyond the outer one, glTF's smooth falloff between (render/lights.h: SpotLightSource).
struct SpotLight {
  std::string name;
  Vec3f position;
  Vec3f direction;          // unit cone axis, the way the light shines
  float inner_angle = 0.f;  // [radians], 0 ≤ inner ≤ outer ≤ π/2
  float outer_angle = kPi / 4;
  Spectrum intensity;  // on the axis
};

// Parallel light from a source at infinity; illuminance is the spectral irradiance on a surface
// facing the light.
struct DirectionalLight {
  std::string name;
  Vec3f direction;  // unit, the way the light travels
  Spectrum illuminance;
};

// An equirectangular (latitude-longitude) image of linear Rec.709 radiance around the scene;
// core/render/environment_map.h defines the mapping.
struct EnvironmentMapDesc {
  std::string file;
  RgbImage image;
  float rotation = 0.f;  // about +Y, right-handed [radians]
  float scale = 1.f;     // multiplies every texel
  uint64_t hash = 0;     // FNV-1a of the image's values as read: names it in fingerprints, whatever its path
  std::optional<DenselySampledSpectrum> white;  // the spectrum of RGB (1, 1, 1), luminance 1; none: D65
};

// The instances one named glTF node placed (its own mesh's, not its children's): how a tool finds
// an object by the name a modelling program gave it.
struct NamedInstances {
  std::string node;
  uint32_t first = 0, end = 0;  // Scene::instances[first, end)
};

struct Scene {
  std::filesystem::path source;
  uint64_t source_hash = 0;  // FNV-1a of the source file and every file its URIs name (gltf_file.h)
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<NamedInstances> named_nodes;                  // nodes with a name and a mesh, in traversal order
  std::vector<std::pair<std::string, Vec3f>> node_origins;  // every named node's origin, in traversal order
  std::vector<Material> materials;
  std::vector<PointLight> point_lights;
  std::vector<SpotLight> spot_lights;
  std::vector<DirectionalLight> directional_lights;
  std::vector<CameraDesc> cameras;                    // in scene traversal order
  std::optional<Spectrum> environment;                // constant radiance from every direction
  std::optional<EnvironmentMapDesc> environment_map;  // at most one of environment, environment_map
  // The medium that fills the space around every closed dielectric (fog, haze); none: vacuum.
  std::optional<Medium> medium;

  // A box around each instance's transformed mesh box: exact for translations and axis scales,
  // a little loose under rotation, and O(instances) however large the meshes.
  Bounds3f world_bounds() const;
  size_t triangle_count() const;  // over all instances
};

}  // namespace prism
