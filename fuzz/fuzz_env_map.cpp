// Fuzzes the environment map reader (OpenEXR or Radiance HDR, told apart by the EXR magic
// number) and the map's sampling distribution, as `prism render --env-map` uses them.

#include <cstring>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/render/environment_map.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::log::set_level(prism::log::Level::quiet);
  const bool exr = size >= 4 && std::memcmp(data, "\x76\x2f\x31\x01", 4) == 0;
  const auto file = prism::fuzz::input_file(data, size, exr ? "sky.exr" : "sky.hdr");
  try {
    const prism::EnvironmentMapDesc desc = prism::load_environment_map(file, 30, 1);
    prism::EnvironmentMap map(desc);
  } catch (const prism::Error&) {
  }
  return 0;
}
