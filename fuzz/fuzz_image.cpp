// Fuzzes texture decoding (PNG, JPEG and the other formats stb_image reads), as the glTF
// importer decodes a material's images.

#include "base/error.h"
#include "materials/texture.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto image = prism::Image::decode(data, size, "fuzz input");
    image->mean(true);
  } catch (const prism::Error&) {
  }
  return 0;
}
