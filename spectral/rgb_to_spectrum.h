#pragma once
// RGB -> smooth reflectance spectrum by the sigmoid-polynomial model of Jakob & Hanika 2019,
// "A Low-Dimensional Function Space for Efficient Spectral Upsampling" (Computer Graphics
// Forum 38(2)): s(c0 λ² + c1 λ + c2) with s(x) = 1/2 + x / (2 sqrt(1 + x²)), which is smooth and
// lies in (0, 1) for every coefficient triple. The coefficients come from a precomputed table
// that the build generates with apps/rgb2spec_opt (build/data/spectra/srgb_sigmoid.coeff).

#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include "spectral/rgb.h"
#include "spectral/wavelengths.h"

namespace prism {

struct RgbSigmoidPolynomial {
  float c0 = 0, c1 = 0, c2 = 0;  // polynomial in λ [nm]

  // s(x) of x clamped to ±10¹⁸, where it is exactly 1 or 0 in float (sqrt(x²) = |x| there): so
  // ±∞ (a grey of 1 or 0) gives those limits without a branch, and x² never overflows.
  static float clamp(float x) { return std::min(std::max(x, -1e18f), 1e18f); }
  static float sigmoid_clamped(float x) { return 0.5f + x / (2.f * std::sqrt(1.f + x * x)); }
  static float sigmoid(float x) { return sigmoid_clamped(clamp(x)); }
  float operator()(float lambda) const { return sigmoid((c0 * lambda + c1) * lambda + c2); }
  // At a path's wavelengths, all lanes at once (SIMD), with the same roundings as one at a time.
  // (Clamped in a loop of its own: fused, the compiler branches on the clamp, lane by lane.)
  template <int N>
  SampledSpectrum<N> operator()(const SampledWavelengths<N>& lambda) const {
    std::array<float, N> x;
    for (int i = 0; i < N; ++i) x[i] = clamp((c0 * lambda[i] + c1) * lambda[i] + c2);
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) r[i] = sigmoid_clamped(x[i]);
    return r;
  }
};

// The table, indexed by the largest RGB component l, a nonlinear grid over that component's
// value (z) and a uniform grid over the other two divided by it (x = rgb[(l+1)%3]/z,
// y = rgb[(l+2)%3]/z). File format (little-endian): 8-byte magic "PRISMRSP", uint32 resolution
// R, float32 z_nodes[R], float32 coefficients[3][R][R][R][3] indexed [l][zi][yi][xi][c].
class RgbToSpectrumTable {
 public:
  static constexpr char kMagic[8] = {'P', 'R', 'I', 'S', 'M', 'R', 'S', 'P'};

  RgbToSpectrumTable(int resolution, std::vector<float> z_nodes, std::vector<float> coefficients);
  static RgbToSpectrumTable load(const std::filesystem::path& file);
  void save(const std::filesystem::path& file) const;

  // The table for linear Rec.709 / sRGB primaries, loaded from data/ on first use.
  static const RgbToSpectrumTable& srgb();

  // rgb must lie in [0, 1]^3.
  RgbSigmoidPolynomial operator()(Rgb rgb) const;

  int resolution() const { return res_; }
  const std::vector<float>& z_nodes() const { return z_nodes_; }
  std::array<float, 3> coefficients(int l, int zi, int yi, int xi) const;

 private:
  int res_;
  std::vector<float> z_nodes_;
  std::vector<float> coeffs_;
};

}  // namespace prism
