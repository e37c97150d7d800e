// KHR_draco_mesh_compression: a primitive's indices and attributes decoded by Debian's libdraco
// into new buffers, views and accessors (the accessors the primitive names keep their type,
// count, min and max; they gain the data). Spec:
// github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression

#include <draco/compression/decode.h>

#include <cstring>

#include "core/base/error.h"
#include "core/scene/gltf_compression.h"

namespace prism {

namespace {

// Appends `bytes` as a new buffer with one view over it; returns the view.
int add_view(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  tinygltf::BufferView view;
  view.buffer = int(model.buffers.size());
  view.byteLength = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

// The attribute's values for every point, converted to the accessor's component type.
template <typename T>
std::vector<unsigned char> point_values(const draco::Mesh& mesh, const draco::PointAttribute& attribute, int components,
                                        const std::string& context) {
  std::vector<unsigned char> out(size_t(mesh.num_points()) * components * sizeof(T));
  T value[16];
  for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
    if (!attribute.ConvertValue<T>(attribute.mapped_index(p), int8_t(components), value))
      fail("{}: cannot convert a value to the accessor's type", context);
    std::memcpy(out.data() + size_t(p.value()) * components * sizeof(T), value, components * sizeof(T));
  }
  return out;
}

std::vector<unsigned char> attribute_bytes(const draco::Mesh& mesh, const draco::PointAttribute& attribute,
                                           const tinygltf::Accessor& accessor, const std::string& context) {
  const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
  if (components < 1 || components > 16) fail("{}: accessor has an invalid type", context);
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return point_values<float>(mesh, attribute, components, context);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return point_values<int8_t>(mesh, attribute, components, context);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return point_values<uint8_t>(mesh, attribute, components, context);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return point_values<int16_t>(mesh, attribute, components, context);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return point_values<uint16_t>(mesh, attribute, components, context);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return point_values<uint32_t>(mesh, attribute, components, context);
    default:
      fail("{}: accessor has invalid componentType {}", context, accessor.componentType);
  }
}

void decode_primitive(tinygltf::Model& model, tinygltf::Primitive& prim, const tinygltf::Value& ext,
                      const std::string& context) {
  if (!ext.Has("bufferView") || !ext.Get("bufferView").IsInt() || !ext.Has("attributes") ||
      !ext.Get("attributes").IsObject())
    fail("{}: KHR_draco_mesh_compression needs a bufferView and attributes", context);
  const int view_index = ext.Get("bufferView").GetNumberAsInt();
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    fail("{}: KHR_draco_mesh_compression refers to bufferView {}, which does not exist", context, view_index);
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size() ||
      view.byteOffset + view.byteLength > model.buffers[view.buffer].data.size())
    fail("{}: the Draco bufferView {} lies outside its buffer", context, view_index);

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(model.buffers[view.buffer].data.data() + view.byteOffset), view.byteLength);
  auto decoded = draco::Decoder().DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) fail("{}: cannot decode the Draco mesh: {}", context, decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();

  const auto& attributes = ext.Get("attributes");
  for (const std::string& semantic : attributes.Keys()) {
    const auto target = prim.attributes.find(semantic);
    if (target == prim.attributes.end()) continue;  // the spec: only attributes the primitive names
    const std::string what = fmt::format("{} Draco attribute {}", context, semantic);
    if (target->second < 0 || size_t(target->second) >= model.accessors.size())
      fail("{}: accessor {} does not exist", what, target->second);
    const auto& id = attributes.Get(semantic);
    const draco::PointAttribute* attribute = id.IsInt() ? mesh->GetAttributeByUniqueId(id.GetNumberAsInt()) : nullptr;
    if (!attribute) fail("{}: the Draco mesh has no attribute {}", what, id.IsInt() ? id.GetNumberAsInt() : -1);
    tinygltf::Accessor& accessor = model.accessors[target->second];
    if (accessor.count != mesh->num_points())
      fail("{}: accessor {} counts {} vertices, the Draco mesh holds {}", what, target->second, accessor.count,
           mesh->num_points());
    accessor.bufferView = add_view(model, attribute_bytes(*mesh, *attribute, accessor, what));
    accessor.byteOffset = 0;
    accessor.sparse.isSparse = false;
  }

  // Indices: u32 triangles, into the accessor the primitive named (or a new one).
  std::vector<unsigned char> indices(size_t(mesh->num_faces()) * 3 * sizeof(uint32_t));
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t index = mesh->face(f)[k].value();
      std::memcpy(indices.data() + (size_t(f.value()) * 3 + k) * 4, &index, 4);
    }
  int accessor_index = ext.Has("prism_indices") ? ext.Get("prism_indices").GetNumberAsInt() : -1;
  if (accessor_index < 0) {
    accessor_index = int(model.accessors.size());
    model.accessors.emplace_back();
  } else if (size_t(accessor_index) >= model.accessors.size()) {
    fail("{}: indices refer to accessor {}, which does not exist", context, accessor_index);
  }
  tinygltf::Accessor& acc = model.accessors[accessor_index];
  acc.type = TINYGLTF_TYPE_SCALAR;
  acc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  acc.count = size_t(mesh->num_faces()) * 3;
  acc.byteOffset = 0;
  acc.normalized = false;
  acc.sparse.isSparse = false;
  acc.bufferView = add_view(model, std::move(indices));
  prim.indices = accessor_index;
}

}  // namespace

void decode_draco(tinygltf::Model& model, const std::string& file) {
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      const auto it = prim.extensions.find("KHR_draco_mesh_compression");
      if (it == prim.extensions.end()) continue;
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        fail("{}: mesh {} primitive {}: Draco compresses triangles, not mode {}", file, m, p, prim.mode);
      const tinygltf::Value ext = it->second;
      decode_primitive(model, prim, ext,
                       fmt::format("{}: mesh {} '{}' primitive {}", file, m, model.meshes[m].name, p));
      prim.mode = TINYGLTF_MODE_TRIANGLES;  // Draco's faces are triangles whatever the mode
      prim.extensions.erase("KHR_draco_mesh_compression");
    }
}

}  // namespace prism
