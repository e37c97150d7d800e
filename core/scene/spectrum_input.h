#pragma once
// Spectra given in a glTF file's extras and on the command line (README, "Spectral inputs"): the
// pieces of the SPECTRUM syntax that do not depend on how it was written. A SPECTRUM is
//   "NAME"                                   a named illuminant (spectral/named_spectra.h)
//   {"blackbody": KELVIN}                     Planck's law (for emission)
//   {"wavelengths": [nm, …], "values": […]}   linear between the points (0 outside them, but for
//                                             an index or a coefficient, which holds its end values)
//   {"file": "name.csv"}                      the same from a file of two columns, nm and value
//                                             (a header line and '#' comments allowed), which
//                                             lies in the scene's folder (SceneFiles' policy)
// in a glTF file (gltf_extras.cpp reads those forms); on the command line a name,
// blackbody:KELVIN or a file's path. What a spectrum is for decides the values it may hold and
// the forms it may take.

#include <string>
#include <string_view>
#include <vector>

#include "spectral/spectrum.h"

namespace prism {

enum class SpectrumUse {
  emission,       // relative power: ≥ 0, some luminance; names and blackbodies allowed
  reflectance,    // a surface's reflectance: in [0, 1]
  transmittance,  // the transmittance reached at a distance: in [0, 1]
  index,          // a refractive index n: > 0
  extinction,     // an extinction coefficient k: ≥ 0
  coefficient,    // a medium's absorption or scattering per scene unit: ≥ 0
};

// A named illuminant, a blackbody of `kelvin`, or any spectrum, checked for `use` (an emission
// must have some luminance; names and blackbodies are emission only); fail naming `what`.
Spectrum named_spectrum(std::string_view name, SpectrumUse use, const std::string& what);
Spectrum blackbody_spectrum(double kelvin, SpectrumUse use, const std::string& what);
Spectrum checked_spectrum(Spectrum s, SpectrumUse use, const std::string& what);

// A spectrum from command-line text: a name, "blackbody:KELVIN", or a file's path (any folder).
Spectrum parse_spectrum_argument(const std::string& text, SpectrumUse use, const std::string& what);

// A table of two columns (nm, value) in CSV text; `what` names it in errors.
TabulatedSpectrum parse_spectrum_csv(std::string_view text, SpectrumUse use, const std::string& what);

// A tabulated spectrum from its points, checked for `use`: at least one point, wavelengths
// strictly increasing within 100–100000 nm, every value finite and allowed. Outside the points an
// emission, reflectance or transmittance is 0, an index or a coefficient holds its end values.
TabulatedSpectrum checked_table(std::vector<double> lambdas, std::vector<double> values, SpectrumUse use,
                                const std::string& what);

// The luminance Y of a spectrum, in Prism's units (a spectrum of Y = 1 is 1 cd/m² as radiance).
double luminance(const Spectrum& s);

// s scaled to luminance y: an emission whose shape a file gives and whose luminance the glTF
// factors give (the spectrum changes the colour, never the exposure). A table keeps its points;
// other kinds are sampled at every nm.
Spectrum spectrum_with_luminance(const Spectrum& s, double y);

}  // namespace prism
