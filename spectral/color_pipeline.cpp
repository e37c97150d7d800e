#include "spectral/color_pipeline.h"

#include <OpenColorIO/OpenColorIO.h>

#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "core/base/data_path.h"
#include "core/base/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace prism {

struct ColorPipeline::Impl {
  OCIO::ConstConfigRcPtr config;
  std::filesystem::path file;
  std::map<std::string, Chromaticities> chromaticities;  // by canonical colour space name

  OCIO::ConstCPUProcessorRcPtr processor(std::string_view from, std::string_view to) const {
    try {
      return config->getProcessor(std::string(from).c_str(), std::string(to).c_str())->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
      fail("{}: cannot convert '{}' to '{}': {}", file.string(), from, to, e.what());
    }
  }
};

ColorPipeline::ColorPipeline(const std::filesystem::path& config_file) : impl_(std::make_unique<Impl>()) {
  impl_->file = config_file;
  try {
    impl_->config = OCIO::Config::CreateFromFile(config_file.c_str());
    impl_->config->validate();
  } catch (const OCIO::Exception& e) {
    fail("{}: invalid OpenColorIO config: {}", config_file.string(), e.what());
  }
  load_chromaticities(config_file.parent_path() / "chromaticities.csv");
}

// Rows "colorspace,red_x,red_y,green_x,green_y,blue_x,blue_y,white_x,white_y" after '#' comments
// and a header line.
void ColorPipeline::load_chromaticities(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (std::exchange(header, false)) continue;
    std::stringstream ss(line);
    std::string name, cell;
    std::getline(ss, name, ',');
    float v[8];
    for (float& x : v) {
      if (!std::getline(ss, cell, ',')) fail("{}: row '{}' needs 8 numbers", file.string(), name);
      x = std::stof(cell);
    }
    impl_->chromaticities[canonical_name(name)] = {{v[0], v[1]}, {v[2], v[3]}, {v[4], v[5]}, {v[6], v[7]}};
  }
}

ColorPipeline::~ColorPipeline() = default;

const ColorPipeline& ColorPipeline::standard() {
  static const ColorPipeline pipeline(data_file("ocio/config.ocio"));
  return pipeline;
}

std::vector<std::string> ColorPipeline::color_spaces() const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumColorSpaces(); ++i)
    names.emplace_back(impl_->config->getColorSpaceNameByIndex(i));
  return names;
}

std::string ColorPipeline::canonical_name(std::string_view space) const {
  const auto cs = impl_->config->getColorSpace(std::string(space).c_str());
  if (!cs) {
    std::string list;
    for (const auto& n : color_spaces()) list += (list.empty() ? "'" : ", '") + n + "'";
    fail("unknown colour space '{}'; {} offers {}", space, impl_->file.string(), list);
  }
  if (cs->isData()) fail("colour space '{}' holds non-colour data and cannot be an image's colour space", space);
  return cs->getName();
}

void ColorPipeline::convert(std::string_view from, std::string_view to, float* rgb, size_t pixels) const {
  OCIO::PackedImageDesc desc(rgb, long(pixels), 1, 3);
  impl_->processor(from, to)->apply(desc);
}

void ColorPipeline::xyz_to_display(std::string_view display, std::string_view view, float* rgb, size_t pixels) const {
  try {
    auto transform = OCIO::DisplayViewTransform::Create();
    transform->setSrc(kXyz);
    transform->setDisplay(std::string(display).c_str());
    transform->setView(std::string(view).c_str());
    OCIO::PackedImageDesc desc(rgb, long(pixels), 1, 3);
    impl_->config->getProcessor(transform)->getDefaultCPUProcessor()->apply(desc);
  } catch (const OCIO::Exception& e) {
    fail("{}: cannot apply display '{}' view '{}': {}", impl_->file.string(), display, view, e.what());
  }
}

Chromaticities ColorPipeline::chromaticities(std::string_view space) const {
  const auto it = impl_->chromaticities.find(canonical_name(space));
  if (it == impl_->chromaticities.end())
    fail("{}: no chromaticities listed for colour space '{}' in chromaticities.csv", impl_->file.string(), space);
  return it->second;
}

std::array<std::array<double, 3>, 3> ColorPipeline::matrix_from_xyz(std::string_view space) const {
  float unit[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // X, Y, Z, one per triple
  convert(kXyz, space, unit, 3);
  std::array<std::array<double, 3>, 3> m;
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column) m[row][column] = unit[column * 3 + row];
  return m;
}

}  // namespace prism
