#pragma once
// Materials as the scene describes them (wavelength-independent descriptions), and the BSDF a
// material yields at one hit for one path's wavelengths.

#include <optional>
#include <string>
#include <variant>

#include "materials/bsdf.h"
#include "spectral/spectrum.h"

namespace prism {

struct DiffuseMaterial {
  Spectrum reflectance = ConstantSpectrum{0.8f};
};

using MaterialKind = std::variant<DiffuseMaterial>;

struct Material {
  std::string name;
  MaterialKind kind;
  std::optional<Spectrum> emission;  // emitted radiance; front face only unless double_sided
  bool double_sided = false;
};

template <int N>
Bsdf<N> make_bsdf(const Material& m, const SampledWavelengths<N>& lambda) {
  return std::visit([&](const auto& kind) -> Bsdf<N> { return DiffuseBsdf<N>(sample(kind.reflectance, lambda)); },
                    m.kind);
}

}  // namespace prism
