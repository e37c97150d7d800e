#pragma once
// A film as an OpenEXR image: the beauty in a colour space (converted from the film's XYZ), and
// the AOV layers and spectral bins the film gathered. `prism render` and `prism merge` both
// write their images through this, so a merged image equals the single render's. Both take
// --white-balance, which adapts the beauty (an output transform: parts merge whatever it is).

#include <optional>
#include <string>

#include "core/render/film.h"
#include "core/render/image_output.h"
#include "spectral/white_balance.h"

namespace prism {

// With a white balance, the beauty's XYZ is adapted first (white_balance.h); AOVs are not.
ExrImage film_image(const Film& film, const std::string& colorspace, const WhiteBalance* white_balance = nullptr);

// --white-balance: a named illuminant, a temperature in kelvin (a blackbody), or "none" (nothing).
std::optional<WhiteBalance> white_balance_option(const std::string& text);

}  // namespace prism
