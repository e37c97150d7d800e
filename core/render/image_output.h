#pragma once
// Image files: scene-referred OpenEXR (float32 or half RGBA, chromaticities and render metadata
// in the header) and 8-bit PNG previews. Both are written atomically: to a temporary file in
// the destination folder, renamed into place only when complete, so a failed or interrupted
// render never leaves a half-written image.

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "spectral/color_pipeline.h"
#include "spectral/rgb.h"

namespace prism {

struct ExrAttribute {
  std::string name;
  std::variant<std::string, int, double> value;
};

// A channel besides R, G, B, A, named with OpenEXR's layer convention (`layer.channel`).
struct ExrChannel {
  std::string name;
  std::vector<float> values;  // one per pixel, top row first
};

struct ExrImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // interleaved, top row first
  Chromaticities chromaticities;
  std::vector<ExrAttribute> metadata;
  std::vector<ExrChannel> channels{};  // AOVs and spectral bins, always 32-bit float
};

void write_exr(const std::filesystem::path& file, const ExrImage& image, bool half);

// rgb holds display-encoded values in [0, 1] (values outside are clamped).
void write_png(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb);

// Reads the R, G and B channels of an OpenEXR file (environment maps, tests, references).
// The largest image read_exr and read_hdr accept (2^27 pixels, 1.6 GB of float RGB).
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 27;

// Fails naming `file` unless 1 ≤ width, height and width × height ≤ kMaxImagePixels; called
// before anything is allocated for the image.
void check_image_size(const std::filesystem::path& file, int64_t width, int64_t height);

RgbImage read_exr(const std::filesystem::path& file);
// Reads one channel of an OpenEXR file as floats, top row first.
std::vector<float> read_exr_channel(const std::filesystem::path& file, const std::string& name);
// Reads a Radiance RGBE (.hdr) file as linear floats.
RgbImage read_hdr(const std::filesystem::path& file);

}  // namespace prism
