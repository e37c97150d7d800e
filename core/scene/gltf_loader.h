#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, or .glb) to Scene, through tinygltf.
// Every index and byte range in the file is checked; a malformed file raises prism::Error with
// the file name and what is wrong, and never crashes.

#include <cstdint>
#include <filesystem>

#include "scene/scene.h"

namespace prism {

struct GltfLoadOptions {
  bool allow_external_paths = false;           // URIs may name files outside the scene file's folder
  uint64_t max_instances = uint64_t(1) << 32;  // more mesh instances than this are refused
};

Scene load_gltf(const std::filesystem::path& file, const GltfLoadOptions& options = {});

}  // namespace prism
