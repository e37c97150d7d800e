#pragma once
// Renders a World through a Camera into a Film, in progressive passes over the whole frame (see
// pass_schedule.h). Each pixel's samples are seeded by (pixel, sample index, seed) and added in
// sample order by one thread, so the image is the same bit for bit whatever the thread count,
// the pass at which the render stopped or resumed, and (for adaptive sampling) it equals in
// every pixel the straight render with that pixel's sample count.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/film.h"
#include "render/path_integrator.h"

namespace prism {

enum class IntegratorKind { path, whitted };

struct RenderOptions {
  IntegratorKind integrator = IntegratorKind::path;
  int spp = 16;  // samples per pixel; with a noise threshold, the most any pixel takes
  uint64_t seed = 0;
  int threads = 0;                        // 0: all hardware threads
  int wavelengths = kDefaultWavelengths;  // per path: 1, 4 or 8
  SamplerKind sampler = SamplerKind::sobol;
  PathOptions path;
  std::optional<PathFeatures> features;  // default: what the scene needs (benchmarks force more)
  double noise_threshold = 0;            // adaptive sampling (adaptive_sampling.h); 0: off
  double time_limit = 0;                 // seconds; stop after the pass that reaches it; 0: none
  uint32_t aovs = 0;                     // Aov flags
  SpectralBins spectral_bins;            // none: no spectral image
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

// Everything a render has done so far: enough to continue it (checkpoint.h).
struct RenderState {
  Film film;
  int passes = 0;  // completed
  RenderStats stats{};
};

// After each pass: its number, the samples per pixel it ended at, and the state.
struct PassReport {
  int pass, samples_end;
  size_t active_pixels;  // pixels that took samples in this pass
};

struct RenderControl {
  const std::atomic<bool>* stop = nullptr;  // when set: finish the current pass and return
  std::function<void(const PassReport&, const RenderState&)> after_pass;
};

struct RenderResult {
  RenderState state;
  bool interrupted = false;  // stopped by RenderControl::stop before the last pass
  bool timed_out = false;    // stopped by the time limit before the last pass

  int width() const { return state.film.width(); }
  int height() const { return state.film.height(); }
  const RenderStats& stats() const { return state.stats; }
};

// Renders from scratch, or continues `resume` (a state of the same scene and options).
RenderResult render(const World& world, const Camera& camera, const RenderOptions& options,
                    const RenderControl& control = {}, std::optional<RenderState> resume = {});

// The path tracer's machinery a scene needs: media for closed dielectrics, dispersion checks
// for dispersive ones.
PathFeatures path_features(const SceneFeatures& f);

}  // namespace prism
