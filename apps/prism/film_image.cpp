#include "apps/prism/film_image.h"

#include <charconv>

#include "core/base/error.h"
#include "core/render/error_estimate.h"
#include "spectral/cie.h"
#include "spectral/named_spectra.h"

namespace prism {

namespace {

// Planar copy of one field of an interleaved image.
std::vector<float> plane(const std::vector<float>& interleaved, int fields, int field) {
  std::vector<float> out(interleaved.size() / fields);
  for (size_t p = 0; p < out.size(); ++p) out[p] = interleaved[p * fields + field];
  return out;
}

}  // namespace

OutputChannels output_channels(const std::string& colorspace, const WhiteBalance* white_balance) {
  const OutputChannels space = ColorPipeline::standard().matrix_from_xyz(colorspace);
  if (!white_balance) return space;
  OutputChannels m{};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column)
      for (int i = 0; i < 3; ++i) m[row][column] += space[row][i] * white_balance->m[i * 3 + column];
  return m;
}

// The AOV layers and spectral bins the options ask for.
std::vector<ExrChannel> extra_channels(const Film& film, const std::string& colorspace, const OutputChannels& output) {
  std::vector<ExrChannel> channels;
  const auto add_layer = [&](const std::string& layer, const std::vector<float>& image, const char* names) {
    for (int c = 0; c < 3; ++c) channels.push_back({layer + "." + names[c], plane(image, 3, c)});
  };
  if (film.aovs() & kAovAlbedo) {
    std::vector<float> albedo = film.albedo_image();
    ColorPipeline::standard().convert(ColorPipeline::kXyz, colorspace, albedo.data(), albedo.size() / 3);
    add_layer("albedo", albedo, "RGB");
  }
  if (film.aovs() & kAovNormal) add_layer("N", film.normal_image(), "XYZ");
  if (film.aovs() & kAovDepth) channels.push_back({"Z", film.depth_image()});
  if (film.aovs() & kAovVariance) {
    const ErrorEstimate error(film, output);
    std::vector<float> rgb(film.pixel_count() * 3), y(film.pixel_count());
    for (size_t p = 0; p < film.pixel_count(); ++p) {
      for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = float(error.output_variance_of_mean(p, k));
      y[p] = float(error.variance_of_mean(p, 1));
    }
    add_layer("variance", rgb, "RGB");
    channels.push_back({"variance.Y", std::move(y)});
  }
  if (film.aovs() & kAovSpp) {
    std::vector<float> n(film.pixel_count());
    for (size_t p = 0; p < n.size(); ++p) n[p] = float(film.samples(p));
    channels.push_back({"spp", std::move(n)});
  }
  const SpectralBins& bins = film.bins();
  if (bins.count() > 0) {
    const std::vector<float> spectral = film.spectral_image();
    for (int b = 0; b < bins.count(); ++b) channels.push_back({bins.channel_name(b), plane(spectral, bins.count(), b)});
  }
  return channels;
}

ExrImage film_image(const Film& film, const std::string& colorspace, const WhiteBalance* white_balance) {
  ExrImage image{film.width(),
                 film.height(),
                 film.xyz_image(),
                 ColorPipeline::standard().chromaticities(colorspace),
                 {},
                 extra_channels(film, colorspace, output_channels(colorspace, white_balance))};
  if (white_balance) white_balance->apply(image.rgb.data(), image.rgb.size() / 3);
  ColorPipeline::standard().convert(ColorPipeline::kXyz, colorspace, image.rgb.data(), image.rgb.size() / 3);
  return image;
}

std::optional<WhiteBalance> white_balance_option(const std::string& text) {
  if (text.empty() || text == "none") return std::nullopt;
  double kelvin = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), kelvin);
  if (ec == std::errc() && end == text.data() + text.size()) {
    if (!(kelvin >= 1000 && kelvin <= 40000))
      fail("--white-balance {}: a colour temperature must be 1000-40000 K", text);
    return WhiteBalance::to_d65(fmt::format("{:g} K", kelvin), spectrum_to_xyz(BlackbodySpectrum(float(kelvin))));
  }
  const auto illuminant = named_illuminant(text);
  if (!illuminant) {
    std::string names;
    for (const std::string& n : named_illuminants()) names += (names.empty() ? "" : ", ") + n;
    fail("--white-balance {}: not a named illuminant ({}), a temperature in kelvin or none", text, names);
  }
  return WhiteBalance::to_d65(text, spectrum_to_xyz(*illuminant));
}

}  // namespace prism
