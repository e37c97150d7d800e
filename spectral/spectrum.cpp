#include "spectral/spectrum.h"

#include <algorithm>

#include "core/base/error.h"
#include "spectral/cie.h"

namespace prism {

TabulatedSpectrum::TabulatedSpectrum(std::vector<float> lambdas, std::vector<float> values, Outside outside)
    : lambdas_(std::move(lambdas)), values_(std::move(values)), outside_(outside) {
  if (lambdas_.empty() || lambdas_.size() != values_.size())
    fail("tabulated spectrum needs as many values as wavelengths (got {} and {})", lambdas_.size(), values_.size());
  if (!std::is_sorted(lambdas_.begin(), lambdas_.end())) fail("tabulated spectrum wavelengths must increase");
}

float TabulatedSpectrum::operator()(float lambda) const {
  const bool hold = outside_ == Outside::hold;
  if (!(lambda > lambdas_.front())) return hold || lambda == lambdas_.front() ? values_.front() : 0.f;  // NaN too
  if (!(lambda < lambdas_.back())) return hold || lambda == lambdas_.back() ? values_.back() : 0.f;
  const size_t i = size_t(std::upper_bound(lambdas_.begin(), lambdas_.end(), lambda) - lambdas_.begin()) - 1;
  const float t = (lambda - lambdas_[i]) / (lambdas_[i + 1] - lambdas_[i]);
  return values_[i] + t * (values_[i + 1] - values_[i]);  // exact where neighbours are equal
}

float BlackbodySpectrum::planck(float lambda_nm, float kelvin) {
  if (kelvin <= 0) return 0.f;
  constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
  const double l = lambda_nm * 1e-9;
  return float((2 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * kelvin)) - 1)));
}

BlackbodySpectrum::BlackbodySpectrum(float kelvin) : kelvin_(kelvin) {
  const float lambda_peak = float(2.8977721e-3 / kelvin * 1e9);  // Wien's displacement law [nm]
  normalization_ = 1.f / planck(lambda_peak, kelvin);
}

RgbAlbedoSpectrum::RgbAlbedoSpectrum(Rgb rgb) {
  for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.f, 1.f);
  rsp = RgbToSpectrumTable::srgb()(rgb);
}

RgbUnboundedSpectrum::RgbUnboundedSpectrum(Rgb rgb) {
  // Defined for any input: NaN reads as 0, and values are clamped to [0, 1e30] so that 2 m stays finite.
  for (int c = 0; c < 3; ++c) rgb[c] = std::isnan(rgb[c]) ? 0.f : std::clamp(rgb[c], 0.f, 1e30f);
  const float m = rgb.max();
  scale = 2 * m;
  rsp = RgbToSpectrumTable::srgb()(scale > 0 ? rgb / scale : Rgb{0, 0, 0});
}

RgbIlluminantSpectrum::RgbIlluminantSpectrum(Rgb rgb) : shape(rgb), illuminant(&cie().d65) {}

float RgbIlluminantSpectrum::operator()(float lambda) const { return shape(lambda) * (*illuminant)(lambda); }

template <int N>
requires(N == 1 || N == 4 ||
         N == 8) SampledSpectrum<N> RgbIlluminantSpectrum::operator()(const SampledWavelengths<N>& lambda) const {
  return shape(lambda) * (*illuminant)(lambda);
}
template SampledSpectrum<1> RgbIlluminantSpectrum::operator()(const SampledWavelengths<1>&) const;
template SampledSpectrum<4> RgbIlluminantSpectrum::operator()(const SampledWavelengths<4>&) const;
template SampledSpectrum<8> RgbIlluminantSpectrum::operator()(const SampledWavelengths<8>&) const;

RgbAbsorptionSpectrum::RgbAbsorptionSpectrum(Rgb t, float distance)
    : transmittance(t), inv_distance(1 / std::max(distance, 1e-30f)) {}

DenselySampledSpectrum densely_sampled(const Spectrum& s) {
  std::vector<float> values;
  for (int lambda = int(kLambdaMin); lambda <= int(kLambdaMax); ++lambda) values.push_back(evaluate(s, float(lambda)));
  return DenselySampledSpectrum(int(kLambdaMin), std::move(values));
}

}  // namespace prism
