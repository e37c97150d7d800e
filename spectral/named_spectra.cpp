#include "spectral/named_spectra.h"

#include <cctype>
#include <cmath>
#include <map>

#include "core/base/data_path.h"
#include "core/base/table_file.h"
#include "spectral/cie.h"

namespace prism {

namespace {

// Every column of a table of relative powers against `wavelength_nm`, by its header name.
void add_columns(std::map<std::string, Spectrum, std::less<>>& into, const char* file) {
  const auto path = data_file(file);
  const NumericTable table = read_numeric_table(path);
  std::vector<float> lambdas;
  for (double l : table.column("wavelength_nm")) lambdas.push_back(float(l));
  for (const std::string& name : table.names) {
    if (name == "wavelength_nm") continue;
    const std::vector<double>& column = table.column(name);
    into.emplace(name, TabulatedSpectrum(lambdas, std::vector<float>(column.begin(), column.end())));
  }
}

const std::map<std::string, Spectrum, std::less<>>& illuminants() {
  static const auto table = [] {
    std::map<std::string, Spectrum, std::less<>> t;
    std::vector<float> a;
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l) a.push_back(float(illuminant_a(l)));
    t.emplace("A", DenselySampledSpectrum(int(kLambdaMin), std::move(a)));
    t.emplace("D65", cie().d65);
    t.emplace("E", ConstantSpectrum{1.f});
    add_columns(t, "cie/cie_daylight.csv");
    add_columns(t, "cie/cie_illuminants_fl_led.csv");
    return t;
  }();
  return table;
}

}  // namespace

double illuminant_a(double lambda_nm) {
  constexpr double c2 = 1.435e7;
  return 100 * std::pow(560 / lambda_nm, 5) * std::expm1(c2 / (2848 * 560.0)) / std::expm1(c2 / (2848 * lambda_nm));
}

std::optional<Spectrum> named_illuminant(std::string_view name) {
  std::string key(name);
  if (key.size() > 2 && key.rfind("FL", 0) == 0 && std::isdigit(static_cast<unsigned char>(key[2])))
    key.erase(1, 1);  // FL1 … FL12: the CIE's names of F1 … F12
  const auto& t = illuminants();
  const auto it = t.find(key);
  if (it == t.end()) return std::nullopt;
  return it->second;
}

const std::vector<std::string>& named_illuminants() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, spectrum] : illuminants()) n.push_back(name);
    return n;
  }();
  return names;
}

}  // namespace prism
