#include "materials/texture.h"

#include <stb_image.h>
#include <webp/decode.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/base/error.h"

namespace prism {

Image::Image(int width, int height, std::vector<uint8_t> rgba)
    : width_(width), height_(height), rgba_(std::move(rgba)) {
  if (width <= 0 || height <= 0 || rgba_.size() != size_t(width) * height * 4)
    fail("image of {}x{} has {} bytes", width, height, rgba_.size());
}

namespace {

// The largest image accepted, checked before the decoder allocates for it (2^28 texels = 1 GB as RGBA).
constexpr uint64_t kMaxTexels = uint64_t(1) << 28;

// A WebP file is a RIFF container of form type "WEBP" (RFC 9649 §2.4).
bool is_webp(const unsigned char* bytes, size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

std::shared_ptr<const Image> decode_webp(const unsigned char* bytes, size_t size, const std::string& what) {
  int w = 0, h = 0;
  if (!WebPGetInfo(bytes, size, &w, &h)) fail("{}: cannot decode the WebP image", what);
  if (uint64_t(w) * uint64_t(h) > kMaxTexels)
    fail("{}: a {}x{} image is larger than the 2^28 texels Prism accepts", what, w, h);
  uint8_t* data = WebPDecodeRGBA(bytes, size, &w, &h);
  if (!data) fail("{}: cannot decode the WebP image", what);
  std::vector<uint8_t> rgba(data, data + size_t(w) * h * 4);
  WebPFree(data);
  return std::make_shared<Image>(w, h, std::move(rgba));
}

}  // namespace

std::shared_ptr<const Image> Image::decode(const unsigned char* bytes, size_t size, const std::string& what) {
  if (is_webp(bytes, size)) return decode_webp(bytes, size, what);
  int w = 0, h = 0, channels = 0;
  if (size > size_t(std::numeric_limits<int>::max())) fail("{}: encoded image of {} bytes is too large", what, size);
  // glTF images are PNG or JPEG (glTF 2.0 §3.8.1), or WebP above: stb_image's other decoders (PNM, BMP, TGA,
  // PSD...) are never reached, and with them their bugs (fuzz_image crashed Debian's PNM reader).
  const bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool jpeg = size >= 3 && std::memcmp(bytes, "\xff\xd8\xff", 3) == 0;
  if (!png && !jpeg) fail("{}: not a WebP, PNG or JPEG image", what);
  if (stbi_info_from_memory(bytes, int(size), &w, &h, &channels) && uint64_t(w) * uint64_t(h) > kMaxTexels)
    fail("{}: a {}x{} image is larger than the 2^28 texels Prism accepts", what, w, h);
  unsigned char* data = stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4);
  if (!data)
    fail("{}: cannot decode the image ({})", what, stbi_failure_reason() ? stbi_failure_reason() : "unknown format");
  std::vector<uint8_t> rgba(data, data + size_t(w) * h * 4);
  stbi_image_free(data);
  return std::make_shared<Image>(w, h, std::move(rgba));
}

namespace {

// srgb_to_linear of every 8-bit value.
const std::array<float, 256>& srgb_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[i] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

}  // namespace

float srgb_to_linear(uint8_t v) { return srgb_table()[v]; }

std::array<float, 4> Image::mean(bool srgb) const {
  std::array<double, 4> sum{};
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < 4; ++c) sum[c] += srgb && c < 3 ? srgb_to_linear(texel(x, y)[c]) : texel(x, y)[c] / 255.0;
  const double n = double(width_) * height_;
  return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n), float(sum[3] / n)};
}

bool Image::any_zero(int channel) const {
  for (size_t i = size_t(channel); i < rgba_.size(); i += 4)
    if (rgba_[i] == 0) return true;
  return false;
}

Vec2f TextureTransform::apply(Vec2f uv) const {
  if (rotation == 0) return {uv.x * scale.x + offset.x, uv.y * scale.y + offset.y};  // most textures: no sin, cos
  const float c = std::cos(rotation), s = std::sin(rotation);
  const Vec2f scaled(uv.x * scale.x, uv.y * scale.y);
  // glTF's rotation matrix [[c, s], [−s, c]] (the extension's column-major 3x3).
  return {c * scaled.x + s * scaled.y + offset.x, -s * scaled.x + c * scaled.y + offset.y};
}

namespace {

// A texel index in [0, n) for integer coordinate i under the wrap mode.
int wrap_index(int i, int n, Wrap mode) {
  switch (mode) {
    case Wrap::clamp_to_edge:
      return std::clamp(i, 0, n - 1);
    case Wrap::mirrored_repeat: {
      const int period = 2 * n, m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    case Wrap::repeat:
      break;
  }
  return ((i % n) + n) % n;
}

}  // namespace

std::array<float, 4> Texture::lookup(Vec2f uv, bool srgb) const {
  uv = transform.apply(uv);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = {0, 0};
  const int w = image->width(), h = image->height();
  const std::array<float, 256>& linear = srgb_table();
  // The texel at wrapped indices.
  const auto fetch = [&](int x, int y) {
    const uint8_t* t = image->texel(x, y);
    std::array<float, 4> v;
    for (int c = 0; c < 4; ++c) v[c] = srgb && c < 3 ? linear[t[c]] : t[c] / 255.f;
    return v;
  };
  // Texel centres sit at half-integers; huge coordinates are clamped before the int cast.
  const float x = std::clamp(uv.x * float(w) - 0.5f, -1e8f, 1e8f), y = std::clamp(uv.y * float(h) - 0.5f, -1e8f, 1e8f);
  if (nearest)
    return fetch(wrap_index(int(std::floor(x + 0.5f)), w, wrap_s), wrap_index(int(std::floor(y + 0.5f)), h, wrap_t));
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float tx = x - float(x0), ty = y - float(y0);
  const int xa = wrap_index(x0, w, wrap_s), xb = wrap_index(x0 + 1, w, wrap_s);
  const int ya = wrap_index(y0, h, wrap_t), yb = wrap_index(y0 + 1, h, wrap_t);
  const auto a = fetch(xa, ya), b = fetch(xb, ya), c = fetch(xa, yb), d = fetch(xb, yb);
  std::array<float, 4> r;
  for (int i = 0; i < 4; ++i) r[i] = (1 - ty) * ((1 - tx) * a[i] + tx * b[i]) + ty * ((1 - tx) * c[i] + tx * d[i]);
  return r;
}

}  // namespace prism
