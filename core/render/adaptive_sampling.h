#pragma once
// Adaptive sampling: after each pass, pixels whose estimated error is below the noise threshold T
// stop taking samples.
//
// A pixel's error is the largest over the image's channels (the output space's R, G and B, which
// RenderOptions::noise_channels gives as rows over XYZ, so that colour noise counts, not only
// luminance noise) of the standard error of the pixel's mean, sqrt(Var[X̂]), divided by
// sqrt(X · X̄), X the pixel's and X̄ the image's mean (for a channel that is not positive there, a
// saturated colour's, the mean magnitude of the three channels stands in for X and X̄). This is
// Cycles' measure (error over the square root of the pixel's value: the noise a viewer sees
// through a display curve, so dark pixels are not chased to a relative precision nobody sees)
// made independent of exposure by X̄: scaling the image leaves it unchanged. Var[X̂] is the
// i.i.d. estimate s²/n, not the calibrated one of error_estimate.h: s²/n is right for pixels
// whose noise is like plain Monte Carlo's (caustics, fireflies) and too high where the scrambled
// nets do better (edges, smooth shading), while the image-wide calibration is an average that
// would let a caustic in an otherwise smooth image stop early. So a pixel below T is converged;
// a pixel above it may be already. A pixel stops only when the largest error in its 3×3
// neighbourhood is below T (as Cycles filters its convergence mask), which makes stopping on a
// lucky low variance estimate rarer.

#include <array>
#include <cstdint>
#include <vector>

#include "core/render/error_estimate.h"
#include "core/render/film.h"

namespace prism {

// Samples every pixel takes before its error is trusted: at least 16 (the estimated standard
// error is then itself within ~18%, 1/sqrt(2(n-1)), for well-behaved pixels), growing as 4/sqrt(T)
// so that stricter thresholds also see rarer events: by the rule of three, an effect a sample
// shows with probability 3/n is seen at least once in n samples with 95% confidence.
int adaptive_min_samples(double threshold);

// The error of pixel p as defined above, given the image's mean X, Y, Z, over the given channels.
double adaptive_error(const Film& film, size_t p, const std::array<double, 3>& image_mean,
                      const OutputChannels& channels = kXyzChannels);

// active[p] = 1 where pixel p still needs samples under threshold T.
void find_unconverged(const Film& film, double threshold, std::vector<uint8_t>& active,
                      const OutputChannels& channels = kXyzChannels);

}  // namespace prism
