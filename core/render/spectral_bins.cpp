#include "core/render/spectral_bins.h"

#include <algorithm>

#include "core/base/error.h"
#include "core/base/number_list.h"
#include "spectral/wavelengths.h"

namespace prism {

SpectralBins SpectralBins::uniform(int count) {
  if (count < 1 || count > 4096) fail("--spectral-bins: the bin count must be 1..4096 (got {})", count);
  SpectralBins b;
  for (int i = 0; i <= count; ++i) b.edges.push_back(kLambdaMin + (kLambdaMax - kLambdaMin) * float(i) / count);
  return b;
}

SpectralBins SpectralBins::parse(const std::string& text) {
  if (text.find(',') == std::string::npos) {
    try {
      size_t used = 0;
      const int count = std::stoi(text, &used);
      if (used == text.size()) return uniform(count);
    } catch (const std::exception&) {
    }
    fail("--spectral-bins '{}': expected a bin count or comma-separated edges in nm", text);
  }
  SpectralBins b;
  b.edges = parse_floats(text, "--spectral-bins");
  if (b.edges.size() < 2 || !std::is_sorted(b.edges.begin(), b.edges.end(), std::less_equal<float>()) ||
      b.edges.front() < kLambdaMin || b.edges.back() > kLambdaMax)
    fail("--spectral-bins '{}': edges must be at least two, strictly ascending, within {}–{} nm", text, kLambdaMin,
         kLambdaMax);
  return b;
}

int SpectralBins::find(float lambda) const {
  if (edges.empty() || lambda < edges.front() || lambda >= edges.back()) return -1;
  return int(std::upper_bound(edges.begin(), edges.end(), lambda) - edges.begin()) - 1;
}

std::string SpectralBins::channel_name(int i) const {
  std::string nm = fmt::format("{:g}", centre(i));
  std::replace(nm.begin(), nm.end(), '.', ',');
  return "S0." + nm + "nm";
}

std::string SpectralBins::to_string() const {
  std::string s;
  for (float e : edges) s += fmt::format("{}{:g}", s.empty() ? "" : ",", e);
  return s;
}

}  // namespace prism
