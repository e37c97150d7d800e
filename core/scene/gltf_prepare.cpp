#include <cstring>
#include <nlohmann/json.hpp>

#include "core/base/error.h"
#include "core/scene/gltf_compression.h"
#include "core/scene/gltf_file.h"

namespace prism {

namespace {

using Json = nlohmann::json;

// Image types of glTF extensions whose data URIs tinygltf 2.7 does not decode.
constexpr const char* kOtherImageTypes[] = {"image/webp", "image/ktx2"};

constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"

void write_u32(std::vector<unsigned char>& out, size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); }

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

std::vector<unsigned char> prepare_for_tinygltf(std::vector<unsigned char> bytes, bool binary,
                                                const std::string& file) {
  const std::string_view text = gltf_json(bytes, binary);
  const bool needed = text.find("draco_mesh_compression") != std::string::npos ||
                      text.find("meshopt_compression") != std::string::npos ||
                      std::any_of(std::begin(kOtherImageTypes), std::end(kOtherImageTypes),
                                  [&](const char* type) { return text.find(type) != std::string::npos; });
  if (!needed) return bytes;
  Json doc = Json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return bytes;  // tinygltf reports the syntax error
  adjust(doc);
  std::string json = doc.dump();
  if (!binary) return {json.begin(), json.end()};
  // Rebuild the GLB around the new JSON chunk, padded with spaces to 4 bytes (§4.4.3.1).
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const size_t rest = 20 + text.size();
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
