#include "tests/support/gltf_builder.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>

namespace prism::test {

namespace {
int components(const std::string& type) {
  return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
}
}  // namespace

int GltfBuilder::view(const void* data, size_t size) {
  const size_t offset = bytes_.size();
  bytes_.resize(offset + (size + 3) / 4 * 4, 0);
  std::memcpy(bytes_.data() + offset, data, size);
  views_.push_back(fmt::format(R"({{"buffer": 0, "byteOffset": {}, "byteLength": {}}})", offset, size));
  return int(views_.size()) - 1;
}

int GltfBuilder::floats(const std::vector<float>& values, const std::string& type) {
  const int v = view(values.data(), 4 * values.size());
  accessors_.push_back(fmt::format(R"({{"bufferView": {}, "componentType": 5126, "count": {}, "type": "{}"}})", v,
                                   values.size() / components(type), type));
  return int(accessors_.size()) - 1;
}

int GltfBuilder::u16(const std::vector<uint16_t>& values, const std::string& type) {
  const int v = view(values.data(), 2 * values.size());
  accessors_.push_back(fmt::format(R"({{"bufferView": {}, "componentType": 5123, "count": {}, "type": "{}"}})", v,
                                   values.size() / components(type), type));
  return int(accessors_.size()) - 1;
}

int GltfBuilder::sparse(int count, const std::string& type, const std::vector<uint16_t>& indices,
                        const std::vector<float>& values) {
  const int iv = view(indices.data(), 2 * indices.size());
  const int vv = view(values.data(), 4 * values.size());
  accessors_.push_back(fmt::format(
      R"({{"componentType": 5126, "count": {}, "type": "{}", "sparse": {{"count": {},
          "indices": {{"bufferView": {}, "componentType": 5123}}, "values": {{"bufferView": {}}}}}}})",
      count, type, indices.size(), iv, vv));
  return int(accessors_.size()) - 1;
}

std::string GltfBuilder::json(const std::string& body) const {
  const auto join = [](const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ",\n    ") + s;
    return out;
  };
  return fmt::format(R"({{
  "asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
  "bufferViews": [{}],
  "accessors": [{}],
{}
}}
)",
                     bytes_.size(), base64(bytes_), join(views_), join(accessors_), body);
}

std::filesystem::path write_animated_triangle(const std::filesystem::path& dir) {
  GltfBuilder b;
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int target = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int times = b.floats({0, 2}, "SCALAR");
  const int step = b.floats({1, 2, 3, 5, 6, 7}, "VEC3");
  const int linear_rotation = b.floats({0, 0, 0, 1, 0, 0.70710678f, 0, 0.70710678f}, "VEC4");
  // CUBICSPLINE: in-tangent, value, out-tangent per key.
  const int cubic = b.floats({9, 9, 9, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 9}, "VEC3");
  const int weights = b.floats({0, 1}, "SCALAR");
  const std::filesystem::path file = dir / "animated.gltf";
  std::ofstream(file) << b.json(fmt::format(R"(
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}}}, "targets": [{{"POSITION": {}}}]}}]}}],
  "animations": [
    {{"name": "step", "samplers": [{{"input": {}, "output": {}, "interpolation": "STEP"}}],
      "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}]}},
    {{"name": "linear", "samplers": [{{"input": {}, "output": {}}}, {{"input": {}, "output": {}}}],
      "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "rotation"}}}},
                   {{"sampler": 1, "target": {{"node": 0, "path": "weights"}}}}]}},
    {{"name": "cubic", "samplers": [{{"input": {}, "output": {}, "interpolation": "CUBICSPLINE"}}],
      "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "scale"}}}}]}}
  ])",
                                            pos, target, times, step, times, linear_rotation, times, weights, times,
                                            cubic));
  return file;
}

std::filesystem::path write_quad_scene(const std::filesystem::path& dir, const std::string& name,
                                       const std::string& material, const std::string& light) {
  GltfBuilder b;
  const int pos = b.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3");
  const int nrm = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int idx = b.u16({0, 1, 2, 0, 2, 3});
  const std::string lights =
      light.empty() ? "" : fmt::format(R"(, "extensions": {{"KHR_lights_punctual": {{"lights": [{}]}}}})", light);
  const std::string light_node =
      light.empty() ? "" : R"(, {"translation": [0, 0, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}})";
  const std::string text = b.json(fmt::format(R"(
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular",
                     "KHR_materials_volume", "KHR_materials_transmission"],
  "scenes": [{{"nodes": [0, 1{}]}}],
  "nodes": [{{"mesh": 0}}, {{"camera": 0, "translation": [0, 0, 2]}}{}],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.4, "znear": 0.01}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}, "NORMAL": {}}}, "indices": {}, "material": 0}}]}}],
  "materials": [{}]{})",
                                              light.empty() ? "" : ", 2", light_node, pos, nrm, idx, material, lights));
  const std::filesystem::path path = dir / (name + ".gltf");
  std::ofstream(path) << text;
  return path;
}

}  // namespace prism::test
