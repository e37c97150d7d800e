// Radiance RGBE (.hdr) images (Ward, "Real Pixels", Graphics Gems II, 1991; Radiance's
// color.c freadscan): a text header, a resolution line, then scanlines of 4-byte RGBE pixels,
// flat or run-length encoded per component. Every length is checked against the file, so a
// malformed file is refused and never read past, looped on or allocated for beyond its size.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/base/error.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

struct Reader {
  const std::vector<unsigned char>& bytes;
  const std::string& name;
  size_t at = 0;

  std::string line() {
    const size_t end = std::find(bytes.begin() + long(at), bytes.end(), '\n') - bytes.begin();
    if (end == bytes.size()) fail("{}: Radiance HDR header is cut short", name);
    std::string text(bytes.begin() + long(at), bytes.begin() + long(end));
    at = end + 1;
    return text;
  }
  unsigned char byte() {
    if (at >= bytes.size()) fail("{}: Radiance HDR pixel data is cut short", name);
    return bytes[at++];
  }
};

// RGBE to linear floats, as stb_image and Radiance's colr_color decode them.
void rgbe_to_float(const unsigned char* rgbe, float* rgb) {
  const float f = rgbe[3] ? std::ldexp(1.f, int(rgbe[3]) - (128 + 8)) : 0.f;
  for (int c = 0; c < 3; ++c) rgb[c] = rgbe[c] * f;
}

}  // namespace

RgbImage read_hdr(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot open", name);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader r{bytes, name};
  const std::string magic = r.line();
  if (magic != "#?RADIANCE" && magic != "#?RGBE") fail("{}: not a Radiance HDR (RGBE) image", name);
  bool rgbe = false;
  for (std::string l = r.line(); !l.empty(); l = r.line())
    if (l.rfind("FORMAT=", 0) == 0) {
      if (l != "FORMAT=32-bit_rle_rgbe") fail("{}: unsupported Radiance format '{}'", name, l.substr(7));
      rgbe = true;
    }
  if (!rgbe) fail("{}: Radiance HDR header without FORMAT=32-bit_rle_rgbe", name);
  std::istringstream size_line(r.line());
  std::string y_axis, x_axis;
  int64_t height = 0, width = 0;
  if (!(size_line >> y_axis >> height >> x_axis >> width) || y_axis != "-Y" || x_axis != "+X")
    fail("{}: Radiance HDR resolution line must read '-Y height +X width'", name);
  check_image_size(file, width, height);
  // The fewest bytes the scanlines can take, flat (4 per pixel) or run-length encoded (a 4-byte
  // head, then per component a 2-byte run for every 127 pixels): checked before allocating.
  const int64_t shortest_scanline = std::min<int64_t>(4 * width, 4 + 4 * 2 * ((width + 126) / 127));
  if (int64_t(bytes.size() - r.at) < height * shortest_scanline)
    fail("{}: Radiance HDR pixel data is cut short ({} bytes for a {}x{} image)", name, bytes.size() - r.at, width,
         height);

  RgbImage img;
  img.width = int(width);
  img.height = int(height);
  img.rgb.resize(size_t(width) * height * 3);
  std::vector<unsigned char> scan(size_t(width) * 4);
  bool flat = width < 8 || width > 0x7fff;
  for (int64_t y = 0; y < height; ++y) {
    if (!flat) {
      unsigned char head[4];
      for (unsigned char& b : head) b = r.byte();
      if (head[0] != 2 || head[1] != 2 || (head[2] & 0x80)) {
        flat = true;  // not run-length encoded: these bytes are the first pixel of flat data
        r.at -= 4;
      } else if ((head[2] << 8 | head[3]) != width) {
        fail("{}: scanline {} gives a width of {}, the header {}", name, y, head[2] << 8 | head[3], width);
      }
    }
    if (flat) {
      if (bytes.size() - r.at < scan.size()) fail("{}: Radiance HDR pixel data is cut short", name);
      std::memcpy(scan.data(), &bytes[r.at], scan.size());
      r.at += scan.size();
    } else {
      // Each component in turn: runs (count > 128: count − 128 copies of one byte) or literals.
      for (int c = 0; c < 4; ++c)
        for (int64_t x = 0; x < width;) {
          int count = r.byte();
          const bool run = count > 128;
          if (run) count -= 128;
          if (count == 0 || count > width - x) fail("{}: scanline {} has a run that does not fit", name, y);
          const unsigned char value = run ? r.byte() : 0;
          for (int i = 0; i < count; ++i, ++x) scan[size_t(x) * 4 + c] = run ? value : r.byte();
        }
    }
    for (int64_t x = 0; x < width; ++x) rgbe_to_float(&scan[size_t(x) * 4], &img.rgb[(size_t(y) * width + x) * 3]);
  }
  return img;
}

}  // namespace prism
