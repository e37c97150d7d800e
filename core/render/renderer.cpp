#include "core/render/renderer.h"

#include <array>
#include <chrono>
#include <mutex>
#include <new>

#include "core/base/clock.h"
#include "core/base/error.h"
#include "core/base/parallel.h"
#include "core/base/progress.h"
#include "core/render/adaptive_sampling.h"
#include "core/render/camera_sample.h"
#include "core/render/error_estimate.h"
#include "core/render/pass_schedule.h"
#include "core/render/sky.h"
#include "core/render/tile_grid.h"
#include "spectral/cie.h"

namespace prism {

namespace {

// A pixel's camera rays are made up to this many at once before any is traced: each waits on a
// chain of divisions and a square root, which overlap across a batch, where one ray at a time
// held up the start of every sample's traversal.
constexpr int kRayBatch = 16;

// The light paths of a pass, for the integrators that trace them: their scene of lights, the thread's
// splat buffer, and for VCM the iteration's photons and wavelengths.
template <int N>
struct PassLightPaths {
  const BdptScene* scene = nullptr;
  SplatBuffer* splats = nullptr;
  const VcmIteration<N>* vcm = nullptr;
  const SampledWavelengths<N>* lambda = nullptr;
};

// The wavelengths every path of VCM iteration s carries (vcm.h), stratified over iterations.
template <int N>
SampledWavelengths<N> iteration_wavelengths(const RenderOptions& options, int s) {
  Sampler sampler(options.seed, options.sampler);
  sampler.start_pixel_sample({-1, -1}, s);
  return SampledWavelengths<N>::sample(sampler.get_2d());
}

// VCM iteration s: the photons of every pixel's light path for sample s, in tile order.
template <int N>
VcmIteration<N> trace_iteration(const BdptScene& scene, const RenderOptions& options, int s,
                                const SampledWavelengths<N>& lambda, const TileGrid& grid, RayCounters& rays) {
  const float r0 = options.merge_radius > 0 ? options.merge_radius : kMergeRadius * scene.disk.radius;
  const float radius = VcmIteration<N>::radius(r0, s + 1);
  const MisFactors factors = MisFactors::vcm(radius, scene.light_paths);
  const int64_t tiles = grid.count();
  std::vector<std::vector<Vec3f>> positions(tiles);
  std::vector<std::vector<Photon<N>>> photons(tiles);
  std::vector<RayCounters> counters(tiles);
  parallel_for(tiles, [&](int64_t t) {
    Sampler sampler(options.seed, options.sampler);
    const TileGrid::Tile tile = grid[t];
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        sampler.start_pixel_sample({x, y}, s);
        trace_photons<N>(scene, lambda, sampler, options.path, factors, counters[t], positions[t], photons[t]);
      }
  });
  std::vector<Vec3f> all_positions;
  std::vector<Photon<N>> all_photons;
  for (int64_t t = 0; t < tiles; ++t) {
    all_positions.insert(all_positions.end(), positions[t].begin(), positions[t].end());
    all_photons.insert(all_photons.end(), photons[t].begin(), photons[t].end());
    rays += counters[t];
  }
  return VcmIteration<N>(std::move(all_positions), std::move(all_photons), radius, scene.light_paths);
}

struct PassStats {
  RayCounters rays;
  uint64_t samples = 0, invalid = 0;
};

// Takes every active pixel of the tile from the samples it has to `end`.
template <int N>
void render_tile(const World& world, const Camera& camera, const RenderOptions& options, RadianceFn<N> radiance,
                 const std::optional<Xyz>& sky, const std::vector<uint8_t>& sky_only, const PassLightPaths<N>& light,
                 TileGrid::Tile tile, int end, const std::vector<uint8_t>& active, Film& film, PassStats& stats) {
  uint64_t invalid_splats = 0;
  const EstimateContext<N> context{world, options.path, light.scene, light.splats, light.vcm, &invalid_splats};
  Sampler sampler(options.seed, options.sampler);
  const bool first_hits = options.aovs & (kAovAlbedo | kAovNormal | kAovDepth);
  const int bins = film.bins().count();
  // A batch's camera rays and each sample's sampler past its jitter (made once per tile: each
  // batch writes the entries it reads).
  std::array<Ray, kRayBatch> rays;
  std::array<Sampler, kRayBatch> samplers;
  CameraSample<N> c;  // each traced sample's, written by camera_sample
  const Film::FixedXyz sky_fixed = Film::to_fixed_xyz(sky.value_or(Xyz{0, 0, 0}));
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      const size_t p = size_t(y) * camera.width() + x;
      if (!active.empty() && !active[p]) continue;
      // Each sample index once, or in the pixels the error estimate replicates twice (error_estimate.h;
      // not in bidirectional renders, whose light paths must be one per sample index).
      const int replicates = !light.scene && replicated_pixel({x, y}, options.seed) ? 2 : 1;
      const int64_t first = int64_t(options.sample_begin + film.samples(p)) * replicates;
      // The samples that saw the sky (camera_sample), per replicate: added together at the end.
      uint32_t sky_samples[2] = {0, 0};
      const int64_t last = int64_t(end) * replicates;
      if (!sky_only.empty() && sky_only[p]) {  // no camera ray of the pixel can meet the scene (sky_pixels)
        // Sample k belongs to replicate k % replicates, and first and last are multiples of replicates.
        for (int r = 0; r < replicates; ++r) sky_samples[r] = uint32_t((last - first) / replicates);
        stats.samples += uint64_t(last - first);
      } else {
        for (int64_t k0 = first; k0 < last; k0 += kRayBatch) {
          const int64_t k1 = std::min(k0 + kRayBatch, last);
          for (int64_t k = k0; k < k1; ++k) {
            if (replicates > 1 || k == first) sampler.start_pixel({x, y}, int(k % replicates));
            // Made in its slot: a prvalue initialises the object a placement new names, where an
            // assignment made it in a temporary and copied it, reading back with one wide load
            // what generate_ray had just stored field by field (x86 cannot forward that: a stall).
            ::new (&rays[k - k0]) Ray(camera_ray(camera, sampler, {x, y}, int(k / replicates)));
            samplers[k - k0] = sampler;
          }
          for (int64_t k = k0; k < k1; ++k) {
            const int r = int(k % replicates);
            ++stats.samples;
            if (!camera_sample<N>(context, radiance, light.lambda, sky, samplers[k - k0], rays[k - k0], stats.rays,
                                  c)) {
              ++sky_samples[r];
              continue;
            }
            FilmSample fs{c.xyz};
            if (first_hits) first_hit<N>(world, rays[k - k0], c.lambda, fs);
            if (!film.add(p, fs, r)) ++stats.invalid;
            if (bins)
              for (int i = 0; i < N; ++i)
                if (c.lambda.pdf()[i] > 0) film.add_spectral(p, c.lambda[i], double(c.L[i]) / (c.lambda.pdf()[i] * N));
          }
        }
      }
      for (int r = 0; r < 2; ++r)
        if (sky_samples[r] > 0 && !film.add_repeated(p, sky_fixed, sky_samples[r], r)) stats.invalid += sky_samples[r];
    }
  stats.invalid += invalid_splats;
}

template <int N>
RenderResult render_with(const World& world, const Camera& camera, const RenderOptions& options,
                         const RenderControl& control, std::optional<RenderState> resume) {
  const Integrator& integ = integrator(options.integrator);
  const PathFeatures features = options.features.value_or(path_features(world.features()));
  const RadianceFn<N> radiance = integ.radiance.make<N>(features);
  const std::optional<Xyz> sky = sky_xyz(world, integ.first_hit, options.spectral_bins.count() > 0);
  const std::vector<uint8_t> sky_only = sky ? sky_pixels(world, camera) : std::vector<uint8_t>{};
  std::optional<BdptScene> bdpt_scene;
  std::optional<ThreadSplats> splats;
  if (integ.light_paths) {
    bdpt_scene.emplace(world, camera, features.media, integ.light_tracing_only);
    splats.emplace(camera.width(), camera.height());
  }
  const uint32_t film_flags = options.aovs | (integ.light_paths ? kFilmSplats : 0u);
  RenderResult result{resume ? std::move(*resume)
                             : RenderState{Film(camera.width(), camera.height(), film_flags, options.spectral_bins)}};
  RenderState& state = result.state;
  const TileGrid grid(camera);
  const int sample_end = options.sample_end > 0 ? options.sample_end : options.spp;
  const int part_spp = sample_end - options.sample_begin;
  const int passes = pass_count(part_spp);
  state.part = {options.sample_begin, sample_end, options.spp, options.crop};
  Progress progress("render", int64_t(passes - std::min(state.passes, passes)) * grid.count(), options.progress);
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
      find_unconverged(state.film, options.noise_threshold, active, options.noise_channels);
      if (std::find(active.begin(), active.end(), 1) == active.end()) {  // every pixel converged
        state.passes = passes;
        break;
      }
    }
    // Every active pixel to `to` samples; the progress bar advances on the pass's last round.
    const auto render_tiles = [&](int to, const VcmIteration<N>* vcm, const SampledWavelengths<N>* lambda, bool last) {
      parallel_for(grid.count(), [&](int64_t tile) {
        PassStats ps;
        const PassLightPaths<N> light{bdpt_scene ? &*bdpt_scene : nullptr, splats ? &splats->local() : nullptr, vcm,
                                      lambda};
        render_tile<N>(world, camera, options, radiance, sky, sky_only, light, grid[tile], to, active, state.film, ps);
        {
          std::lock_guard lock(stats_mutex);
          state.stats.rays += ps.rays;
          state.stats.samples += ps.samples;
          state.stats.invalid_samples += ps.invalid;
        }
        if (last) progress.advance();
      });
    };
    if (integ.photon_iterations) {
      // One VCM iteration per sample index: all light paths and their photons first.
      for (int s = options.sample_begin + int(state.film.samples(0)); s < end; ++s) {
        const SampledWavelengths<N> lambda = iteration_wavelengths<N>(options, s);
        const VcmIteration<N> iteration = trace_iteration<N>(*bdpt_scene, options, s, lambda, grid, state.stats.rays);
        render_tiles(s + 1, &iteration, &lambda, s + 1 == end);
      }
    } else {
      render_tiles(end, nullptr, nullptr, true);
    }
    if (splats)
      for (SplatBuffer& b : *splats) {
        state.film.add_splats(b);
        b.clear();
      }
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
    // The limit counts the runs before a resume too (their seconds are in the checkpoint).
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

PathFeatures path_features(const SceneFeatures& f) { return {f.dielectric_volumes || f.scene_medium, f.dispersion}; }

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
  if (!integrator(options.integrator).per_pixel() &&
      (options.noise_threshold > 0 || !c.empty() || options.spectral_bins.count() > 0))
    fail(
        "the {} integrator splats light paths over the whole frame: it takes no noise threshold, crop window or "
        "spectral bins",
        integrator(options.integrator).name);
  if (resume && (resume->film.width() != camera.width() || resume->film.height() != camera.height()))
    fail("the state to resume is {}x{}, the camera {}x{}", resume->film.width(), resume->film.height(), camera.width(),
         camera.height());
  if (world.features().scattering && !integrator(options.integrator).scattering)
    fail("the {} integrator does not render scattering media yet; the path integrator does (--integrator path)",
         integrator(options.integrator).name);
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
