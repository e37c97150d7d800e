#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, or .glb) to Scene, through tinygltf.
// Every index and byte range in the file is checked; a malformed file raises prism::Error with
// the file name and what is wrong, and never crashes.

#include <filesystem>

#include "scene/scene.h"

namespace prism {

Scene load_gltf(const std::filesystem::path& file);

}  // namespace prism
