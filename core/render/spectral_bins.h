#pragma once
// Wavelength bins of a spectral image: N equal bins over 360–830 nm, or explicit edges, named as
// in the OpenEXR spectral layout of Fichet, Pacanowski & Wilkie (2021, "An OpenEXR Layout for
// Spectral Images", JCGT 10(3)): `S0.<centre>nm` with a decimal comma.

#include <string>
#include <vector>

namespace prism {

struct SpectralBins {
  std::vector<float> edges;  // ascending; bin i is [edges[i], edges[i+1]); empty: no bins

  static SpectralBins uniform(int count);  // over the CIE range kLambdaMin..kLambdaMax
  // "N" for N equal bins, or "e0,e1,...,eN" edges in nm (ascending, inside the CIE range).
  static SpectralBins parse(const std::string& text);

  int count() const { return edges.empty() ? 0 : int(edges.size()) - 1; }
  float width(int i) const { return edges[i + 1] - edges[i]; }
  float centre(int i) const { return 0.5f * (edges[i] + edges[i + 1]); }
  // The bin that holds λ, or -1 outside the edges.
  int find(float lambda) const;
  std::string channel_name(int i) const;
  std::string to_string() const;  // the edges, for headers and checkpoint fingerprints
};

}  // namespace prism
