#include "spectral/cie.h"

#include <utility>

#include "core/base/data_path.h"
#include "core/base/error.h"
#include "core/base/table_file.h"

namespace prism {

namespace {

// A table sampled at every nm from kLambdaMin to kLambdaMax, as the CIE publishes them.
DenselySampledSpectrum dense_column(const NumericTable& table, const std::string& name, const std::string& file) {
  const auto& lambdas = table.column("wavelength_nm");
  const auto& values = table.column(name);
  const int count = int(kLambdaMax - kLambdaMin) + 1;
  if (int(lambdas.size()) != count || lambdas.front() != kLambdaMin)
    fail("{}: expected 1-nm rows from {} to {} nm", file, kLambdaMin, kLambdaMax);
  return DenselySampledSpectrum(int(kLambdaMin), std::vector<float>(values.begin(), values.end()));
}

CieTables load_cie() {
  CieTables t;
  const auto cmf_file = data_file("cie/cie1931_2deg_xyz.csv");
  const auto cmf = read_numeric_table(cmf_file);
  t.x = dense_column(cmf, "xbar", cmf_file.string());
  t.y = dense_column(cmf, "ybar", cmf_file.string());
  t.z = dense_column(cmf, "zbar", cmf_file.string());
  double y_sum = 0;
  for (float v : t.y.values()) y_sum += v;
  t.y_integral = float(y_sum);
  for (size_t i = 0; i < t.y.values().size(); ++i)
    t.xyz_rows.push_back({{t.x.values()[i], t.y.values()[i], t.z.values()[i], 0.f}});

  const auto d65_file = data_file("cie/cie_d65.csv");
  const auto d65 = dense_column(read_numeric_table(d65_file), "relative_power", d65_file.string());
  double d65_y = 0;
  for (size_t i = 0; i < d65.values().size(); ++i) d65_y += double(d65.values()[i]) * t.y.values()[i];
  std::vector<float> normalized(d65.values());
  for (float& v : normalized) v = float(v * (y_sum / d65_y));
  t.d65 = DenselySampledSpectrum(int(kLambdaMin), std::move(normalized));
  return t;
}

}  // namespace

const CieTables& cie() {
  static const CieTables tables = load_cie();
  return tables;
}

Xyz spectrum_to_xyz(const Spectrum& s) {
  const CieTables& t = cie();
  double x = 0, y = 0, z = 0;
  for (int i = 0; i < int(t.y.values().size()); ++i) {
    const double v = evaluate(s, float(t.y.lambda_min() + i));
    x += v * t.x.values()[i];
    y += v * t.y.values()[i];
    z += v * t.z.values()[i];
  }
  return {float(x / t.y_integral), float(y / t.y_integral), float(z / t.y_integral)};
}

Xyz sampled_xyz_mean(const Spectrum& s) {
  const CieTables& t = cie();
  double sum[3] = {0, 0, 0};
  for (size_t j = 0; j + 1 < t.xyz_rows.size(); ++j)
    for (const auto& [f, weight] : {std::pair{0.0, 1 / 6.0}, {0.5, 4 / 6.0}, {1.0, 1 / 6.0}}) {
      const double v = weight * evaluate(s, float(kLambdaMin + double(j) + f));
      for (int c = 0; c < 3; ++c) sum[c] += v * ((1 - f) * t.xyz_rows[j].v[c] + f * t.xyz_rows[j + 1].v[c]);
    }
  return {float(sum[0] / t.y_integral), float(sum[1] / t.y_integral), float(sum[2] / t.y_integral)};
}

}  // namespace prism
