#pragma once
// A homogeneous participating medium: light travelling through it is absorbed at rate σ_a(λ) and
// scattered at rate σ_s(λ) per scene unit (the extinction σ_t = σ_a + σ_s), and scattered light
// leaves by the Henyey–Greenstein phase function of asymmetry g (phase_function.h). Without σ_s
// it is the Beer–Lambert absorption of a tinted glass or liquid; with it, milk, marble or fog.
// How paths cross it is core/render/medium_sampling.h.

#include <optional>

#include "materials/phase_function.h"
#include "spectral/spectrum.h"

namespace prism {

struct Medium {
  std::optional<Spectrum> sigma_a{};  // absorption per scene unit; none: 0
  std::optional<Spectrum> sigma_s{};  // scattering per scene unit; none: 0 (absorption alone)
  HenyeyGreenstein phase{};

  bool absorbs() const { return sigma_a.has_value(); }
  bool scatters() const { return sigma_s.has_value(); }
  bool empty() const { return !sigma_a && !sigma_s; }
};

}  // namespace prism
