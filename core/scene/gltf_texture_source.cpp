// Which image a glTF texture shows: EXT_texture_webp's WebP image (decoded by libwebp), else the
// core `source`. KHR_texture_basisu's KTX2 images cannot be decoded (no Debian package reads
// KTX2 or Basis Universal), so its textures fall back to their `source` PNG or JPEG, and a
// texture without one is refused.

#include "core/scene/gltf_import.h"

namespace prism {

namespace {

int extension_source(const tinygltf::Texture& t, const char* extension) {
  const auto it = t.extensions.find(extension);
  if (it == t.extensions.end() || !it->second.Has("source") || !it->second.Get("source").IsInt()) return -1;
  return it->second.Get("source").GetNumberAsInt();
}

}  // namespace

int GltfLoader::texture_source(const tinygltf::Texture& t, int index, const std::string& context) {
  if (const int webp = extension_source(t, "EXT_texture_webp"); webp >= 0) return webp;
  if (extension_source(t, "KHR_texture_basisu") >= 0) {
    if (t.source < 0)
      fail(
          "{}: {}: texture {} has only a KTX2 image (KHR_texture_basisu), which Prism cannot decode (no Debian "
          "package reads KTX2/Basis Universal) and no fallback PNG or JPEG source",
          file_, context, index);
    warn_once("KTX2 images (KHR_texture_basisu) cannot be decoded; using the textures' fallback PNG/JPEG sources");
  }
  if (t.source < 0) fail("{}: {}: texture {} has no image source", file_, context, index);
  return t.source;
}

}  // namespace prism
