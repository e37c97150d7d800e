#pragma once
// Renders a World through a Camera into CIE XYZ: 16×16 tiles over all allowed threads, each
// pixel's samples seeded by (pixel, sample index, seed), so the image is the same bit for bit
// whatever the thread count.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/path_integrator.h"

namespace prism {

enum class IntegratorKind { path, whitted };

struct RenderOptions {
  IntegratorKind integrator = IntegratorKind::path;
  int spp = 16;
  uint64_t seed = 0;
  int threads = 0;                        // 0: all hardware threads
  int wavelengths = kDefaultWavelengths;  // per path: 1, 4 or 8
  SamplerKind sampler = SamplerKind::sobol;
  PathOptions path;
  std::optional<PathFeatures> features;  // default: what the scene needs (benchmarks force more)
  bool progress = true;
};

struct RenderStats {
  RayCounters rays;
  uint64_t samples = 0;
  uint64_t invalid_samples = 0;  // NaN or Inf estimates, counted and dropped (added as 0)
  double seconds = 0;

  double samples_per_second() const { return seconds > 0 ? samples / seconds : 0; }
  std::string summary() const;
};

struct RenderResult {
  int width, height;
  std::vector<float> xyz;  // interleaved, width × height × 3, top row first
  RenderStats stats;
};

RenderResult render(const World& world, const Camera& camera, const RenderOptions& options);

// The path tracer's machinery a scene needs: media for closed dielectrics, dispersion checks
// for dispersive ones.
PathFeatures path_features(const SceneFeatures& f);

}  // namespace prism
