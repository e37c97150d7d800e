#include "render/image_output.h"

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
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace prism {

namespace {

// Writes through `write(temporary_path)`, then renames the result over `file`.
template <typename Write>
void write_atomically(const std::filesystem::path& file, Write&& write) {
  const auto dir = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) fail("{}: cannot create the folder {}", file.string(), dir.string());
  const auto temporary = dir / fmt::format(".{}.tmp{}", file.filename().string(), getpid());
  try {
    write(temporary);
    std::filesystem::rename(temporary, file);
  } catch (const std::exception& e) {
    std::filesystem::remove(temporary, ec);
    fail("{}: cannot write: {}", file.string(), e.what());
  }
}

}  // namespace

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

RgbImage read_exr(const std::filesystem::path& file) {
  try {
    Imf::InputFile in(file.c_str());
    for (const char* name : {"R", "G", "B"})
      if (!in.header().channels().findChannel(name)) throw std::runtime_error("it has no R, G and B channels");
    const Imath::Box2i dw = in.header().dataWindow();
    RgbImage img;
    check_image_size(file, int64_t(dw.max.x) - dw.min.x + 1, int64_t(dw.max.y) - dw.min.y + 1);
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    const size_t pixels = size_t(img.width) * img.height;
    std::vector<float> planes(pixels * 3);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int ch = 0; ch < 3; ++ch) {
      char* base = reinterpret_cast<char*>(planes.data() + ch * pixels) -
                   (size_t(dw.min.x) + size_t(dw.min.y) * img.width) * sizeof(float);
      fb.insert(names[ch], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * img.width));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    img.rgb.resize(pixels * 3);
    for (size_t p = 0; p < pixels; ++p)
      for (int ch = 0; ch < 3; ++ch) img.rgb[p * 3 + ch] = planes[ch * pixels + p];
    return img;
  } catch (const std::exception& e) {
    fail("{}: cannot read OpenEXR image: {}", file.string(), e.what());
  }
}

}  // namespace prism
