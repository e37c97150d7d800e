#pragma once
// A film as an OpenEXR image: the beauty in a colour space (converted from the film's XYZ), and
// the AOV layers and spectral bins the film gathered. `prism render` and `prism merge` both
// write their images through this, so a merged image equals the single render's. Both take
// --white-balance, which adapts the beauty (an output transform: parts merge whatever it is).

#include <optional>
#include <string>

#include "core/render/error_estimate.h"
#include "core/render/film.h"
#include "core/render/image_output.h"
#include "spectral/white_balance.h"

namespace prism {

// The image's channels as rows of the matrix that takes the film's XYZ to them: the white balance
// (if any), then the colour space's matrix. The error estimate and adaptive sampling measure these.
OutputChannels output_channels(const std::string& colorspace, const WhiteBalance* white_balance = nullptr);

// With a white balance, the beauty's XYZ is adapted first (white_balance.h); AOVs are not. The
// variance AOV holds the estimated variance of each pixel's Y and of its R, G and B as written.
ExrImage film_image(const Film& film, const std::string& colorspace, const WhiteBalance* white_balance = nullptr);

// --white-balance: a named illuminant, a temperature in kelvin (a blackbody), or "none" (nothing).
std::optional<WhiteBalance> white_balance_option(const std::string& text);

}  // namespace prism
