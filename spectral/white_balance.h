#pragma once
// White balance, as a camera's: the colours seen under an illuminant adapted so that its white
// becomes the scene-referred white, D65 (the film's XYZ, which OpenColorIO turns into the output
// space from there). A von Kries transform in the Bradford cone space (Lam 1985, as ICC v4 and
// CIE 15's CMCCAT97 use it): scale the cone responses ρ, γ, β by the target white's over the
// source's. (CAT02, CIECAM02's space, behaves alike for everyday colours but gives negative cone
// responses for some saturated ones, which the Bradford space keeps positive.)

#include <array>
#include <string>

#include "spectral/rgb.h"
#include "spectral/spectrum.h"

namespace prism {

struct WhiteBalance {
  std::string name;        // the illuminant, as the header records it
  Xyz white;               // its white (Y = 1)
  std::array<float, 9> m;  // XYZ → adapted XYZ, row major

  // The adaptation from `from` (the XYZ of an illuminant, any luminance) to D65's white.
  static WhiteBalance to_d65(std::string name, const Xyz& from);
  Xyz operator()(const Xyz& xyz) const;
  // In place, over n interleaved XYZ triples.
  void apply(float* xyz, size_t n) const;
};

}  // namespace prism
