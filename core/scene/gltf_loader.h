#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, or .glb) to Scene, through tinygltf.
// Every index and byte range in the file is checked; a malformed file raises prism::Error with
// the file name and what is wrong, and never crashes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace prism {

// Which of the file's scenes, material variants and animation poses to build, and what the file
// may reach.
struct GltfOptions {
  std::optional<int> scene;    // default: the file's `scene`, else 0
  std::string variant;         // KHR_materials_variants name; empty: the default materials
  std::optional<double> time;  // pose the animation at this time [s]; unset: the file's own pose
  // The animation a time plays: a name or 0-based index, or "all" (every animation at once);
  // empty: the first, as viewers play a file.
  std::string animation;
  // Limits for untrusted files:
  bool allow_external_paths = false;           // URIs may name files outside the scene file's folder
  uint64_t max_instances = uint64_t(1) << 32;  // more node visits and mesh instances than this are refused
};

Scene load_gltf(const std::filesystem::path& file, const GltfOptions& options = {});

// What `prism info` lists about a file, besides the scene it builds.
struct GltfSummary {
  struct Extension {
    std::string name;
    bool required = false;
    std::string handling;  // what Prism does with it; empty: not supported
  };
  struct Animation {
    std::string name;
    double start = 0, end = 0;  // key times [s]
    size_t channels = 0;
  };
  std::vector<std::string> scenes;  // names ("" when unnamed)
  int scene = 0;                    // the one built
  std::vector<std::string> cameras;
  std::vector<std::string> variants;
  std::vector<Animation> animations;
  std::vector<Extension> extensions;  // used ones, required ones marked
  size_t skins = 0, morphed_meshes = 0;
};

// A glTF file read once and posed at any time of its animations: a sequence of frames reads
// the file, converts its materials, textures and static meshes once, and on each new pose
// rewrites only the instance transforms, cameras, lights and the meshes that deform.
class GltfScene {
 public:
  GltfScene(const std::filesystem::path& file, const GltfOptions& options = {});
  ~GltfScene();

  Scene& scene();
  GltfSummary summary() const;
  bool animated() const;  // the chosen animations have channels
  // Poses the scene at `seconds`; false (and the scene untouched) when nothing moved.
  bool pose(double seconds);
  // Frees the parsed file (its buffers and encoded images) once no other pose is needed; the
  // scene stays. Only scene() may be called afterwards.
  void close();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace prism
