#pragma once
// Builds the RGB -> spectrum table of Jakob & Hanika 2019 ("A Low-Dimensional Function Space for
// Efficient Spectral Upsampling", CGF 38(2)): for each linear Rec.709 albedo on a grid, the
// sigmoid-polynomial reflectance whose colour under D65 matches it in CIELAB. Used offline by
// apps/rgb2spec_opt; the renderer only loads the result (RgbToSpectrumTable::srgb()).

#include <array>
#include <span>

#include "spectral/rgb.h"
#include "spectral/rgb_to_spectrum.h"

namespace prism {

// Coefficients (a0, a1, a2) of s(a0 t² + a1 t + a2) over the normalised wavelength
// t = (λ − 360 nm) / (830 nm − 360 nm), in which the fit is well conditioned.
using NormalizedCoefficients = std::array<double, 3>;

struct SigmoidFit {
  NormalizedCoefficients normalized;
  double delta_e;  // CIE 1976 ΔE*ab between the target and the fitted reflectance's colour

  RgbSigmoidPolynomial polynomial() const;  // the same function with λ in nm
};

// Gauss–Newton from `start` on the CIELAB difference between `target` (linear Rec.709 in [0,1]³)
// and the colour of the reflectance under D65, by the same 1-nm sum spectrum_to_xyz uses.
SigmoidFit fit_sigmoid_polynomial(Rgb target, NormalizedCoefficients start);

// Linear Rec.709 colour of a reflectance under D65: spectrum_to_xyz of its 1-nm samples, then the
// XYZ -> Rec.709 matrix of the OCIO config (what rendering an albedo under D65 converges to).
Rgb reflectance_rgb(const RgbSigmoidPolynomial& reflectance);

// The albedo at node (l, zi, yi, xi) of a table with these z nodes (layout in rgb_to_spectrum.h).
Rgb table_node_rgb(std::span<const float> z_nodes, int l, int zi, int yi, int xi);

// The complete table (layout in rgb_to_spectrum.h), fitted in parallel; the result does not
// depend on the number of threads.
RgbToSpectrumTable fit_rgb_to_spectrum_table(int resolution);

}  // namespace prism
