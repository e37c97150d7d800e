#pragma once
// Named spectra: the CIE's standard and typical illuminants, read from data/cie/ on first use
// (sources in data/README.md). Each is relative, as tabulated; whoever uses one scales it.
//   A                        CIE standard illuminant A, by its defining formula
//   D50, D55, D65, D75       daylight
//   E                        equal energy
//   F1 … F12                 typical fluorescent lamps (also by the CIE's names FL1 … FL12)
//   LED-B1 … LED-B5, LED-BH1, LED-RGB1, LED-V1, LED-V2   typical LED lamps (CIE 15:2018)

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/spectrum.h"

namespace prism {

// The illuminant of that name, or nothing.
std::optional<Spectrum> named_illuminant(std::string_view name);

// Every name named_illuminant knows (without the FL aliases), for messages and --help.
const std::vector<std::string>& named_illuminants();

// Illuminant A's relative spectral power at λ nm, by its definition (ISO/CIE 11664-2:2022):
// 100 (560/λ)^5 (exp(c₂/(2848 · 560)) − 1) / (exp(c₂/(2848 λ)) − 1), c₂ = 1.435·10⁷ nm K: Planck's
// law at 2856 K with the second radiation constant of today's value, 1.4388·10⁷ nm K.
double illuminant_a(double lambda_nm);

}  // namespace prism
