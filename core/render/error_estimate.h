#pragma once
// The error of a render, estimated from the render itself.
//
// The i.i.d. estimate of a pixel's variance, s²/n, overstates the error of Owen-scrambled samples
// (they are negatively correlated; docs/design.md, "The error estimate"), and a single scrambled
// net has no unbiased variance estimate of its own. Independently scrambled replicates of the same
// net have one: their spread (Owen 1997, "Monte Carlo variance of scrambled net quadrature";
// L'Ecuyer & Lemieux 2002, "Recent advances in randomized quasi-Monte Carlo methods", §6).
// Splitting every pixel's samples into two replicates would cost the image quality (two nets of
// n/2 points are worse than one of n; docs/performance.md, "The error estimate's calibration"), so
// only a sparse random set S of pixels, one in 16, takes a second, independently scrambled copy of
// its sample indices (sampler replicate 1); every other pixel keeps its whole net. On S, replicate
// means A and B measure the true variance, E[(A − B)²] = Var A + Var B; its ratio to the i.i.d.
// estimate of the same quantity (ratio estimation over a random sample, Cochran 1977, "Sampling
// Techniques" §6),
//   κ_c = Σ_S (A_c − B_c)² / Σ_S s²_c (1/n_A + 1/n_B),   c = X, Y, Z,
// calibrates every pixel's estimate: Var[mean of channel c] = κ_c · s²_c / n. κ is one number per
// channel for the whole image, so the per-pixel estimates are right on average over the image, not
// necessarily in every region (scrambled nets gain most at edges and on smooth gradients). Without
// replicated pixels (images smaller than 4×4 blocks) κ = 1, the i.i.d. estimate.

#include <array>

#include "core/base/rng.h"
#include "core/base/vec.h"
#include "core/render/film.h"

namespace prism {

// S: one pixel in every 4×4 block, at a place hashed from the block and the seed (stratified
// random sampling, Cochran 1977 §5: it covers the image evenly, so that a small feature that
// dominates the error is not missed by chance), independent of the image.
inline constexpr int kReplicatedBlock = 4;

inline bool replicated_pixel(Vec2i p, uint64_t seed) {
  const uint64_t h = hash_ints(p.x / kReplicatedBlock, p.y / kReplicatedBlock, seed, 0x5e1ecdu);
  return p.x % kReplicatedBlock == int(h % kReplicatedBlock) &&
         p.y % kReplicatedBlock == int(h / kReplicatedBlock % kReplicatedBlock);
}

// The channels of an output colour space as the rows of the matrix that takes XYZ to them (every
// output space Prism writes is linear in XYZ: ColorPipeline::matrix_from_xyz); XYZ's own by default.
using OutputChannels = std::array<std::array<double, 3>, 3>;
inline constexpr OutputChannels kXyzChannels{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

class ErrorEstimate {
 public:
  // With the output space's channels, whose variances come from the film's squares and products
  // (colour noise: the wavelengths' spread shows in them more than in luminance).
  explicit ErrorEstimate(const Film& film, const OutputChannels& output = kXyzChannels);

  // Estimated variance of pixel p's mean of channel c (0, 1, 2: X, Y, Z).
  double variance_of_mean(size_t p, int c) const { return calibration_[c] * film_.variance_of_mean(p, c); }
  // Estimated relative RMSE of the image's luminance: sqrt(mean over pixels of the variance of
  // each pixel's Y) / mean Y. (The true value replaces the variance by the squared error against
  // the converged image.)
  double rel_rmse() const;
  // Per-pixel relative RMSE sqrt(variance of the mean) / Y, at quantile q (0..1) over the
  // pixels with Y > 0.
  double pixel_rel_rmse_quantile(double q) const;
  // Estimated variance of pixel p's mean of output channel k, calibrated by that channel's own κ.
  double output_variance_of_mean(size_t p, int k) const {
    return output_calibration_[k] * film_.variance_of_mean(p, output_[k]);
  }
  // Estimated relative RMSE of the output image: sqrt(mean over pixels and channels of their
  // variances) / the mean over pixels and channels of their values (as `prism compare` measures).
  double output_rel_rmse() const;
  // κ for X, Y and Z, and how many replicated pixels measured it.
  const std::array<double, 3>& calibration() const { return calibration_; }
  size_t replicated_pixels() const { return replicated_pixels_; }

 private:
  const Film& film_;
  OutputChannels output_;
  std::array<double, 3> calibration_{1, 1, 1}, output_calibration_{1, 1, 1};
  size_t replicated_pixels_ = 0;
};

}  // namespace prism
