// Fuzzes a glTF or GLB scene through prepare_scene, as `prism render` loads it: file reading,
// the importer, the camera and the World (BVH, lights), stopping before rendering.

#include "apps/prism/scene_setup.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::log::set_level(prism::log::Level::quiet);
  prism::SceneArgs args;
  args.scene = prism::fuzz::input_file(data, size, "scene.gltf").string();
  args.width = args.height = 8;
  args.max_memory_gb = 0.05;  // 100 000 node visits and instances: quick runs, the limit's path taken
  try {
    prism::prepare_scene(args);
  } catch (const prism::Error&) {
  }
  return 0;
}
