#pragma once
// A constant sky seen straight from the camera, without tracing what cannot change it.
//
// A camera ray that leaves the scene at once sees the constant environment, and the XYZ that the
// path's wavelengths estimate of it has a known mean (sampled_xyz_mean): that mean, found once, is
// such a sample's value, the estimate replaced by its expectation given the ray (Rao–Blackwell),
// without the wavelengths' colour noise or their spectral work. And a pixel whose every camera ray
// leaves the scene at once (nothing in the accel can meet the rays through it: Camera::frustum,
// Accel::may_meet) takes that value for each of its samples untraced. Both give the image the rays
// would have given, bit for bit. (Not in a scene filled with a medium: there no ray leaves unhindered.)

#include <cstdint>
#include <optional>
#include <vector>

#include "core/render/camera.h"
#include "core/render/world.h"
#include "spectral/rgb.h"

namespace prism {

// The XYZ of a camera sample that leaves the scene at once, for an estimator that takes the first
// hit (Integrator::first_hit) and no spectral bins (they need the lanes); none without a constant sky.
std::optional<Xyz> sky_xyz(const World& world, bool first_hit, bool spectral_bins);

// Per pixel, row by row: 1 where no camera ray through the pixel can meet the scene. Found tile by
// tile, then pixel by pixel in the tiles that may meet something.
std::vector<uint8_t> sky_pixels(const World& world, const Camera& camera);

}  // namespace prism
