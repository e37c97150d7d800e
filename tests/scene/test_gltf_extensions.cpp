// glTF extensions for compression, quantization, instancing, textures and the older material
// models, each on a small file generated here (encoded with the same libraries' encoders).

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/test_scenes.h"

using namespace prism;
using Json = nlohmann::json;

namespace {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

// A glTF document with one binary buffer, written as .gltf (data URI) or .glb.
struct GltfBuilder {
  std::vector<unsigned char> bin;
  Json doc = {{"asset", {{"version", "2.0"}}}, {"bufferViews", Json::array()}, {"accessors", Json::array()}};

  // Appends bytes (4-byte aligned) as a new bufferView; returns its index.
  int view(const void* data, size_t size, int stride = 0, int buffer = 0) {
    bin.resize((bin.size() + 3) / 4 * 4);
    Json v = {{"buffer", buffer}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (stride) v["byteStride"] = stride;
    bin.insert(bin.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + size);
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size() - 1);
  }
  int accessor(int view, int component_type, size_t count, const char* type, bool normalized = false) {
    Json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size() - 1);
  }
  void use(const char* extension, bool required) {
    doc["extensionsUsed"].push_back(extension);
    if (required) doc["extensionsRequired"].push_back(extension);
  }
  // One node showing mesh 0.
  void single_node(Json node = Json::object()) {
    node["mesh"] = 0;
    doc["nodes"] = Json::array({node});
    doc["scenes"] = Json::array({{{"nodes", {0}}}});
    doc["scene"] = 0;
  }
  std::filesystem::path write_gltf(const std::filesystem::path& file, Json extra_buffers = Json::array()) {
    Json d = doc;
    d["buffers"] = Json::array(
        {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bin)}}});
    for (const Json& b : extra_buffers) d["buffers"].push_back(b);
    std::ofstream(file) << d.dump(1);
    return file;
  }
  std::filesystem::path write_glb(const std::filesystem::path& file, Json extra_buffers = Json::array()) {
    Json d = doc;
    d["buffers"] = Json::array({{{"byteLength", bin.size()}}});
    for (const Json& b : extra_buffers) d["buffers"].push_back(b);
    std::string json = d.dump();
    json.resize((json.size() + 3) / 4 * 4, ' ');
    std::vector<unsigned char> body = bin;
    body.resize((body.size() + 3) / 4 * 4, 0);
    const uint32_t header[5] = {0x46546C67, 2, uint32_t(12 + 8 + json.size() + 8 + body.size()), uint32_t(json.size()),
                                0x4E4F534A};
    const uint32_t bin_header[2] = {uint32_t(body.size()), 0x004E4942};
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(header), sizeof header);
    out.write(json.data(), std::streamsize(json.size()));
    out.write(reinterpret_cast<const char*>(bin_header), sizeof bin_header);
    out.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
    return file;
  }
};

// glTF 2.0 §3.11: the value a normalized or plain integer component stands for.
double dequantized(int raw, int type, bool normalized) {
  if (!normalized) return raw;
  switch (type) {
    case kByte:
      return std::max(raw / 127.0, -1.0);
    case kUnsignedByte:
      return raw / 255.0;
    case kShort:
      return std::max(raw / 32767.0, -1.0);
    default:
      return raw / 65535.0;
  }
}

int component_size(int type) { return type == kByte || type == kUnsignedByte ? 1 : 2; }

// `count` elements of `components` raw integers of `type`, each element padded to 4 bytes.
std::vector<unsigned char> pack(const std::vector<int>& raw, int components, int type, int& stride) {
  const int size = component_size(type);
  stride = (components * size + 3) / 4 * 4;
  std::vector<unsigned char> out(raw.size() / components * stride, 0);
  for (size_t i = 0; i < raw.size(); ++i) {
    unsigned char* p = out.data() + (i / components) * stride + (i % components) * size;
    if (size == 1) *p = uint8_t(int8_t(raw[i]));
    if (size == 2) {
      const uint16_t v = uint16_t(int16_t(raw[i]));
      std::memcpy(p, &v, 2);
    }
  }
  return out;
}

// A grid of n × n vertices in the z = 0 plane, two triangles per cell.
void grid(int n, std::vector<float>& positions, std::vector<uint32_t>& indices) {
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) positions.insert(positions.end(), {float(x), float(y), 0.25f * float((x * y) % 3)});
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const uint32_t a = uint32_t(y * n + x), b = a + 1, c = a + uint32_t(n), d = c + 1;
      indices.insert(indices.end(), {a, b, c, b, d, c});
    }
}

// Each triangle's indices rotated to start at its smallest, which keeps the winding.
std::vector<uint32_t> rotated_to_smallest(std::vector<uint32_t> indices) {
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    std::rotate(indices.begin() + std::ptrdiff_t(t),
                std::min_element(indices.begin() + std::ptrdiff_t(t), indices.begin() + std::ptrdiff_t(t + 3)),
                indices.begin() + std::ptrdiff_t(t + 3));
  return indices;
}

}  // namespace

TEST_CASE("KHR_mesh_quantization: every attribute type the extension allows is dequantized at load") {
  const auto dir = test::temp_dir("gltf_quantized");
  // Raw integers that each type can hold, with the signed minimum where there is one.
  for (const int type : {kByte, kUnsignedByte, kShort, kUnsignedShort})
    for (const bool normalized : {false, true}) {
      INFO("componentType " << type << (normalized ? " normalized" : ""));
      const bool is_signed = type == kByte || type == kShort;
      const int lo = is_signed ? (type == kByte ? -128 : -32768) : 0, hi = type == kByte ? 127 : 100;
      const std::vector<int> positions = {lo, 0, 0, hi, 0, 0, 0, hi, 1};
      const std::vector<int> texcoords = {0, 0, hi, 0, 0, hi};
      GltfBuilder b;
      b.use("KHR_mesh_quantization", true);
      int stride = 0;
      auto bytes = pack(positions, 3, type, stride);
      const int pos = b.accessor(b.view(bytes.data(), bytes.size(), stride), type, 3, "VEC3", normalized);
      bytes = pack(texcoords, 2, type, stride);
      const int uv = b.accessor(b.view(bytes.data(), bytes.size(), stride), type, 3, "VEC2", normalized);
      Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv}};
      if (is_signed) {  // normals and tangents: normalized signed types only
        const int one = type == kByte ? 127 : 32767;
        bytes = pack({0, 0, one, 0, 0, one, 0, 0, one}, 3, type, stride);
        attributes["NORMAL"] = b.accessor(b.view(bytes.data(), bytes.size(), stride), type, 3, "VEC3", true);
        bytes = pack({one, 0, 0, -one, one, 0, 0, one, one, 0, 0, -one}, 4, type, stride);
        attributes["TANGENT"] = b.accessor(b.view(bytes.data(), bytes.size(), stride), type, 3, "VEC4", true);
      }
      b.doc["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", attributes}}})}}});
      b.single_node();
      const Scene scene = load_gltf(b.write_gltf(dir / "quantized.gltf"));
      REQUIRE(scene.meshes.size() == 1);
      const Mesh& m = scene.meshes[0];
      REQUIRE(m.positions.size() == 3);
      for (int v = 0; v < 3; ++v) {
        for (int c = 0; c < 3; ++c)
          CHECK(m.positions[v][c] == Approx(dequantized(positions[3 * v + c], type, normalized)).epsilon(1e-6));
        CHECK(m.uv[0][v].x == Approx(dequantized(texcoords[2 * v], type, normalized)).epsilon(1e-6));
        CHECK(m.uv[0][v].y == Approx(dequantized(texcoords[2 * v + 1], type, normalized)).epsilon(1e-6));
      }
      if (is_signed) {
        REQUIRE(m.normals.size() == 3);
        CHECK(m.normals[1].z == Approx(1).epsilon(1e-6));
        REQUIRE(m.tangents.size() == 3);
        CHECK(m.tangents[0][0] == Approx(1).epsilon(1e-6));
        CHECK(m.tangents[0][3] == -1);  // the bitangent's sign survives quantization
      }
    }
}

TEST_CASE("EXT_mesh_gpu_instancing: one instance per TRS, placed under the node's transform") {
  const auto dir = test::temp_dir("gltf_instancing");
  GltfBuilder b;
  b.use("EXT_mesh_gpu_instancing", true);
  b.use("KHR_mesh_quantization", false);
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int pos = b.accessor(b.view(triangle, sizeof triangle), kFloat, 3, "VEC3");
  const float translation[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3};
  const float scale[9] = {1, 1, 1, 2, 2, 2, 1, 3, 1};
  // Rotations as normalized shorts: identity, 90° about z, 180° about y.
  const int16_t q = int16_t(std::lround(std::sqrt(0.5) * 32767));
  const int16_t rotation[12] = {0, 0, 0, 32767, 0, 0, q, q, 0, 32767, 0, 0};
  const Json attributes = {{"TRANSLATION", b.accessor(b.view(translation, sizeof translation), kFloat, 3, "VEC3")},
                           {"SCALE", b.accessor(b.view(scale, sizeof scale), kFloat, 3, "VEC3")},
                           {"ROTATION", b.accessor(b.view(rotation, sizeof rotation), kShort, 3, "VEC4", true)}};
  // Two primitives: each instance places both.
  const Json prim = {{"attributes", {{"POSITION", pos}}}};
  b.doc["meshes"] = Json::array({{{"primitives", Json::array({prim, prim})}}});
  b.single_node(
      {{"translation", {0, 0, 10}}, {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attributes}}}}}});
  const Scene scene = load_gltf(b.write_gltf(dir / "instanced.gltf"));
  REQUIRE(scene.meshes.size() == 2);
  REQUIRE(scene.instances.size() == 6);
  CHECK(scene.triangle_count() == 6);
  // Vertex (1, 0, 0) of each instance: node T · instance T · R · S.
  const Vec3d expected[3] = {{1 + 1, 0, 10}, {0, 2 + 2, 10}, {0 - 1, 0, 10 + 3}};
  for (int i = 0; i < 3; ++i)
    for (int p = 0; p < 2; ++p) {
      const Instance& inst = scene.instances[2 * i + p];
      CHECK(inst.mesh == uint32_t(p));
      const Vec3d v = inst.to_world.point({1, 0, 0});
      INFO("instance " << i);
      CHECK(length(v - expected[i]) < 1e-4);  // the shorts' rounding of cos 45°
    }

  // A count mismatch between the attributes is an error naming them.
  b.doc["accessors"][attributes["SCALE"].get<int>()]["count"] = 2;
  CHECK_THROWS_WITH(load_gltf(b.write_gltf(dir / "mismatch.gltf")),
                    Catch::Contains("EXT_mesh_gpu_instancing") && Catch::Contains("instances"));
}

TEST_CASE("EXT_ and KHR_meshopt_compression round-trip vertices and indices exactly, in .gltf and .glb") {
  const auto dir = test::temp_dir("gltf_meshopt");
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  grid(9, positions, indices);
  const size_t vertices = positions.size() / 3;
  for (const char* extension : {"EXT_meshopt_compression", "KHR_meshopt_compression"})
    for (const bool sequence : {false, true}) {
      INFO(extension << (sequence ? " INDICES" : " TRIANGLES"));
      GltfBuilder b;
      b.use(extension, true);
      std::vector<unsigned char> vb(meshopt_encodeVertexBufferBound(vertices, 12));
      vb.resize(meshopt_encodeVertexBuffer(vb.data(), vb.size(), positions.data(), vertices, 12));
      std::vector<unsigned char> ib(meshopt_encodeIndexBufferBound(indices.size(), vertices));
      ib.resize(sequence ? meshopt_encodeIndexSequence(ib.data(), ib.size(), indices.data(), indices.size())
                         : meshopt_encodeIndexBuffer(ib.data(), ib.size(), indices.data(), indices.size()));
      const int vview = b.view(vb.data(), vb.size()), iview = b.view(ib.data(), ib.size());
      // The plain views live in buffer 1, a fallback without data; the compressed bytes in buffer 0.
      auto& views = b.doc["bufferViews"];
      const Json vcompressed = views[vview], icompressed = views[iview];
      views[vview] = {{"buffer", 1}, {"byteOffset", 0}, {"byteLength", vertices * 12}, {"byteStride", 12}};
      views[vview]["extensions"][extension] = {{"buffer", 0},
                                               {"byteOffset", vcompressed["byteOffset"]},
                                               {"byteLength", vcompressed["byteLength"]},
                                               {"byteStride", 12},
                                               {"count", vertices},
                                               {"mode", "ATTRIBUTES"}};
      views[iview] = {{"buffer", 1}, {"byteOffset", vertices * 12}, {"byteLength", indices.size() * 4}};
      views[iview]["extensions"][extension] = {{"buffer", 0},
                                               {"byteOffset", icompressed["byteOffset"]},
                                               {"byteLength", icompressed["byteLength"]},
                                               {"byteStride", 4},
                                               {"count", indices.size()},
                                               {"mode", sequence ? "INDICES" : "TRIANGLES"}};
      const int pos = b.accessor(vview, kFloat, vertices, "VEC3"),
                idx = b.accessor(iview, kUnsignedInt, indices.size(), "SCALAR");
      b.doc["meshes"] =
          Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}})}}});
      b.single_node();
      Json fallback = {{"byteLength", vertices * 12 + indices.size() * 4}};
      fallback["extensions"][extension] = {{"fallback", true}};
      for (const auto& file : {b.write_gltf(dir / "meshopt.gltf", Json::array({fallback})),
                               b.write_glb(dir / "meshopt.glb", Json::array({fallback}))}) {
        INFO(file.string());
        const Scene scene = load_gltf(file);
        REQUIRE(scene.meshes.size() == 1);
        const Mesh& m = scene.meshes[0];
        REQUIRE(m.positions.size() == vertices);
        for (size_t v = 0; v < vertices; ++v)
          CHECK(m.positions[v] == Vec3f(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]));
        // The triangle codec may rotate a triangle's vertices (keeping its winding).
        CHECK(rotated_to_smallest(m.indices) == rotated_to_smallest(indices));
      }
    }
}

TEST_CASE("KHR_draco_mesh_compression decodes to the encoded triangles, within Draco's quantization") {
  const auto dir = test::temp_dir("gltf_draco");
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  grid(6, positions, indices);
  const int faces = int(indices.size() / 3);
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(faces);
  const int pos_att = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int uv_att = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < faces; ++f) {
    const float* p[3];
    float uv[3][2];
    for (int k = 0; k < 3; ++k) {
      p[k] = &positions[3 * indices[3 * f + k]];
      uv[k][0] = p[k][0] / 5, uv[k][1] = p[k][1] / 5;
    }
    builder.SetAttributeValuesForFace(pos_att, draco::FaceIndex(f), p[0], p[1], p[2]);
    builder.SetAttributeValuesForFace(uv_att, draco::FaceIndex(f), uv[0], uv[1], uv[2]);
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  REQUIRE(mesh);
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer encoded;
  REQUIRE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());

  GltfBuilder b;
  b.use("KHR_draco_mesh_compression", true);
  const int view = b.view(encoded.data(), encoded.size());
  const size_t points = mesh->num_points();
  const int pos = b.accessor(-1, kFloat, points, "VEC3"), uv = b.accessor(-1, kFloat, points, "VEC2");
  const int idx = b.accessor(-1, kUnsignedShort, indices.size(), "SCALAR");
  Json prim = {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}};
  prim["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", view},
      {"attributes",
       {{"POSITION", mesh->attribute(pos_att)->unique_id()}, {"TEXCOORD_0", mesh->attribute(uv_att)->unique_id()}}}};
  b.doc["meshes"] = Json::array({{{"primitives", Json::array({prim})}}});
  b.single_node();
  for (const auto& file : {b.write_gltf(dir / "draco.gltf"), b.write_glb(dir / "draco.glb")}) {
    INFO(file.string());
    const Scene scene = load_gltf(file);
    REQUIRE(scene.meshes.size() == 1);
    const Mesh& m = scene.meshes[0];
    REQUIRE(m.indices.size() == indices.size());
    // Draco reorders vertices and faces: compare the triangles as sets of centroids, each to
    // the 14-bit quantization step of the grid's extent (5 / 2¹⁴ ≈ 3e-4).
    const auto centroids = [](const std::vector<Vec3f>& p, const std::vector<uint32_t>& idx) {
      std::vector<std::array<float, 3>> c;
      for (size_t t = 0; t < idx.size(); t += 3) {
        const Vec3f s = (p[idx[t]] + p[idx[t + 1]] + p[idx[t + 2]]) / 3.f;
        c.push_back({std::round(s.x * 12) / 12, std::round(s.y * 12) / 12, std::round(s.z * 12) / 12});
      }
      std::sort(c.begin(), c.end());
      return c;
    };
    std::vector<Vec3f> original;
    for (size_t v = 0; v < positions.size(); v += 3)
      original.push_back({positions[v], positions[v + 1], positions[v + 2]});
    CHECK(centroids(m.positions, m.indices) == centroids(original, indices));
    for (size_t v = 0; v < m.positions.size(); ++v) {
      const Vec3f p = m.positions[v];
      CHECK(std::abs(p.x - std::round(p.x)) < 1e-3f);  // grid points, to the quantization step
      CHECK(m.uv[0][v].x == Approx(p.x / 5).margin(1e-3));
    }
  }
}

namespace {

// A 2x2 RGBA image as lossless WebP.
std::vector<unsigned char> webp_2x2(const uint8_t rgba[16]) {
  uint8_t* out = nullptr;
  const size_t size = WebPEncodeLosslessRGBA(rgba, 2, 2, 8, &out);
  std::vector<unsigned char> bytes(out, out + size);
  WebPFree(out);
  return bytes;
}

// A quad facing +z with a base-colour texture whose texture object is `texture`, images given.
GltfBuilder textured_quad(const Json& texture,
                          const std::vector<std::pair<std::string, std::vector<unsigned char>>>& images) {
  GltfBuilder b;
  const float quad[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const int pos = b.accessor(b.view(quad, sizeof quad), kFloat, 4, "VEC3");
  const int tex = b.accessor(b.view(uv, sizeof uv), kFloat, 4, "VEC2");
  const int ind = b.accessor(b.view(idx, sizeof idx), kUnsignedShort, 6, "SCALAR");
  b.doc["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}},
                                                               {"indices", ind},
                                                               {"material", 0}}})}}});
  b.doc["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["textures"] = Json::array({texture});
  for (const auto& [mime, bytes] : images)
    b.doc["images"].push_back({{"uri", "data:" + mime + ";base64," + test::base64(bytes)}});
  b.single_node();
  return b;
}

const Image& base_color_image(const Scene& scene) {
  return *std::get<PbrMaterial>(scene.materials.at(0).kind).base_color_texture->image;
}

}  // namespace

TEST_CASE("EXT_texture_webp images decode; KHR_texture_basisu falls back to the texture's source or is refused") {
  const auto dir = test::temp_dir("gltf_textures");
  const uint8_t texels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 128, 10, 20, 30, 40};
  const auto webp = webp_2x2(texels);
  const auto image = Image::decode(webp.data(), webp.size(), "test.webp");
  REQUIRE(image->width() == 2);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 4; ++c) CHECK(image->texel(i % 2, i / 2)[c] == texels[4 * i + c]);

  Json texture = {{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}};
  GltfBuilder b = textured_quad(texture, {{"image/webp", webp}});
  b.use("EXT_texture_webp", true);
  CHECK(base_color_image(load_gltf(b.write_gltf(dir / "webp.gltf"))).texel(1, 1)[2] == 30);

  // KTX2 (no Debian decoder): the core `source` is shown instead ...
  const std::vector<unsigned char> ktx2 = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  texture = {{"source", 1}, {"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}};
  b = textured_quad(texture, {{"image/ktx2", ktx2}, {"image/webp", webp}});
  b.use("KHR_texture_basisu", false);
  CHECK(base_color_image(load_gltf(b.write_gltf(dir / "basisu.gltf"))).texel(0, 1)[3] == 128);
  // ... and a texture with only a KTX2 image is refused by name.
  texture = {{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}};
  b = textured_quad(texture, {{"image/ktx2", ktx2}});
  b.use("KHR_texture_basisu", true);
  CHECK_THROWS_WITH(load_gltf(b.write_gltf(dir / "ktx2_only.gltf")),
                    Catch::Contains("ktx2_only.gltf") && Catch::Contains("KTX2") && Catch::Contains("no fallback"));
}

TEST_CASE("KHR_materials_volume: a thickness texture is kept only if some texel's G is 0 (a thin wall there)") {
  // The thickness serves only to mark thin walls (G = 0); a texture without such a texel marks none
  // anywhere, and is dropped so that no hit looks it up.
  const auto dir = test::temp_dir("gltf_thickness");
  const auto load = [&](uint8_t green, const char* name) {
    const uint8_t texels[16] = {9, 200, 9, 255, 9, 1, 9, 255, 9, green, 9, 255, 9, 50, 9, 255};
    GltfBuilder b = textured_quad({{"source", 0}}, {{"image/webp", webp_2x2(texels)}});
    b.doc["materials"][0] = {
        {"pbrMetallicRoughness", {{"metallicFactor", 0}}},
        {"extensions",
         {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
          {"KHR_materials_volume", {{"thicknessFactor", 1}, {"thicknessTexture", {{"index", 0}}}}}}}};
    b.use("KHR_materials_transmission", false);
    b.use("KHR_materials_volume", false);
    b.use("EXT_texture_webp", false);
    const Scene scene = load_gltf(b.write_gltf(dir / name));
    return std::get<PbrMaterial>(scene.materials.at(0).kind).thickness_texture.has_value();
  };
  CHECK(load(0, "thin_in_a_corner.gltf"));
  CHECK_FALSE(load(2, "thick_everywhere.gltf"));
}

namespace {

// One triangle with material `material` (a JSON object), loaded.
Scene triangle_with_material(const std::filesystem::path& file, const Json& material, const char* extension) {
  GltfBuilder b;
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int pos = b.accessor(b.view(triangle, sizeof triangle), kFloat, 3, "VEC3");
  b.doc["meshes"] =
      Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", pos}}}, {"material", 0}}})}}});
  b.doc["materials"] = Json::array({material});
  b.use(extension, true);
  b.single_node();
  return load_gltf(b.write_gltf(file));
}

}  // namespace

TEST_CASE("KHR_materials_unlit: the base colour is emitted and nothing is scattered") {
  const auto dir = test::temp_dir("gltf_unlit");
  Json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.5, 0.8, 1}}}}};
  material["extensions"]["KHR_materials_unlit"] = Json::object();
  const Scene scene = triangle_with_material(dir / "unlit.gltf", material, "KHR_materials_unlit");
  const Material& m = scene.materials.at(0);
  REQUIRE(m.emission);
  CHECK(m.emission_rgb == Rgb{0.2f, 0.5f, 0.8f});
  const auto& p = std::get<PbrMaterial>(m.kind);
  CHECK(p.base_color == Rgb{0, 0, 0});  // scatters nothing
  CHECK(p.metallic == 0);
  CHECK(p.specular == 0);
  CHECK(p.transmission == 0);

  // Seen head on, with no light at all, the surface shows its base colour.
  Scene lit = scene;
  lit.meshes.clear();
  lit.instances.clear();
  test::add_mesh(lit, test::make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}, 0));
  const auto img = test::render_rgb(lit, test::look_at({0, 0, 3}, {0, 0, 0}, 30), 16, 16, 16);
  CHECK(img.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c);
    const double expected = c == 0 ? 0.2 : c == 1 ? 0.5 : 0.8;
    // Only the wavelengths' noise separates the image from the colour (and the spectral round
    // trip, < 1e-3).
    const double se = img.standard_error(c, 0, 0, 16, 16);
    CHECK(se < 0.01);
    CHECK(std::abs(img.mean(c) - expected) < 5 * se + 1e-3);
  }
}

TEST_CASE("KHR_materials_pbrSpecularGlossiness converts to metal-rough as the extension's sample code does") {
  const auto dir = test::temp_dir("gltf_specgloss");
  const auto convert = [&](Json factors) {
    Json material;
    material["extensions"]["KHR_materials_pbrSpecularGlossiness"] = factors;
    const Scene scene = triangle_with_material(dir / "sg.gltf", material, "KHR_materials_pbrSpecularGlossiness");
    return std::get<PbrMaterial>(scene.materials.at(0).kind);
  };
  // A dielectric's specular (F0 = 0.04) keeps the diffuse colour as the base colour, metallic 0.
  PbrMaterial p = convert(
      {{"diffuseFactor", {0.5, 0.25, 0.125, 0.75}}, {"specularFactor", {0.04, 0.04, 0.04}}, {"glossinessFactor", 0.7}});
  CHECK(p.metallic == 0);
  CHECK(p.base_color.r == Approx(0.5));
  CHECK(p.base_color.g == Approx(0.25));
  CHECK(p.base_color.b == Approx(0.125));
  CHECK(p.alpha == Approx(0.75));
  CHECK(p.roughness == Approx(0.3));
  // No diffuse and a bright coloured specular: a metal of that colour.
  p = convert({{"diffuseFactor", {0, 0, 0, 1}}, {"specularFactor", {0.9, 0.6, 0.3}}, {"glossinessFactor", 1}});
  CHECK(p.metallic == Approx(1).margin(0.05));
  CHECK(p.base_color.r == Approx(0.9).margin(0.05));
  CHECK(p.base_color.b == Approx(0.3).margin(0.05));
  CHECK(p.roughness == 0);
  // Malformed factors are named.
  CHECK_THROWS_WITH(convert({{"specularFactor", {1, 1}}}), Catch::Contains("specularFactor"));
}
