#include "materials/medium.h"

#include <vector>

namespace prism {

Medium medium_of_albedo(const Spectrum& sigma_t, const Spectrum& multiscatter, float g) {
  std::vector<float> sigma_s, sigma_a;
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l) {
    const float t = evaluate(sigma_t, float(l));
    const float s = t * single_scattering_albedo(evaluate(multiscatter, float(l)));
    sigma_s.push_back(s);
    sigma_a.push_back(std::max(t - s, 0.f));
  }
  return Medium{.sigma_a = DenselySampledSpectrum(int(kLambdaMin), std::move(sigma_a)),
                .sigma_s = DenselySampledSpectrum(int(kLambdaMin), std::move(sigma_s)),
                .phase = {g}};
}

}  // namespace prism
