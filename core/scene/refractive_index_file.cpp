#include "core/scene/refractive_index_file.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/base/error.h"
#include "spectral/wavelengths.h"

namespace prism {

namespace {

struct Table {
  std::vector<double> lambda_um, values;
};

// The numbers of one line, separated by commas, tabs or spaces; false if anything else is there.
bool line_numbers(const std::string& line, std::vector<double>& out) {
  out.clear();
  const char* p = line.c_str();
  const char* end = p + line.size();
  while (p < end) {
    while (p < end && (*p == ',' || *p == ' ' || *p == '\t' || *p == '\r')) ++p;
    if (p == end) break;
    double v = 0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc()) return false;
    out.push_back(v);
    p = next;
  }
  return true;
}

// The rows of `columns` numbers in a text block (YAML "data" or a CSV section).
std::vector<std::vector<double>> rows(const std::string& text, size_t columns, const std::string& what) {
  std::vector<std::vector<double>> out;
  std::istringstream in(text);
  std::string line;
  std::vector<double> numbers;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (!line_numbers(line, numbers) || numbers.size() != columns)
      fail("{}: expected {} numbers on the line '{}'", what, columns, line);
    out.push_back(numbers);
  }
  return out;
}

void check_increasing(const std::vector<double>& lambda_um, const std::string& what) {
  if (lambda_um.empty()) fail("{}: a table without rows", what);
  for (size_t i = 0; i < lambda_um.size(); ++i) {
    if (!(lambda_um[i] > 0 && lambda_um[i] < 1e3)) fail("{}: wavelength {} µm is out of range", what, lambda_um[i]);
    if (i > 0 && !(lambda_um[i] > lambda_um[i - 1]))
      fail("{}: wavelengths must increase ({} µm after {} µm)", what, lambda_um[i], lambda_um[i - 1]);
  }
}

// A tabulated quantity against λ in µm, as a spectrum in nm that holds its end values.
TabulatedSpectrum tabulated(const Table& t, bool positive, const std::string& what) {
  check_increasing(t.lambda_um, what);
  std::vector<float> nm, v;
  for (size_t i = 0; i < t.values.size(); ++i) {
    const double x = t.values[i];
    if (!std::isfinite(x) || x < 0 || (positive && x == 0))
      fail("{}: value {} at {} µm must be finite and {}", what, x, t.lambda_um[i],
           positive ? "positive" : "non-negative");
    nm.push_back(float(t.lambda_um[i] * 1e3));
    v.push_back(float(x));
  }
  return TabulatedSpectrum(std::move(nm), std::move(v));
}

// n(λ) of refractiveindex.info's dispersion formula `formula` (1–9) with coefficients c, λ in µm.
double formula_index(int formula, const std::vector<double>& c, double l) {
  const auto at = [&](size_t i) { return i < c.size() ? c[i] : 0.0; };
  const double l2 = l * l;
  double r = at(0);
  switch (formula) {
    case 1:  // Sellmeier: n² − 1 = C1 + Σ C_{2i} λ² / (λ² − C_{2i+1}²)
      for (size_t i = 1; i + 1 < c.size(); i += 2) r += c[i] * l2 / (l2 - c[i + 1] * c[i + 1]);
      return std::sqrt(std::max(r + 1, 0.0));
    case 2:  // Sellmeier-2: n² − 1 = C1 + Σ C_{2i} λ² / (λ² − C_{2i+1})
      for (size_t i = 1; i + 1 < c.size(); i += 2) r += c[i] * l2 / (l2 - c[i + 1]);
      return std::sqrt(std::max(r + 1, 0.0));
    case 3:  // polynomial: n² = C1 + Σ C_{2i} λ^{C_{2i+1}}
      for (size_t i = 1; i + 1 < c.size(); i += 2) r += c[i] * std::pow(l, c[i + 1]);
      return std::sqrt(std::max(r, 0.0));
    case 4:  // RefractiveIndex.INFO: n² = C1 + Σ_{two} C λ^C / (λ² − C^C) + Σ C λ^C
      r += at(1) * std::pow(l, at(2)) / (l2 - std::pow(at(3), at(4)));
      r += at(5) * std::pow(l, at(6)) / (l2 - std::pow(at(7), at(8)));
      for (size_t i = 9; i + 1 < c.size(); i += 2) r += c[i] * std::pow(l, c[i + 1]);
      return std::sqrt(std::max(r, 0.0));
    case 5:  // Cauchy: n = C1 + Σ C_{2i} λ^{C_{2i+1}}
      for (size_t i = 1; i + 1 < c.size(); i += 2) r += c[i] * std::pow(l, c[i + 1]);
      return r;
    case 6:  // gases: n − 1 = C1 + Σ C_{2i} / (C_{2i+1} − λ⁻²)
      for (size_t i = 1; i + 1 < c.size(); i += 2) r += c[i] / (c[i + 1] - 1 / l2);
      return r + 1;
    case 7: {  // Herzberger: n = C1 + C2/(λ² − 0.028) + C3 (1/(λ² − 0.028))² + C4 λ² + C5 λ⁴ + C6 λ⁶
      const double q = 1 / (l2 - 0.028);
      return r + at(1) * q + at(2) * q * q + at(3) * l2 + at(4) * l2 * l2 + at(5) * l2 * l2 * l2;
    }
    case 8: {  // Retro: (n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²
      const double a = r + at(1) * l2 / (l2 - at(2)) + at(3) * l2;
      return std::sqrt(std::max((1 + 2 * a) / (1 - a), 0.0));
    }
    case 9:  // Exotic: n² = C1 + C2/(λ² − C3) + C4 (λ − C5)/((λ − C5)² + C6)
      r += at(1) / (l2 - at(2)) + at(3) * (l - at(4)) / ((l - at(4)) * (l - at(4)) + at(5));
      return std::sqrt(std::max(r, 0.0));
  }
  return 0;
}

// A formula's n as Prism's index model: Sellmeier exactly, the others at every nm of the visible
// range inside the formula's wavelength range (µm).
IorModel formula_model(int formula, const std::vector<double>& c, double lo_um, double hi_um, const std::string& what) {
  if (formula < 1 || formula > 9)
    fail("{}: dispersion formula {} is not one of refractiveindex.info's 1-9", what, formula);
  if ((formula == 1 || formula == 2) && c.size() % 2 == 1) {
    SellmeierIor s;
    s.a = float(c[0]);
    for (size_t i = 1; i + 1 < c.size(); i += 2) {
      s.b.push_back(float(c[i]));
      s.c.push_back(float(formula == 1 ? c[i + 1] * c[i + 1] : c[i + 1]));
    }
    return s;
  }
  std::vector<float> nm, n;
  const double first = std::max(double(kLambdaMin), std::ceil(lo_um * 1e3)),
               last = std::min(double(kLambdaMax), std::floor(hi_um * 1e3));
  if (!(first <= last)) fail("{}: the formula's range {}-{} µm misses the visible, 0.36-0.83 µm", what, lo_um, hi_um);
  for (double l = first; l <= last; ++l) {
    const double v = formula_index(formula, c, l * 1e-3);
    if (!(std::isfinite(v) && v > 0)) fail("{}: the formula gives n = {} at {} nm", what, v, l);
    nm.push_back(float(l));
    n.push_back(float(v));
  }
  return TabulatedIor{TabulatedSpectrum(std::move(nm), std::move(n))};
}

std::vector<double> scalar_numbers(const YAML::Node& node, const char* field, const std::string& what) {
  std::vector<double> out;
  if (!node || !node.IsScalar() || !line_numbers(node.as<std::string>(), out) || out.empty())
    fail("{}: \"{}\" must be a list of numbers", what, field);
  return out;
}

OpticalConstants read_yaml(std::string_view text, const std::string& what) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    fail("{}: not a refractiveindex.info YAML file: {}", what, e.what());
  }
  const YAML::Node data = root["DATA"];
  if (!data || !data.IsSequence() || data.size() == 0) fail("{}: no DATA entries", what);
  std::optional<IorModel> n;
  std::optional<TabulatedSpectrum> k;
  try {
    for (const YAML::Node& entry : data) {
      const std::string type = entry["type"] ? entry["type"].as<std::string>() : "";
      if (type == "tabulated nk" || type == "tabulated n" || type == "tabulated k") {
        const size_t columns = type == "tabulated nk" ? 3 : 2;
        if (!entry["data"]) fail("{}: a \"{}\" entry without data", what, type);
        Table tn, tk;
        for (const auto& r : rows(entry["data"].as<std::string>(), columns, what)) {
          (type == "tabulated k" ? tk : tn).lambda_um.push_back(r[0]);
          (type == "tabulated k" ? tk : tn).values.push_back(r[1]);
          if (columns == 3) tk.lambda_um.push_back(r[0]), tk.values.push_back(r[2]);
        }
        if (type != "tabulated k") n = TabulatedIor{tabulated(tn, true, what + " (n)")};
        if (type != "tabulated n") k = tabulated(tk, false, what + " (k)");
      } else if (type.rfind("formula ", 0) == 0) {
        const std::vector<double> range = scalar_numbers(entry["wavelength_range"], "wavelength_range", what);
        if (range.size() != 2) fail("{}: \"wavelength_range\" must hold two wavelengths in µm", what);
        n = formula_model(std::atoi(type.c_str() + 8), scalar_numbers(entry["coefficients"], "coefficients", what),
                          range[0], range[1], what);
      } else {
        fail("{}: unknown DATA type '{}' (expected tabulated nk, tabulated n, tabulated k or formula 1-9)", what, type);
      }
    }
  } catch (const YAML::Exception& e) {
    fail("{}: not a refractiveindex.info YAML file: {}", what, e.what());
  }
  if (!n) fail("{}: the file gives no refractive index n", what);
  return {*n, std::move(k)};
}

OpticalConstants read_csv(std::string_view text, const std::string& what) {
  Table tn, tk;
  Table* section = nullptr;
  std::istringstream in{std::string(text)};
  std::string line;
  std::vector<double> numbers;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (line.rfind("wl,n", 0) == 0 || line.rfind("wl,k", 0) == 0) {
      section = line[3] == 'n' ? &tn : &tk;
      continue;
    }
    if (!section) fail("{}: line {}: expected a \"wl,n\" header first (refractiveindex.info's CSV)", what, row);
    if (!line_numbers(line, numbers) || numbers.size() != 2)
      fail("{}: line {} is not two numbers, a wavelength in µm and a value: '{}'", what, row, line);
    section->lambda_um.push_back(numbers[0]);
    section->values.push_back(numbers[1]);
  }
  if (tn.values.empty()) fail("{}: no \"wl,n\" rows (refractiveindex.info's CSV)", what);
  OpticalConstants c{TabulatedIor{tabulated(tn, true, what + " (n)")}, std::nullopt};
  if (!tk.values.empty()) c.k = tabulated(tk, false, what + " (k)");
  return c;
}

}  // namespace

OpticalConstants read_refractive_index(std::string_view text, const std::string& what) {
  const bool yaml = text.find("DATA:") != std::string_view::npos;
  return yaml ? read_yaml(text, what) : read_csv(text, what);
}

Spectrum index_spectrum(const IorModel& n) {
  if (const auto* t = std::get_if<TabulatedIor>(&n)) return t->n;
  std::vector<float> nm, values;
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l) {
    nm.push_back(float(l));
    values.push_back(ior(n, float(l)));
  }
  return TabulatedSpectrum(std::move(nm), std::move(values));
}

}  // namespace prism
