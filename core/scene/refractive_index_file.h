#pragma once
// Optical constants in the download formats of refractiveindex.info (Polyanskiy 2024, "Refractiveindex.info
// database of optical constants", Sci. Data 11, 94), wavelengths in µm:
//   CSV    a "wl,n" block of rows "λ,n", then optionally a "wl,k" block of rows "λ,k"
//   YAML   a database page: DATA entries "tabulated nk" (λ n k rows), "tabulated n", "tabulated k",
//          and the dispersion formulas 1–6 ("formula N" with "coefficients" and "wavelength_range")
// Formulas 1 and 2 (Sellmeier) stay formulas; the others are tabulated at every nm of the visible
// range their wavelength_range covers. Tabulated data hold their end values beyond their range.

#include <optional>
#include <string>
#include <string_view>

#include "materials/ior.h"
#include "spectral/spectrum.h"

namespace prism {

struct OpticalConstants {
  IorModel n;                          // the index n(λ), λ in nm
  std::optional<TabulatedSpectrum> k;  // the extinction coefficient k(λ), when the file has one
};

// Reads a file's text in either format (YAML when it has a DATA: key); `what` names it in errors.
OpticalConstants read_refractive_index(std::string_view text, const std::string& what);

// n(λ) as a spectrum, for a conductor's complex index (a formula tabulated at every nm).
Spectrum index_spectrum(const IorModel& n);

}  // namespace prism
