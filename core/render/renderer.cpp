#include "render/renderer.h"

#include <chrono>
#include <mutex>

#include "base/clock.h"
#include "base/error.h"
#include "base/parallel.h"
#include "base/progress.h"
#include "render/adaptive_sampling.h"
#include "render/error_estimate.h"
#include "render/pass_schedule.h"
#include "render/whitted_integrator.h"
#include "spectral/cie.h"

namespace prism {

namespace {

constexpr int kTileSize = 16;

template <int N>
using RadianceFn = SampledSpectrum<N> (*)(const World&, Ray, SampledWavelengths<N>&, Sampler&, const PathOptions&,
                                          RayCounters&);

// The radiance estimator for these options, compiled for the scene's features.
template <int N>
RadianceFn<N> radiance_estimator(const World& world, const RenderOptions& options) {
  if (options.integrator == IntegratorKind::whitted)
    return [](const World& w, Ray r, SampledWavelengths<N>& l, Sampler& s, const PathOptions& o, RayCounters& c) {
      return whitted_radiance<N>(w, r, l, s, o, c);
    };
  const PathFeatures f = options.features.value_or(path_features(world.features()));
  if (f.media) return f.dispersion ? &path_radiance<N, true, true> : &path_radiance<N, true, false>;
  return f.dispersion ? &path_radiance<N, false, true> : &path_radiance<N, false, false>;
}

// One camera sample: its wavelengths, the radiance they carry, and what the film keeps of it.
template <int N>
struct CameraSample {
  SampledWavelengths<N> lambda;
  SampledSpectrum<N> L;
  Xyz xyz;
  Ray ray;
};

// The body of the render: sample s of a pixel, from the sampler's stream for (pixel, s, seed)
// alone, through the camera and the radiance estimator to CIE XYZ.
template <int N>
CameraSample<N> camera_sample(const World& world, const Camera& camera, const RenderOptions& options,
                              RadianceFn<N> radiance, Sampler& sampler, Vec2i pixel, int s, int replicate,
                              RayCounters& rays) {
  sampler.start_pixel_sample(pixel, s, replicate);
  const Vec2f jitter = sampler.get_2d();
  CameraSample<N> c{SampledWavelengths<N>::sample(sampler.get_2d()), {}, {}, {}};
  c.ray = camera.generate_ray(float(pixel.x) + jitter.x, float(pixel.y) + jitter.y);
  c.L = radiance(world, c.ray, c.lambda, sampler, options.path, rays);
  c.xyz = to_xyz(c.L, c.lambda);
  return c;
}

// What the first surface along a camera ray shows: its albedo under D65 (as XYZ, converted like
// the image), shading normal and distance.
template <int N>
void first_hit(const World& world, const Ray& ray, const SampledWavelengths<N>& lambda, FilmSample& out) {
  const auto si = world.intersect(ray);
  if (!si) return;
  const Material& m = *si->material;
  SampledSpectrum<N> albedo;
  if (const auto* d = std::get_if<DiffuseMaterial>(&m.kind)) {
    albedo = sample(d->reflectance, lambda);
  } else {
    const RgbAlbedoSpectrum base(std::get<PbrMaterial>(m.kind).inputs(si->at).base_color);
    for (int i = 0; i < N; ++i) albedo[i] = base(lambda[i]);
  }
  for (int i = 0; i < N; ++i) albedo[i] *= cie().d65(lambda[i]);
  out.albedo = to_xyz(albedo, lambda);
  out.normal = si->ns;
  out.depth = si->t;
  out.hit = true;
}

struct PassStats {
  RayCounters rays;
  uint64_t samples = 0, invalid = 0;
};

// Takes every active pixel of the tile at (x0, y0) from the samples it has to `end`.
template <int N>
void render_tile(const World& world, const Camera& camera, const RenderOptions& options, RadianceFn<N> radiance, int x0,
                 int y0, int end, const std::vector<uint8_t>& active, Film& film, PassStats& stats) {
  Sampler sampler(options.seed, options.sampler);
  const bool first_hits = options.aovs & (kAovAlbedo | kAovNormal | kAovDepth);
  const int bins = film.bins().count();
  const int x1 = std::min(x0 + kTileSize, camera.width()), y1 = std::min(y0 + kTileSize, camera.height());
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t p = size_t(y) * camera.width() + x;
      if (!active.empty() && !active[p]) continue;
      // Each sample index once, or in the pixels the error estimate replicates twice (error_estimate.h).
      const int replicates = replicated_pixel({x, y}, options.seed) ? 2 : 1;
      for (int64_t k = int64_t(options.sample_begin + film.samples(p)) * replicates; k < int64_t(end) * replicates;
           ++k) {
        const int s = int(k / replicates), r = int(k % replicates);
        const CameraSample<N> c = camera_sample<N>(world, camera, options, radiance, sampler, {x, y}, s, r, stats.rays);
        FilmSample fs{c.xyz};
        if (first_hits) first_hit<N>(world, c.ray, c.lambda, fs);
        ++stats.samples;
        if (!film.add(p, fs, r)) ++stats.invalid;
        if (bins)
          for (int i = 0; i < N; ++i)
            if (c.lambda.pdf()[i] > 0) film.add_spectral(p, c.lambda[i], double(c.L[i]) / (c.lambda.pdf()[i] * N));
      }
    }
}

template <int N>
RenderResult render_with(const World& world, const Camera& camera, const RenderOptions& options,
                         const RenderControl& control, std::optional<RenderState> resume) {
  const RadianceFn<N> radiance = radiance_estimator<N>(world, options);
  RenderResult result{resume ? std::move(*resume)
                             : RenderState{Film(camera.width(), camera.height(), options.aovs, options.spectral_bins)}};
  RenderState& state = result.state;
  const int tiles_x = (camera.width() + kTileSize - 1) / kTileSize;
  const int tiles_y = (camera.height() + kTileSize - 1) / kTileSize;
  const int sample_end = options.sample_end > 0 ? options.sample_end : options.spp;
  const int part_spp = sample_end - options.sample_begin;
  const int passes = pass_count(part_spp);
  state.part = {options.sample_begin, sample_end, options.spp, options.crop};
  Progress progress("render", int64_t(passes - std::min(state.passes, passes)) * tiles_x * tiles_y, options.progress);
  std::mutex stats_mutex;
  std::vector<uint8_t> active;  // empty: all pixels
  if (!options.crop.empty()) {
    active.resize(state.film.pixel_count());
    for (int y = 0; y < camera.height(); ++y)
      for (int x = 0; x < camera.width(); ++x) active[size_t(y) * camera.width() + x] = options.crop.contains(x, y);
  }
  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = state.stats.seconds;
  ThreadLimit limit(options.threads);
  while (state.passes < passes) {
    const int end = options.sample_begin + pass_end(state.passes, part_spp);
    if (options.noise_threshold > 0) {
      find_unconverged(state.film, options.noise_threshold, active);
      if (std::find(active.begin(), active.end(), 1) == active.end()) {  // every pixel converged
        state.passes = passes;
        break;
      }
    }
    parallel_for(int64_t(tiles_x) * tiles_y, [&](int64_t tile) {
      PassStats ps;
      render_tile<N>(world, camera, options, radiance, int(tile % tiles_x) * kTileSize, int(tile / tiles_x) * kTileSize,
                     end, active, state.film, ps);
      {
        std::lock_guard lock(stats_mutex);
        state.stats.rays += ps.rays;
        state.stats.samples += ps.samples;
        state.stats.invalid_samples += ps.invalid;
      }
      progress.advance();
    });
    state.stats.seconds = seconds_before + seconds_since(start);
    if (control.after_pass) {
      const size_t active_pixels =
          active.empty() ? state.film.pixel_count() : size_t(std::count(active.begin(), active.end(), 1));
      control.after_pass({state.passes, end, active_pixels}, state);
    }
    // Stop requests take effect between passes, so that every pixel has whole passes.
    if (++state.passes == passes) break;
    if (control.stop && control.stop->load()) {
      result.interrupted = true;
      break;
    }
    // The limit counts the sessions before a resume too (their seconds are in the checkpoint).
    if (options.time_limit > 0 && state.stats.seconds >= options.time_limit) {
      result.timed_out = true;
      break;
    }
  }
  progress.finish();
  state.stats.seconds = seconds_before + seconds_since(start);
  return result;
}

}  // namespace

PathFeatures path_features(const SceneFeatures& f) { return {f.dielectric_volumes, f.dispersion}; }

std::string RenderStats::summary() const {
  return fmt::format(
      "{} samples in {:.2f} s ({:.3g} samples/s); rays: {} primary, {} secondary, {} shadow; {} invalid samples",
      samples, seconds, samples_per_second(), rays.primary, rays.secondary, rays.shadow, invalid_samples);
}

RenderResult render(const World& world, const Camera& camera, const RenderOptions& options,
                    const RenderControl& control, std::optional<RenderState> resume) {
  if (options.spp <= 0) fail("samples per pixel must be positive (got {})", options.spp);
  if (!(options.noise_threshold >= 0))
    fail("the noise threshold must be non-negative (got {})", options.noise_threshold);
  const int sample_end = options.sample_end > 0 ? options.sample_end : options.spp;
  if (options.sample_begin < 0 || options.sample_begin >= sample_end || sample_end > options.spp)
    fail("the sample range {}:{} is empty or not inside 0:{} (--spp)", options.sample_begin, sample_end, options.spp);
  const PixelWindow& c = options.crop;
  if (!c.empty() && (c.x0 < 0 || c.y0 < 0 || c.x1 > camera.width() || c.y1 > camera.height()))
    fail("the crop window {},{},{},{} is not inside the {}x{} frame", c.x0, c.y0, c.x1, c.y1, camera.width(),
         camera.height());
  if (options.noise_threshold > 0 && (options.sample_begin > 0 || !c.empty()))
    fail("adaptive sampling (a noise threshold) cannot be split into sample ranges or crop windows");
  if (resume && (resume->film.width() != camera.width() || resume->film.height() != camera.height()))
    fail("the state to resume is {}x{}, the camera {}x{}", resume->film.width(), resume->film.height(), camera.width(),
         camera.height());
  cie();  // load the colour tables before the threads start, so errors surface here
  switch (options.wavelengths) {
    case 1:
      return render_with<1>(world, camera, options, control, std::move(resume));
    case 4:
      return render_with<4>(world, camera, options, control, std::move(resume));
    case 8:
      return render_with<8>(world, camera, options, control, std::move(resume));
    default:
      fail("wavelengths per path must be 1, 4 or 8 (got {})", options.wavelengths);
  }
}

}  // namespace prism
