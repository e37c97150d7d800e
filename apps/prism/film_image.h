#pragma once
// A film as an OpenEXR image: the beauty in a colour space (converted from the film's XYZ), and
// the AOV layers and spectral bins the film gathered. `prism render` and `prism merge` both
// write their images through this, so a merged image equals the single render's.

#include <string>

#include "core/render/film.h"
#include "core/render/image_output.h"

namespace prism {

ExrImage film_image(const Film& film, const std::string& colorspace);

}  // namespace prism
