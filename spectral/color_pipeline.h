#pragma once
// The colour pipeline at the end of a render: the film's CIE XYZ (D65-relative, scene-referred)
// goes through OpenColorIO, with Prism's own config (data/ocio/config.ocio), to the output
// colour space, or through a display view to an 8-bit preview.

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace prism {

// CIE xy of the primaries and white of an RGB space (what OpenEXR's chromaticities attribute holds).
struct Chromaticities {
  float red[2], green[2], blue[2], white[2];
};

class ColorPipeline {
 public:
  static constexpr const char* kXyz = "CIE-XYZ-D65";
  static constexpr const char* kDefaultOutput = "Linear Rec.709 (sRGB)";
  static constexpr const char* kDefaultDisplay = "sRGB";
  static constexpr const char* kDefaultView = "Standard";

  explicit ColorPipeline(const std::filesystem::path& config_file);
  ~ColorPipeline();
  static const ColorPipeline& standard();  // data/ocio/config.ocio, loaded once

  // The colour space's canonical name (aliases and any letter case accepted); throws
  // prism::Error listing the available spaces if there is none such, or if it holds data.
  std::string canonical_name(std::string_view space) const;
  std::vector<std::string> color_spaces() const;

  // Converts interleaved RGB triples in place.
  void convert(std::string_view from, std::string_view to, float* rgb, size_t pixels) const;
  // The 3×3 matrix (rows: the space's channels) that takes the film's XYZ to a linear output
  // space, found by converting the unit vectors (every output space of the config is linear).
  std::array<std::array<double, 3>, 3> matrix_from_xyz(std::string_view space) const;
  // Converts XYZ triples in place through a display's view (e.g. sRGB / Standard) for previews.
  void xyz_to_display(std::string_view display, std::string_view view, float* rgb, size_t pixels) const;

  // Native primaries and white of an RGB space, from chromaticities.csv beside the config
  // (the config's matrices include the adaptation to D65, so they cannot tell the native white).
  Chromaticities chromaticities(std::string_view space) const;

 private:
  void load_chromaticities(const std::filesystem::path& file);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace prism
