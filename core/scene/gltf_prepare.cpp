#include <cstring>
#include <nlohmann/json.hpp>

#include "base/error.h"
#include "scene/gltf_compression.h"

namespace prism {

namespace {

using Json = nlohmann::json;

// Image types of glTF extensions whose data URIs tinygltf 2.7 does not decode.
constexpr const char* kOtherImageTypes[] = {"image/webp", "image/ktx2"};

constexpr uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A;  // "glTF", "JSON"

uint32_t read_u32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void write_u32(std::vector<unsigned char>& out, size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); }

bool is_glb(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 20 && read_u32(bytes.data()) == kGlbMagic;
}

// The JSON chunk of a GLB (glTF 2.0 §4.4): a 12-byte header, then the chunk's length and type.
bool glb_json_chunk(const std::vector<unsigned char>& bytes, size_t& length) {
  length = read_u32(bytes.data() + 12);
  return read_u32(bytes.data() + 16) == kJsonChunk && length <= bytes.size() - 20;
}

bool uses(const Json& doc, const char* extension) {
  const auto it = doc.find("extensionsUsed");
  return it != doc.end() && it->is_array() && std::find(it->begin(), it->end(), extension) != it->end();
}

// The adjustments prepare_for_tinygltf describes, on the parsed JSON.
void adjust(Json& doc) {
  if (uses(doc, "KHR_draco_mesh_compression") && doc.contains("meshes") && doc["meshes"].is_array())
    for (Json& mesh : doc["meshes"]) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (Json& prim : mesh["primitives"]) {
        if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
        Json& ext = prim["extensions"];
        if (!ext.contains("KHR_draco_mesh_compression") || !ext["KHR_draco_mesh_compression"].is_object()) continue;
        Json& draco = ext["KHR_draco_mesh_compression"];
        draco.erase("prism_indices");
        if (prim.contains("indices")) {
          draco["prism_indices"] = prim["indices"];
          prim.erase("indices");
        }
      }
    }
  if ((uses(doc, "EXT_meshopt_compression") || uses(doc, "KHR_meshopt_compression")) && doc.contains("buffers") &&
      doc["buffers"].is_array())
    for (Json& buffer : doc["buffers"]) {
      if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("extensions")) continue;
      const Json& ext = buffer["extensions"];
      const bool fallback =
          ext.is_object() && ((ext.contains("EXT_meshopt_compression")) || (ext.contains("KHR_meshopt_compression")));
      if (!fallback) continue;
      // Only views that decode_meshopt redirects may refer to a fallback buffer.
      buffer["uri"] = "data:application/octet-stream;base64,AA==";
      buffer["byteLength"] = 1;
    }
  if (doc.contains("images") && doc["images"].is_array())
    for (Json& image : doc["images"]) {
      if (!image.is_object() || !image.contains("uri") || !image["uri"].is_string()) continue;
      const std::string uri = image["uri"];
      for (const char* type : kOtherImageTypes)
        if (uri.rfind(std::string("data:") + type + ";base64,", 0) == 0)
          image["uri"] = "data:application/octet-stream;base64," + uri.substr(uri.find(',') + 1);
    }
}

}  // namespace

std::string gltf_json_text(const std::vector<unsigned char>& bytes) {
  if (!is_glb(bytes)) return std::string(bytes.begin(), bytes.end());
  size_t length = 0;
  if (!glb_json_chunk(bytes, length)) return {};
  return std::string(bytes.begin() + 20, bytes.begin() + 20 + std::ptrdiff_t(length));
}

std::vector<unsigned char> prepare_for_tinygltf(std::vector<unsigned char> bytes, const std::string& file) {
  const std::string text = gltf_json_text(bytes);
  const bool needed = text.find("draco_mesh_compression") != std::string::npos ||
                      text.find("meshopt_compression") != std::string::npos ||
                      std::any_of(std::begin(kOtherImageTypes), std::end(kOtherImageTypes),
                                  [&](const char* type) { return text.find(type) != std::string::npos; });
  if (!needed) return bytes;
  Json doc = Json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return bytes;  // tinygltf reports the syntax error
  adjust(doc);
  std::string json = doc.dump();
  if (!is_glb(bytes)) return {json.begin(), json.end()};
  // Rebuild the GLB around the new JSON chunk, padded with spaces to 4 bytes (§4.4.3.1).
  json.resize((json.size() + 3) / 4 * 4, ' ');
  size_t old_length = 0;
  glb_json_chunk(bytes, old_length);
  const size_t rest = 20 + old_length;
  std::vector<unsigned char> out(20 + json.size() + (bytes.size() - rest));
  std::memcpy(out.data(), bytes.data(), 12);
  std::memcpy(out.data() + 20, json.data(), json.size());
  std::memcpy(out.data() + 20 + json.size(), bytes.data() + rest, bytes.size() - rest);
  if (out.size() > UINT32_MAX) fail("{}: the GLB is larger than 4 GiB", file);
  write_u32(out, 8, uint32_t(out.size()));
  write_u32(out, 12, uint32_t(json.size()));
  write_u32(out, 16, kJsonChunk);
  return out;
}

}  // namespace prism
