#include "support/gltf_builder.h"

#include <fmt/format.h>

#include <cstring>

namespace prism::test {

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t(bytes[i]) << 16) | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

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

}  // namespace prism::test
