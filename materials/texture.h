#pragma once
// Image textures as glTF defines them (glTF 2.0 §3.8): 8-bit RGBA texels decoded by stb_image
// from the file's PNG or JPEG bytes (libwebp: WebP), a sampler (wrap modes, nearest or bilinear filtering), a
// texture-coordinate set and KHR_texture_transform. (0, 0) is the image's top-left corner.
// Colour textures (base colour, emissive) are sRGB-encoded and decoded to linear on lookup.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/base/vec.h"

namespace prism {

class Image {
 public:
  Image(int width, int height, std::vector<uint8_t> rgba);
  // Decodes PNG, JPEG or WebP bytes; throws prism::Error naming `what` if they are not an image.
  static std::shared_ptr<const Image> decode(const unsigned char* bytes, size_t size, const std::string& what);

  int width() const { return width_; }
  int height() const { return height_; }
  const uint8_t* texel(int x, int y) const { return &rgba_[(size_t(y) * width_ + x) * 4]; }
  std::array<float, 4> mean(bool srgb) const;  // average texel, decoded
  bool any_zero(int channel) const;            // whether some texel has 0 in channel (0-3)

 private:
  int width_, height_;
  std::vector<uint8_t> rgba_;
};

enum class Wrap { repeat, clamp_to_edge, mirrored_repeat };

// KHR_texture_transform: uv' = T(offset) · R(rotation) · S(scale) · uv.
struct TextureTransform {
  Vec2f offset{0, 0}, scale{1, 1};
  float rotation = 0;
  Vec2f apply(Vec2f uv) const;
};

// IEC 61966-2-1 sRGB decoding of an 8-bit value.
float srgb_to_linear(uint8_t v);

struct Texture {
  std::shared_ptr<const Image> image;
  Wrap wrap_s = Wrap::repeat, wrap_t = Wrap::repeat;
  bool nearest = false;  // glTF magFilter NEAREST; otherwise bilinear
  int texcoord = 0;      // TEXCOORD_n set
  TextureTransform transform;

  // RGBA at texture coordinates uv (before the transform), RGB decoded from sRGB when srgb.
  std::array<float, 4> lookup(Vec2f uv, bool srgb) const;
};

}  // namespace prism
