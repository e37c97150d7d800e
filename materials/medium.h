#pragma once
// A homogeneous participating medium: light travelling through it is absorbed at rate σ_a(λ) and
// scattered at rate σ_s(λ) per scene unit (the extinction σ_t = σ_a + σ_s), and scattered light
// leaves by the Henyey–Greenstein phase function of asymmetry g (phase_function.h). Without σ_s
// it is the Beer–Lambert absorption of a tinted glass or liquid; with it, milk, marble or fog.
// How paths cross it is core/render/medium_sampling.h.

#include <algorithm>
#include <cmath>
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

// The single-scattering albedo σ_s/σ_t that gives a thick, isotropically scattering medium the
// multiple-scattering albedo ρ_ms (the colour it looks after many bounces): Kulla & Conty 2017,
// "Revisiting Physically Based Shading at Imageworks", slide 26's fit, which the glTF scattering
// drafts (KHR_materials_volume_scatter, KHR_materials_scatter) adopt:
//   ρ_ss = 1 − (4.09712 + 4.20863 ρ_ms − √(9.59217 + 41.6808 ρ_ms + 17.7126 ρ_ms²))².
inline float single_scattering_albedo(float multiscatter) {
  const double m = std::clamp(double(multiscatter), 0.0, 1.0);
  const double s = 4.09712 + 4.20863 * m - std::sqrt(9.59217 + 41.6808 * m + 17.7126 * m * m);
  return float(std::clamp(1 - s * s, 0.0, 1.0));
}

// The medium of extinction σ_t(λ) whose multiple-scattering albedo is ρ_ms(λ): σ_s = σ_t ρ_ss(ρ_ms),
// σ_a = σ_t − σ_s, wavelength by wavelength (at every nm), and phase asymmetry g.
Medium medium_of_albedo(const Spectrum& sigma_t, const Spectrum& multiscatter, float g);

}  // namespace prism
