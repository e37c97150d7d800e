#pragma once
// Illuminance meters: another product of the same transport as the film, not a second renderer.
// At a point p with normal n the illuminance is E = ∫ L(p, ω) cos θ dω over the hemisphere about
// n. A white Lambertian surface at p (albedo 1) reflects L_o = E / π towards every direction, and
// that radiance is what the path tracer estimates for a camera ray meeting such a surface at p,
// with every light path it handles (light sampled and found, inter-reflected, through glass). So a
// meter takes the path tracer's estimate from a virtual surface at p, and E = π L_o. The surface is
// not in the scene: it casts no shadow and nothing else sees it, as a lux meter's cell barely does.
//
// In Prism's photometric units (README, "Units") luminance Y = 1 is 1 cd/m², so Y(π L_o) is the
// illuminance in lux. Each point's samples are seeded by (point, sample index, seed) alone and
// summed in order, so readings are the same at any thread count.

#include <cstdint>
#include <vector>

#include "core/base/vec.h"
#include "core/render/path_integrator.h"
#include "core/render/spectral_bins.h"
#include "core/render/world.h"

namespace prism {

struct MeterPoint {
  Vec3f p, n;  // position and unit normal, world space
};

struct MeterOptions {
  int spp = 256;         // samples per point; with rel_error > 0, the most any point takes
  double rel_error = 0;  // > 0: sample until every point's standard error is below rel_error × its reading
  uint64_t seed = 0;
  int threads = 0;  // 0: all hardware threads
  PathOptions path;
  SpectralBins bins;  // none: no spectral irradiance
  bool progress = true;
};

struct MeterReading {
  double illuminance = 0;  // lux
  double std_error = 0;    // lux: the standard error of the mean of the point's samples
  int samples = 0;
  std::vector<double> spectral;  // per bin: mean spectral irradiance over the bin (per nm), when asked
};

std::vector<MeterReading> measure(const World& world, const std::vector<MeterPoint>& points,
                                  const MeterOptions& options);

}  // namespace prism
