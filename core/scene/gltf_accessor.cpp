#include "core/scene/gltf_accessor.h"

#include <cstring>

#include "core/base/error.h"

namespace prism {

namespace {

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

// One component as a double; normalized integers map to [0,1] or [−1,1] (glTF §3.11).
double read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = int8_t(*p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    default:
      return 0;
  }
}

// Start and stride of `count` elements of `element_size` bytes in a buffer view, checked
// against the view and its buffer.
const unsigned char* view_elements(const tinygltf::Model& model, int view_index, size_t offset, size_t count,
                                   size_t element_size, size_t& stride, const std::string& what) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    fail("{}: bufferView {} does not exist", what, view_index);
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    fail("{}: buffer {} does not exist", what, view.buffer);
  const tinygltf::Buffer& buffer = model.buffers[view.buffer];
  stride = view.byteStride ? view.byteStride : element_size;
  if (stride < element_size)
    fail("{}: byteStride {} is smaller than an element ({} bytes)", what, stride, element_size);
  // Compared by subtraction, never by a sum or product that could wrap around 2^64.
  if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
    fail("{}: bufferView {} (bytes {} + {}) lies outside its buffer of {} bytes", what, view_index, view.byteOffset,
         view.byteLength, buffer.data.size());
  if (count > 0 && (offset > view.byteLength || element_size > view.byteLength - offset ||
                    count - 1 > (view.byteLength - offset - element_size) / stride))
    fail(
        "{}: accessor reads past the end of its data ({} elements of {} bytes every {} from byte {} of bufferView {} "
        "holding {})",
        what, count, element_size, stride, offset, view_index, view.byteLength);
  return buffer.data.data() + view.byteOffset + offset;
}

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index, const std::string& what) {
  if (index < 0 || size_t(index) >= model.accessors.size()) fail("{}: accessor {} does not exist", what, index);
  return model.accessors[index];
}

// Elements of any accessor as `components` values of type T each.
template <typename T>
std::vector<T> read_accessor(const tinygltf::Model& model, int index, int components, const std::string& what) {
  const tinygltf::Accessor& acc = accessor_at(model, index, what);
  if (tinygltf::GetNumComponentsInType(uint32_t(acc.type)) != components)
    fail("{}: accessor {} has {} components per element, expected {}", what, index,
         tinygltf::GetNumComponentsInType(uint32_t(acc.type)), components);
  const int csize = component_size(acc.componentType);
  if (csize == 0) fail("{}: accessor {} has invalid componentType {}", what, index, acc.componentType);
  const size_t element_size = size_t(csize) * components;
  // Check the data range before allocating, so a corrupt count cannot exhaust memory.
  const unsigned char* base = nullptr;
  size_t stride = 0;
  if (acc.bufferView >= 0)
    base = view_elements(model, acc.bufferView, acc.byteOffset, acc.count, element_size, stride, what);
  else if (acc.count > (size_t(1) << 28))
    fail("{}: accessor {} claims {} elements without data", what, index, acc.count);
  std::vector<T> out(acc.count * components, T(0));  // no bufferView: zeros (glTF §3.6.2.3)

  const auto read_elements = [&](const unsigned char* from, size_t step, size_t count, auto&& target_of) {
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < components; ++c)
        out[target_of(i) * components + c] =
            T(read_component(from + i * step + size_t(c) * csize, acc.componentType, acc.normalized));
  };
  if (base) read_elements(base, stride, acc.count, [](size_t i) { return i; });
  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    size_t istride, vstride;
    const int isize = component_size(sp.indices.componentType);
    if (isize == 0 || sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail("{}: sparse indices of accessor {} have an invalid type", what, index);
    const auto* ibase = view_elements(model, sp.indices.bufferView, sp.indices.byteOffset, size_t(sp.count),
                                      size_t(isize), istride, what + " (sparse indices)");
    const auto* vbase = view_elements(model, sp.values.bufferView, sp.values.byteOffset, size_t(sp.count), element_size,
                                      vstride, what + " (sparse values)");
    read_elements(vbase, vstride, size_t(sp.count), [&](size_t i) {
      const auto target = size_t(read_component(ibase + i * istride, sp.indices.componentType, false));
      if (target >= acc.count) fail("{}: sparse index {} out of range (count {})", what, target, acc.count);
      return target;
    });
  }
  return out;
}

}  // namespace

int accessor_components(const tinygltf::Model& model, int index, const std::string& what) {
  return tinygltf::GetNumComponentsInType(uint32_t(accessor_at(model, index, what).type));
}

std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, int components,
                                        const std::string& what) {
  return read_accessor<float>(model, index, components, what);
}

std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index, const std::string& what) {
  const tinygltf::Accessor& acc = accessor_at(model, index, what);
  if (acc.type != TINYGLTF_TYPE_SCALAR) fail("{}: index accessor {} is not SCALAR", what, index);
  if (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail("{}: index accessor {} must hold unsigned integers (componentType {})", what, index, acc.componentType);
  return read_accessor<uint32_t>(model, index, 1, what);
}

}  // namespace prism
