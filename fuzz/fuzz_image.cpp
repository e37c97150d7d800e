// Fuzzes texture decoding (PNG, JPEG and the other formats stb_image reads), as the glTF
// importer decodes a material's images. Headers of more than 2^22 texels are skipped: decoding
// them is only slow (the importer's 2^28 limit is checked by the hostile-input test), and a
// 15-byte PNM header of 6666x33065 would spend the fuzzer's time filling 880 MB.

#include <stb_image.h>

#include <cstdint>

#include "core/base/error.h"
#include "materials/texture.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  int w = 0, h = 0, channels = 0;
  if (size < (1u << 30) && stbi_info_from_memory(data, int(size), &w, &h, &channels) &&
      uint64_t(w) * uint64_t(h) > (uint64_t(1) << 22))
    return 0;
  try {
    const auto image = prism::Image::decode(data, size, "fuzz input");
    image->mean(true);
  } catch (const prism::Error&) {
  }
  return 0;
}
