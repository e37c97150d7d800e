#pragma once
// How different two colours look: CIELAB (CIE 15) relative to a white, and the CIEDE2000 colour
// difference (CIE 142-2001; the formula as Sharma, Wu & Dalal 2005 give it, with their test data).

#include "spectral/rgb.h"

namespace prism {

struct Lab {
  double l, a, b;
};

// CIELAB of `xyz` relative to the white `white` (the XYZ of the perfect diffuser under the light).
Lab to_lab(const Xyz& xyz, const Xyz& white);

// ΔE00 with kL = kC = kH = 1.
double ciede2000(const Lab& a, const Lab& b);

}  // namespace prism
