#include "spectral/sigmoid_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/parallel.h"
#include "core/base/transform.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"

namespace prism {

namespace {

constexpr double kLambdaSpan = double(kLambdaMax) - double(kLambdaMin);
constexpr int kMaxIterations = 50;
constexpr int kMaxStepHalvings = 12;
constexpr double kTolerance = 1e-4;  // ΔE*ab: ~1e-6 in RGB, yet above the noise of the float sigmoid
constexpr float kStartZ = 0.2f;      // chains start at the node nearest this z, where c = 0 converges

// 3x3 matrices are kept in the linear part of a Transform, which brings inverse() along.
// The matrix of the OCIO conversion from `from` to `to`: its columns are the images of the unit vectors.
Transform ocio_matrix(const char* from, const char* to) {
  float columns[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ColorPipeline::standard().convert(from, to, &columns[0][0], 3);
  Transform m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.m[i][j] = columns[j][i];
  return m;
}

// What every fit shares, derived once from the CIE tables and the OCIO config.
struct FitContext {
  std::vector<double> t;      // normalised wavelength of each 1-nm sample
  std::vector<Vec3d> weight;  // d65(λ) {x̄,ȳ,z̄}(λ) / Σȳ, so that XYZ = Σ r(λ) weight(λ)
  Vec3d white;                // XYZ of the perfect reflector under D65: CIELAB's reference white
  Transform xyz_to_rgb, rgb_to_xyz;
};

FitContext make_context() {
  const CieTables& tables = cie();
  FitContext c;
  for (size_t i = 0; i < tables.y.values().size(); ++i) {
    const double lambda = tables.y.lambda_min() + double(i);
    c.t.push_back((lambda - kLambdaMin) / kLambdaSpan);
    const Vec3d cmf(tables.x.values()[i], tables.y.values()[i], tables.z.values()[i]);
    c.weight.push_back(cmf * (double(tables.d65.values()[i]) / tables.y_integral));
    c.white += c.weight.back();
  }
  c.xyz_to_rgb = ocio_matrix(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput);
  c.rgb_to_xyz = inverse(c.xyz_to_rgb);
  return c;
}

const FitContext& context() {
  static const FitContext c = make_context();
  return c;
}

// A vector-valued function's value and its Jacobian (in a Transform's linear part).
struct Linearization {
  Vec3d value;
  Transform jacobian;
};

// CIE 1976 L*a*b* of xyz relative to `white`, with ∂Lab/∂XYZ.
Linearization cielab(const Vec3d& xyz, const Vec3d& white) {
  constexpr double d = 6.0 / 29.0;
  Vec3d f, df;
  for (int i = 0; i < 3; ++i) {
    const double u = xyz[i] / white[i];
    const bool cube_root = u > d * d * d;
    f[i] = cube_root ? std::cbrt(u) : u / (3 * d * d) + 4.0 / 29.0;
    df[i] = (cube_root ? 1 / (3 * f[i] * f[i]) : 1 / (3 * d * d)) / white[i];
  }
  Linearization lab{{116 * f.y - 16, 500 * (f.x - f.y), 200 * (f.y - f.z)}, {}};
  lab.jacobian.m[0] = {0, 116 * df.y, 0, 0};
  lab.jacobian.m[1] = {500 * df.x, -500 * df.y, 0, 0};
  lab.jacobian.m[2] = {0, 200 * df.y, -200 * df.z, 0};
  return lab;
}

// XYZ under D65 of the reflectance s(a0 t² + a1 t + a2) (J&H 2019's sigmoid of a quadratic),
// with ∂XYZ/∂(a0, a1, a2) = Σ s'(x) (t², t, 1) weight, where s'(x) = 1 / (2 (1 + x²)^(3/2)).
Linearization reflectance_xyz(const FitContext& c, const NormalizedCoefficients& a) {
  Linearization out;
  Vec3d d[3];
  for (size_t i = 0; i < c.t.size(); ++i) {
    const double t = c.t[i], x = (a[0] * t + a[1]) * t + a[2];
    out.value += c.weight[i] * double(RgbSigmoidPolynomial::sigmoid(float(x)));
    const Vec3d w = c.weight[i] * (0.5 / ((1 + x * x) * std::sqrt(1 + x * x)));
    d[0] += w * (t * t);
    d[1] += w * t;
    d[2] += w;
  }
  for (int row = 0; row < 3; ++row)
    for (int k = 0; k < 3; ++k) out.jacobian.m[row][k] = d[k][row];
  return out;
}

// The residual Lab(reflectance) − Lab(target), whose norm (ΔE*ab) J&H 2019 minimise, and its Jacobian.
Linearization residual(const FitContext& c, const NormalizedCoefficients& a, const Vec3d& target_lab) {
  const Linearization xyz = reflectance_xyz(c, a);
  const Linearization lab = cielab(xyz.value, c.white);
  return {lab.value - target_lab, lab.jacobian * xyz.jacobian};
}

// Node values of the largest component: smoothstep(smoothstep(k / (R − 1))), dense near 0 and 1.
std::vector<float> z_nodes(int resolution) {
  const auto smoothstep = [](double x) { return x * x * (3 - 2 * x); };
  std::vector<float> z(resolution);
  for (int k = 0; k < resolution; ++k) z[k] = float(smoothstep(smoothstep(k / double(resolution - 1))));
  return z;
}

}  // namespace

RgbSigmoidPolynomial SigmoidFit::polynomial() const {
  // Substitute t = (λ − m) / w into a0 t² + a1 t + a2 and collect the powers of λ.
  const double m = kLambdaMin, w = kLambdaSpan;
  const auto& [a0, a1, a2] = normalized;
  return {float(a0 / (w * w)), float(a1 / w - 2 * a0 * m / (w * w)), float(a0 * m * m / (w * w) - a1 * m / w + a2)};
}

SigmoidFit fit_sigmoid_polynomial(Rgb target, NormalizedCoefficients a) {
  const FitContext& c = context();
  const Vec3d target_lab = cielab(c.rgb_to_xyz.vector(Vec3d(target.r, target.g, target.b)), c.white).value;
  Linearization r = residual(c, a, target_lab);
  for (int iteration = 0; iteration < kMaxIterations && length(r.value) > kTolerance; ++iteration) {
    // Gauss–Newton (J&H 2019's optimiser); with three residuals and three unknowns it solves J Δ = −r.
    const Vec3d step = inverse(r.jacobian).vector(-r.value);
    // Backtracking: halve the step until ΔE decreases; stop when no step does.
    bool improved = false;
    for (int halvings = 0; halvings < kMaxStepHalvings && !improved; ++halvings) {
      const double s = std::ldexp(1.0, -halvings);
      const NormalizedCoefficients trial = {a[0] + s * step.x, a[1] + s * step.y, a[2] + s * step.z};
      Linearization r_trial = residual(c, trial, target_lab);
      if (length(r_trial.value) < length(r.value)) {
        a = trial;
        r = r_trial;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return {a, length(r.value)};
}

Rgb reflectance_rgb(const RgbSigmoidPolynomial& reflectance) {
  const DenselySampledSpectrum& d65 = cie().d65;
  std::vector<float> lit(d65.values().size());
  for (size_t i = 0; i < lit.size(); ++i) lit[i] = reflectance(float(d65.lambda_min() + int(i))) * d65.values()[i];
  const Xyz xyz = spectrum_to_xyz(DenselySampledSpectrum(d65.lambda_min(), std::move(lit)));
  const Vec3d rgb = context().xyz_to_rgb.vector(Vec3d(xyz.x, xyz.y, xyz.z));
  return {float(rgb.x), float(rgb.y), float(rgb.z)};
}

Rgb table_node_rgb(std::span<const float> z_nodes, int l, int zi, int yi, int xi) {
  const float z = z_nodes[zi], last = float(z_nodes.size() - 1);
  Rgb rgb;
  rgb[l] = z;
  rgb[(l + 1) % 3] = float(xi) / last * z;
  rgb[(l + 2) % 3] = float(yi) / last * z;
  return rgb;
}

RgbToSpectrumTable fit_rgb_to_spectrum_table(int resolution) {
  const int res = resolution;
  const std::vector<float> z = z_nodes(res);
  const int start =
      int(std::min_element(z.begin(), z.end(),
                           [](float p, float q) { return std::abs(p - kStartZ) < std::abs(q - kStartZ); }) -
          z.begin());
  std::vector<float> coefficients(size_t(3) * res * res * res * 3);

  // One chain per (l, yi, xi) along z; chains are independent, so threads cannot change the result.
  parallel_for(int64_t(3) * res * res, [&](int64_t chain) {
    const int l = int(chain / (res * res)), yi = int(chain / res % res), xi = int(chain % res);
    const auto fit_node = [&](int zi, const NormalizedCoefficients& start_coefficients) {
      const SigmoidFit fit = fit_sigmoid_polynomial(table_node_rgb(z, l, zi, yi, xi), start_coefficients);
      const RgbSigmoidPolynomial p = fit.polynomial();
      float* out = &coefficients[((((size_t(l) * res + zi) * res + yi) * res) + xi) * 3];
      out[0] = p.c0, out[1] = p.c1, out[2] = p.c2;
      return fit.normalized;
    };
    // J&H 2019's continuation: each node starts from its neighbour's solution, upward from the
    // start node and then downward.
    const NormalizedCoefficients at_start = fit_node(start, {0, 0, 0});
    NormalizedCoefficients a = at_start;
    for (int zi = start + 1; zi < res; ++zi) a = fit_node(zi, a);
    a = at_start;
    for (int zi = start - 1; zi >= 0; --zi) a = fit_node(zi, a);
  });
  return RgbToSpectrumTable(res, z, std::move(coefficients));
}

}  // namespace prism
