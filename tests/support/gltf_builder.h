#pragma once
// Small glTF files built in code for the tests: binary data packed into one embedded buffer, one
// bufferView per accessor, and the rest of the JSON written by the test.

#include <cstdint>
#include <string>
#include <vector>

namespace prism::test {

std::string base64(const std::vector<unsigned char>& bytes);

struct GltfBuilder {
  // Accessors of floats ("SCALAR", "VEC3", "VEC4", "MAT4", ...) and of u16 indices or joints;
  // each returns the accessor's index.
  int floats(const std::vector<float>& values, const std::string& type);
  int u16(const std::vector<uint16_t>& values, const std::string& type = "SCALAR");
  // A sparse float accessor: `count` zeros but for the elements at `indices`.
  int sparse(int count, const std::string& type, const std::vector<uint16_t>& indices,
             const std::vector<float>& values);
  // The whole file: `body` holds the other top-level members (scenes, nodes, meshes, ...).
  std::string json(const std::string& body) const;

 private:
  int view(const void* data, size_t size);
  std::vector<unsigned char> bytes_;
  std::vector<std::string> views_, accessors_;
};

}  // namespace prism::test
