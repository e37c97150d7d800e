#pragma once
// How far an image is from another of the same size (linear RGB, all pixels and channels), for
// the commands that measure renders: converge (against a reference) and compare.

#include <vector>

namespace prism {

struct ImageErrors {
  double rmse;          // root-mean-square difference
  double relative_mse;  // mean of d² / (reference² + 0.01), the usual guard against dark pixels
  double mean_error;    // mean(image) − mean(reference): a bias shows as a plateau in it
  double reference_mean;
};

ImageErrors image_errors(const std::vector<float>& image, const std::vector<float>& reference);

// The image as a display shows it: linear values clipped to [0, 1] and sRGB-encoded (IEC
// 61966-2-1), so that an error of it is the noise a viewer sees, not that of clipped highlights.
std::vector<float> display_encoded(const std::vector<float>& linear);

}  // namespace prism
