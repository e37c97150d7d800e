#include "core/render/image_output.h"

#include <ImfAttribute.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>

#include "core/base/atomic_file.h"
#include "core/base/error.h"

namespace prism {

void check_image_size(const std::filesystem::path& file, int64_t width, int64_t height) {
  if (width < 1 || height < 1 || width > int64_t(kMaxImagePixels) || width * height > int64_t(kMaxImagePixels))
    fail("{}: a {}x{} image (Prism reads images of 1 to 2^27 pixels)", file.string(), width, height);
}

void write_exr(const std::filesystem::path& file, const ExrImage& image, bool half) {
  if (image.rgb.size() != size_t(image.width) * image.height * 3) fail("{}: image size mismatch", file.string());
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    Imf::Header header(image.width, image.height);
    const Chromaticities& c = image.chromaticities;
    Imf::addChromaticities(header, Imf::Chromaticities({c.red[0], c.red[1]}, {c.green[0], c.green[1]},
                                                       {c.blue[0], c.blue[1]}, {c.white[0], c.white[1]}));
    for (const ExrAttribute& a : image.metadata) {
      if (const auto* s = std::get_if<std::string>(&a.value))
        header.insert(a.name, Imf::StringAttribute(*s));
      else if (const auto* i = std::get_if<int>(&a.value))
        header.insert(a.name, Imf::IntAttribute(*i));
      else
        header.insert(a.name, Imf::DoubleAttribute(std::get<double>(a.value)));
    }
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(type));
    for (const ExrChannel& c : image.channels) {
      if (c.values.size() != size_t(image.width) * image.height)
        throw std::runtime_error("channel " + c.name + " has the wrong size");
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    }

    // Planar copies in the file's pixel type; alpha is 1 (every pixel is covered).
    const size_t pixels = size_t(image.width) * image.height;
    std::vector<float> planes_f(half ? 0 : pixels * 4);
    std::vector<Imath::half> planes_h(half ? pixels * 4 : 0);
    for (size_t p = 0; p < pixels; ++p)
      for (int ch = 0; ch < 4; ++ch) {
        const float v = ch < 3 ? image.rgb[p * 3 + ch] : 1.f;
        if (half)
          planes_h[ch * pixels + p] = Imath::half(v);
        else
          planes_f[ch * pixels + p] = v;
      }
    Imf::FrameBuffer fb;
    const size_t size = half ? sizeof(Imath::half) : sizeof(float);
    for (int ch = 0; ch < 4; ++ch) {
      char* base = half ? reinterpret_cast<char*>(planes_h.data() + ch * pixels)
                        : reinterpret_cast<char*>(planes_f.data() + ch * pixels);
      fb.insert(names[ch], Imf::Slice(type, base, size, size * image.width));
    }
    for (const ExrChannel& c : image.channels)
      fb.insert(c.name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(c.values.data())),
                                   sizeof(float), sizeof(float) * image.width));
    Imf::OutputFile out(tmp.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(image.height);
  });
}

void write_png(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb) {
  std::vector<unsigned char> bytes(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.f, 1.f) : 0.f;
    bytes[i] = static_cast<unsigned char>(std::lround(v * 255.f));
  }
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    if (!stbi_write_png(tmp.c_str(), width, height, 3, bytes.data(), width * 3))
      throw std::runtime_error("PNG encoder failed");
  });
}

namespace {

// The highest ratio of pixel bytes to file bytes each OpenEXR compression can reach: RLE
// stores a run of 128 bytes in 2; deflate (ZIP, ZIPS) at most 1032:1, PXR24 deflates 24 of
// each 32 bits; B44A keeps a flat 4×4 block of halves (32 bytes) in 3 (B44 always in 14). PIZ and DWA have no
// simple bound and get deflate after RLE (64 · 1032).
double best_compression_ratio(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION:
      return 1;
    case Imf::RLE_COMPRESSION:
      return 64;
    case Imf::ZIPS_COMPRESSION:
    case Imf::ZIP_COMPRESSION:
      return 1032;
    case Imf::PXR24_COMPRESSION:
      return 1032 * 4 / 3.;
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
      return 32 / 3.;
    default:
      return 64 * 1032;
  }
}

// OpenEXR 3.1 fills a chunk whose stored data is shorter than its lines with zeros, so a
// 700-byte file can claim 40 million pixels; refuse, before allocating, a file with missing
// chunks or fewer bytes than its pixels need under its compression's best ratio.
void check_exr_holds_its_pixels(const std::filesystem::path& file, const Imf::InputFile& in) {
  if (!in.isComplete()) fail("{}: the OpenEXR file is incomplete (chunks are missing)", file.string());
  const Imath::Box2i dw = in.header().dataWindow();
  double bytes_per_pixel = 0;
  for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c)
    bytes_per_pixel +=
        (c.channel().type == Imf::HALF ? 2. : 4.) / (double(c.channel().xSampling) * c.channel().ySampling);
  const double pixel_bytes = bytes_per_pixel * (double(dw.max.x) - dw.min.x + 1) * (double(dw.max.y) - dw.min.y + 1);
  const double file_bytes = double(std::filesystem::file_size(file));
  if (pixel_bytes > file_bytes * best_compression_ratio(in.header().compression()))
    fail("{}: the OpenEXR pixel data is cut short ({:.0f} bytes cannot hold {:.0f} bytes of pixels)", file.string(),
         file_bytes, pixel_bytes);
}

// Reads the named channels as floats, planar (one plane per name, top row first).
struct ExrPlanes {
  int width, height;
  std::vector<float> planes;
};
ExrPlanes read_exr_planes(const std::filesystem::path& file, const std::vector<std::string>& names) {
  try {
    Imf::InputFile in(file.c_str());
    for (const std::string& name : names)
      if (!in.header().channels().findChannel(name)) throw std::runtime_error("it has no channel " + name);
    const Imath::Box2i dw = in.header().dataWindow();
    check_image_size(file, int64_t(dw.max.x) - dw.min.x + 1, int64_t(dw.max.y) - dw.min.y + 1);
    check_exr_holds_its_pixels(file, in);
    ExrPlanes img{dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, {}};
    const size_t pixels = size_t(img.width) * img.height;
    img.planes.resize(pixels * names.size());
    Imf::FrameBuffer fb;
    // Slice::Make places the data window's origin at the plane's start (offsetting the pointer
    // ourselves by a window origin far from 0 is undefined behaviour, found by fuzz_env_map).
    for (size_t ch = 0; ch < names.size(); ++ch)
      fb.insert(names[ch], Imf::Slice::Make(Imf::FLOAT, img.planes.data() + ch * pixels, dw, sizeof(float),
                                            sizeof(float) * img.width));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("{}: cannot read OpenEXR image: {}", file.string(), e.what());
  }
}

}  // namespace

RgbImage read_exr(const std::filesystem::path& file) {
  const ExrPlanes in = read_exr_planes(file, {"R", "G", "B"});
  RgbImage img{in.width, in.height, std::vector<float>(in.planes.size())};
  const size_t pixels = size_t(img.width) * img.height;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t ch = 0; ch < 3; ++ch) img.rgb[p * 3 + ch] = in.planes[ch * pixels + p];
  return img;
}

std::vector<float> read_exr_channel(const std::filesystem::path& file, const std::string& name) {
  return read_exr_planes(file, {name}).planes;
}

}  // namespace prism
