// EXT_meshopt_compression and KHR_meshopt_compression: bufferViews whose data is encoded by
// meshoptimizer's vertex or index codec, optionally with a filter (octahedral normals,
// quaternions, exponential floats), decoded with Debian's libmeshoptimizer.
// Spec: github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression

#include <meshoptimizer.h>

#include "core/base/error.h"
#include "core/scene/gltf_compression.h"

namespace prism {

namespace {

size_t number(const tinygltf::Value& ext, const char* key, size_t fallback, const std::string& context) {
  if (!ext.Has(key)) return fallback;
  const auto& v = ext.Get(key);
  if (!v.IsNumber() || v.GetNumberAsDouble() < 0 || v.GetNumberAsDouble() > 9e15)
    fail("{}: {} must be a non-negative integer", context, key);
  return size_t(v.GetNumberAsDouble());
}

std::string text(const tinygltf::Value& ext, const char* key, const char* fallback) {
  return ext.Has(key) && ext.Get(key).IsString() ? ext.Get(key).Get<std::string>() : fallback;
}

// The decoded bytes of one compressed view.
std::vector<unsigned char> decode_view(const tinygltf::Model& model, const tinygltf::Value& ext,
                                       const std::string& context) {
  const size_t buffer = number(ext, "buffer", SIZE_MAX, context), offset = number(ext, "byteOffset", 0, context);
  const size_t length = number(ext, "byteLength", SIZE_MAX, context), stride = number(ext, "byteStride", 0, context);
  const size_t count = number(ext, "count", SIZE_MAX, context);
  const std::string mode = text(ext, "mode", ""), filter = text(ext, "filter", "NONE");
  if (buffer >= model.buffers.size()) fail("{}: buffer {} does not exist", context, buffer);
  const auto& data = model.buffers[buffer].data;
  if (length == SIZE_MAX || offset > data.size() || length > data.size() - offset)
    fail("{}: compressed bytes [{}, +{}) lie outside buffer {} ({} bytes)", context, offset, length, buffer,
         data.size());
  if (count == SIZE_MAX || stride == 0) fail("{}: needs count and byteStride", context);
  // The codecs cannot expand a byte into more than a few hundred (a run of identical vertices
  // costs two bits per 16 bytes): a larger claim is a corrupt file, refused before allocating.
  if (count > (size_t(1) << 32) / stride || count * stride > 1024 * length + 65536)
    fail("{}: {} elements of {} bytes cannot come from {} compressed bytes", context, count, stride, length);
  std::vector<unsigned char> out(count * stride);
  const unsigned char* src = data.data() + offset;
  int result = -1;
  if (mode == "ATTRIBUTES") {
    if (stride % 4 != 0 || stride > 256)
      fail("{}: ATTRIBUTES byteStride {} must be a multiple of 4 up to 256", context, stride);
    result = meshopt_decodeVertexBuffer(out.data(), count, stride, src, length);
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (stride != 2 && stride != 4) fail("{}: {} byteStride must be 2 or 4, not {}", context, mode, stride);
    if (mode == "TRIANGLES" && count % 3 != 0) fail("{}: TRIANGLES count {} is not a multiple of 3", context, count);
    result = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), count, stride, src, length)
                                 : meshopt_decodeIndexSequence(out.data(), count, stride, src, length);
  } else {
    fail("{}: unknown mode '{}' (ATTRIBUTES, TRIANGLES or INDICES)", context, mode);
  }
  if (result != 0) fail("{}: the compressed data is corrupt (meshoptimizer error {})", context, result);
  if (filter == "NONE") return out;
  if (mode != "ATTRIBUTES") fail("{}: filter {} applies to ATTRIBUTES only", context, filter);
  if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8))
    meshopt_decodeFilterOct(out.data(), count, stride);
  else if (filter == "QUATERNION" && stride == 8)
    meshopt_decodeFilterQuat(out.data(), count, stride);
  else if (filter == "EXPONENTIAL")
    meshopt_decodeFilterExp(out.data(), count, stride);
  else
    fail("{}: filter {} with byteStride {} is not supported by meshoptimizer {}.{}", context, filter, stride,
         MESHOPTIMIZER_VERSION / 1000, MESHOPTIMIZER_VERSION % 1000 / 10);
  return out;
}

}  // namespace

void decode_meshopt(tinygltf::Model& model, const std::string& file) {
  for (size_t v = 0; v < model.bufferViews.size(); ++v) {
    tinygltf::BufferView& view = model.bufferViews[v];
    for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
      const auto it = view.extensions.find(name);
      if (it == view.extensions.end()) continue;
      const std::string context = fmt::format("{}: bufferView {} ({})", file, v, name);
      tinygltf::Buffer decoded;
      decoded.data = decode_view(model, it->second, context);
      view.buffer = int(model.buffers.size());
      view.byteOffset = 0;
      view.byteLength = decoded.data.size();
      model.buffers.push_back(std::move(decoded));
      view.extensions.erase(it);
      break;
    }
  }
}

}  // namespace prism
