#include "render/renderer.h"

#include <atomic>
#include <chrono>
#include <mutex>

#include "base/clock.h"
#include "base/error.h"
#include "base/parallel.h"
#include "base/progress.h"
#include "render/film.h"
#include "render/whitted_integrator.h"
#include "spectral/cie.h"

namespace prism {

namespace {

constexpr int kTileSize = 16;

struct TileStats {
  RayCounters rays;
  uint64_t samples = 0, invalid = 0;
};

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

template <int N>
void render_tile(const World& world, const Camera& camera, const RenderOptions& options, RadianceFn<N> radiance, int x0,
                 int y0, Film& film, TileStats& stats) {
  Sampler sampler(options.seed, options.sampler);
  const int x1 = std::min(x0 + kTileSize, camera.width()), y1 = std::min(y0 + kTileSize, camera.height());
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int s = 0; s < options.spp; ++s) {
        sampler.start_pixel_sample({x, y}, s);
        const Vec2f jitter = sampler.get_2d();
        SampledWavelengths<N> lambda = SampledWavelengths<N>::sample(sampler.get_2d());
        const Ray ray = camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y);
        const SampledSpectrum<N> L = radiance(world, ray, lambda, sampler, options.path, stats.rays);
        const Xyz xyz = to_xyz(L, lambda);
        ++stats.samples;
        if (std::isfinite(xyz.x) && std::isfinite(xyz.y) && std::isfinite(xyz.z)) {
          film.add(x, y, xyz);
        } else {
          ++stats.invalid;
        }
      }
}

template <int N>
RenderResult render_with(const World& world, const Camera& camera, const RenderOptions& options) {
  const RadianceFn<N> radiance = radiance_estimator<N>(world, options);
  Film film(camera.width(), camera.height());
  const int tiles_x = (camera.width() + kTileSize - 1) / kTileSize;
  const int tiles_y = (camera.height() + kTileSize - 1) / kTileSize;
  Progress progress("render", int64_t(tiles_x) * tiles_y, options.progress);
  RenderStats stats;
  std::mutex stats_mutex;
  const auto start = std::chrono::steady_clock::now();
  {
    ThreadLimit limit(options.threads);
    parallel_for(int64_t(tiles_x) * tiles_y, [&](int64_t tile) {
      TileStats ts;
      render_tile<N>(world, camera, options, radiance, int(tile % tiles_x) * kTileSize, int(tile / tiles_x) * kTileSize,
                     film, ts);
      {
        std::lock_guard lock(stats_mutex);
        stats.rays += ts.rays;
        stats.samples += ts.samples;
        stats.invalid_samples += ts.invalid;
      }
      progress.advance();
    });
  }
  progress.finish();
  stats.seconds = seconds_since(start);
  return {camera.width(), camera.height(), film.xyz_image(options.spp), stats};
}

}  // namespace

PathFeatures path_features(const SceneFeatures& f) { return {f.dielectric_volumes, f.dispersion}; }

std::string RenderStats::summary() const {
  return fmt::format(
      "{} samples in {:.2f} s ({:.3g} samples/s); rays: {} primary, {} secondary, {} shadow; {} invalid samples",
      samples, seconds, samples_per_second(), rays.primary, rays.secondary, rays.shadow, invalid_samples);
}

RenderResult render(const World& world, const Camera& camera, const RenderOptions& options) {
  if (options.spp <= 0) fail("samples per pixel must be positive (got {})", options.spp);
  cie();  // load the colour tables before the threads start, so errors surface here
  switch (options.wavelengths) {
    case 1:
      return render_with<1>(world, camera, options);
    case 4:
      return render_with<4>(world, camera, options);
    case 8:
      return render_with<8>(world, camera, options);
    default:
      fail("wavelengths per path must be 1, 4 or 8 (got {})", options.wavelengths);
  }
}

}  // namespace prism
