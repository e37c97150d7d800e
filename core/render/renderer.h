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

#include "core/render/camera.h"
#include "core/render/error_estimate.h"
#include "core/render/film.h"
#include "core/render/integrators.h"
#include "core/render/path_integrator.h"

namespace prism {

// VCM's initial merging radius when none is given, as a fraction of the scene's bounding radius.
constexpr float kMergeRadius = 0.005f;

// A window of pixels [x0, x1) × [y0, y1) of the frame; empty: the whole frame.
struct PixelWindow {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool operator==(const PixelWindow&) const = default;
};

// Which part of a render a state holds: sample indices [sample_begin, sample_end) of the pixels
// in `crop` (merge.h joins parts into the whole).
struct RenderPart {
  int sample_begin = 0, sample_end = 0, total = 0;
  PixelWindow crop;
  bool operator==(const RenderPart&) const = default;
};

struct RenderOptions {
  IntegratorKind integrator = IntegratorKind::path;  // a row of the table in integrators.h
  int spp = 16;                          // samples per pixel; with a noise threshold, the most any pixel takes
  int sample_begin = 0, sample_end = 0;  // a part of the render: sample indices [begin, end) (end 0: spp)
  PixelWindow crop;                      // a part of the render: these pixels only (empty: all)
  uint64_t seed = 0;
  int threads = 0;                        // 0: all hardware threads
  int wavelengths = kDefaultWavelengths;  // per path: 1, 4 or 8
  SamplerKind sampler = SamplerKind::sobol;
  PathOptions path;
  float merge_radius = 0;  // VCM's initial merging radius (scene units); 0: kMergeRadius × the scene's radius
  std::optional<PathFeatures> features;          // default: what the scene needs (benchmarks force more)
  double noise_threshold = 0;                    // adaptive sampling (adaptive_sampling.h); 0: off
  OutputChannels noise_channels = kXyzChannels;  // the channels its error is measured in (the output space's)
  double time_limit = 0;                         // seconds; stop after the pass that reaches it; 0: none
  uint32_t aovs = 0;                             // Aov flags
  SpectralBins spectral_bins;                    // none: no spectral image
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
  explicit RenderState(Film f) : film(std::move(f)) {}
  Film film;
  int passes = 0;  // completed
  RenderPart part;
  std::string fingerprint;  // as loaded from a checkpoint or part file (checkpoint.h)
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
