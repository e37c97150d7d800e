#include "core/scene/spectrum_input.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/base/error.h"
#include "spectral/cie.h"
#include "spectral/named_spectra.h"

namespace prism {

namespace {

const char* use_name(SpectrumUse use) {
  switch (use) {
    case SpectrumUse::emission:
      return "an emission spectrum";
    case SpectrumUse::reflectance:
      return "a reflectance";
    case SpectrumUse::transmittance:
      return "a transmittance";
    case SpectrumUse::index:
      return "a refractive index";
    case SpectrumUse::extinction:
      return "an extinction coefficient";
    case SpectrumUse::coefficient:
      return "a medium's coefficient";
  }
  return "a spectrum";
}

// Whether `v` may be a value of a spectrum for `use`, and the range to name when not.
bool allowed(SpectrumUse use, double v, const char*& range) {
  switch (use) {
    case SpectrumUse::emission:
    case SpectrumUse::extinction:
    case SpectrumUse::coefficient:
      range = "finite and non-negative";
      return std::isfinite(v) && v >= 0;
    case SpectrumUse::reflectance:
    case SpectrumUse::transmittance:
      range = "in [0, 1]";
      return v >= 0 && v <= 1;
    case SpectrumUse::index:
      range = "finite and positive";
      return std::isfinite(v) && v > 0;
  }
  return false;
}

std::string names_list() {
  std::string list;
  for (const std::string& n : named_illuminants()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

double luminance(const Spectrum& s) { return sampled_xyz_mean(s).y; }

Spectrum spectrum_with_luminance(const Spectrum& s, double y) {
  const float scale = float(y / luminance(s));
  const auto scaled = [scale](const std::vector<float>& values) {
    std::vector<float> out(values);
    for (float& v : out) v *= scale;
    return out;
  };
  // Tables keep their points (a step at a table's end stays a step); other kinds at every nm.
  if (const auto* t = std::get_if<TabulatedSpectrum>(&s))
    return TabulatedSpectrum(t->lambdas(), scaled(t->values()), t->outside());
  const DenselySampledSpectrum dense =
      std::holds_alternative<DenselySampledSpectrum>(s) ? std::get<DenselySampledSpectrum>(s) : densely_sampled(s);
  return DenselySampledSpectrum(dense.lambda_min(), scaled(dense.values()));
}

Spectrum named_spectrum(std::string_view name, SpectrumUse use, const std::string& what) {
  if (use != SpectrumUse::emission)
    fail("{}: '{}' names an illuminant, not {} (give a table or a file)", what, name, use_name(use));
  const auto s = named_illuminant(name);
  if (!s) fail("{}: no spectrum is named '{}' (known: {})", what, name, names_list());
  return *s;
}

Spectrum blackbody_spectrum(double kelvin, SpectrumUse use, const std::string& what) {
  if (use != SpectrumUse::emission) fail("{}: a blackbody is an emission spectrum, not {}", what, use_name(use));
  if (!(kelvin >= 100 && kelvin <= 1e6))
    fail("{}: a blackbody needs a temperature in [100, 1e6] K (got {})", what, kelvin);
  return BlackbodySpectrum(float(kelvin));
}

Spectrum checked_spectrum(Spectrum s, SpectrumUse use, const std::string& what) {
  if (use == SpectrumUse::emission && !(luminance(s) > 0))
    fail("{}: the emission spectrum has no luminance (it is 0 wherever the eye sees, 360-830 nm)", what);
  return s;
}

TabulatedSpectrum checked_table(std::vector<double> lambdas, std::vector<double> values, SpectrumUse use,
                                const std::string& what) {
  if (lambdas.empty()) fail("{}: the table is empty", what);
  if (lambdas.size() != values.size()) fail("{}: {} wavelengths but {} values", what, lambdas.size(), values.size());
  for (size_t i = 0; i < lambdas.size(); ++i) {
    if (!(lambdas[i] >= 100 && lambdas[i] <= 1e5))
      fail("{}: wavelength {} nm (row {}) is not in 100-100000 nm", what, lambdas[i], i + 1);
    if (i > 0 && !(lambdas[i] > lambdas[i - 1]))
      fail("{}: wavelengths must increase (row {}: {} nm after {} nm)", what, i + 1, lambdas[i], lambdas[i - 1]);
    const char* range = "";
    if (!allowed(use, values[i], range))
      fail("{}: value {} at {} nm: {} must be {}", what, values[i], lambdas[i], use_name(use), range);
  }
  // Light and reflectance stop where the table does; an index or a coefficient holds its end values.
  const bool constants = use == SpectrumUse::index || use == SpectrumUse::extinction || use == SpectrumUse::coefficient;
  return TabulatedSpectrum(std::vector<float>(lambdas.begin(), lambdas.end()),
                           std::vector<float>(values.begin(), values.end()),
                           constants ? TabulatedSpectrum::Outside::hold : TabulatedSpectrum::Outside::zero);
}

TabulatedSpectrum parse_spectrum_csv(std::string_view text, SpectrumUse use, const std::string& what) {
  std::vector<double> lambdas, values;
  std::istringstream in{std::string(text)};
  std::string line;
  bool header_allowed = true;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    // Two numbers separated by a comma (or a semicolon, tab or spaces).
    double pair[2];
    int found = 0;
    const char* p = line.c_str() + first;
    const char* end = line.c_str() + line.size();
    while (found < 2 && p < end) {
      const auto [next, ec] = std::from_chars(p, end, pair[found]);
      if (ec != std::errc()) break;
      ++found;
      p = next;
      while (p < end && (*p == ',' || *p == ';' || *p == ' ' || *p == '\t')) ++p;
    }
    if (found != 2 || p != end) {
      // One header line before the numbers: words, not a malformed row of numbers.
      const char start = line[first];
      if (header_allowed && lambdas.empty() && !std::isdigit(static_cast<unsigned char>(start)) && start != '-' &&
          start != '+' && start != '.') {
        header_allowed = false;
        continue;
      }
      fail("{}: line {} is not two numbers, a wavelength in nm and a value: '{}'", what, row, line);
    }
    lambdas.push_back(pair[0]);
    values.push_back(pair[1]);
  }
  return checked_table(std::move(lambdas), std::move(values), use, what);
}

Spectrum parse_spectrum_argument(const std::string& text, SpectrumUse use, const std::string& what) {
  if (text.rfind("blackbody:", 0) == 0) {
    double kelvin = 0;
    const char* begin = text.c_str() + 10;
    const auto [end, ec] = std::from_chars(begin, text.c_str() + text.size(), kelvin);
    if (ec != std::errc() || *end) fail("{} '{}': expected blackbody:KELVIN", what, text);
    return checked_spectrum(blackbody_spectrum(kelvin, use, what), use, what);
  }
  if (named_illuminant(text)) return checked_spectrum(named_spectrum(text, use, what), use, what);
  std::ifstream in(text, std::ios::binary);
  if (!in)
    fail("{} '{}': neither a named spectrum ({}), blackbody:KELVIN, nor a readable file", what, text, names_list());
  std::stringstream contents;
  contents << in.rdbuf();
  return checked_spectrum(parse_spectrum_csv(contents.str(), use, what + " (" + text + ")"), use, what);
}

}  // namespace prism
