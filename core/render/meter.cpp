#include "core/render/meter.h"

#include <algorithm>
#include <cmath>

#include "core/base/error.h"
#include "core/base/parallel.h"
#include "core/base/progress.h"
#include "core/render/integrators.h"
#include "core/render/renderer.h"
#include "spectral/cie.h"

namespace prism {

namespace {

constexpr int kLanes = 8;     // wavelengths per path, the renderer's default
constexpr int kChunk = 4096;  // samples per task: a point's samples are shared out among the threads in these

// A point's running sums: of the samples' illuminance and its square, and per spectral bin.
struct Sums {
  double e = 0, e2 = 0;
  std::vector<double> spectral;
  int samples = 0;
  void add(const Sums& o) {
    e += o.e, e2 += o.e2;
    for (size_t b = 0; b < spectral.size(); ++b) spectral[b] += o.spectral[b];
  }
  double mean() const { return samples > 0 ? e / samples : 0; }
  // The standard error of the mean, from the samples' own spread (i.i.d.: conservative for the
  // stratified default sampler).
  double std_error() const {
    if (samples < 2) return INFINITY;
    const double m = mean();
    return std::sqrt(std::max(0.0, (e2 / samples - m * m) / (samples - 1)));
  }
  bool converged(double rel_error) const { return std_error() <= rel_error * mean() || (samples >= 16 && e == 0); }
};

// The white Lambertian surface a meter reads, at a point: nothing of it is in the scene.
const Material& meter_material() {
  static const Material m{"meter", DiffuseMaterial{ConstantSpectrum{1.f}}};
  return m;
}

SurfaceInteraction meter_surface(const MeterPoint& point) {
  SurfaceInteraction si{};
  si.p = point.p;
  const float scale = std::max({std::abs(point.p.x), std::abs(point.p.y), std::abs(point.p.z), 1.f});
  si.p_error = Vec3f(scale, scale, scale) * 1e-6f;  // as a hit's rounding bound, for the spawned rays' offset
  si.n = si.ns = si.wo = point.n;
  si.t = 1;
  si.material = &meter_material();
  si.instance = si.prim = kNoInstance;
  return si;
}

// Takes samples [from, to) of one point, adding them to `sums`.
void sample_point(const World& world, const MeterPoint& point, size_t index, int from, int to,
                  const MeterOptions& options, RadianceFn<kLanes> radiance, Sums& sums) {
  const std::optional<SurfaceInteraction> first = meter_surface(point);
  const EstimateContext<kLanes> context{world, options.path};
  Sampler sampler(options.seed, SamplerKind::sobol);
  RayCounters counters;
  const Ray ray{point.p + point.n, -point.n};  // arriving along the normal (the surface is Lambertian)
  const int bins = options.bins.count();
  for (int s = from; s < to; ++s) {
    sampler.start_pixel_sample({int(index % 65536), int(index / 65536)}, s);
    const SampledWavelengths<kLanes> lambda = SampledWavelengths<kLanes>::sample(sampler.get_2d());
    const SampledSpectrum<kLanes> L = radiance(context, ray, lambda, sampler, counters, &first);
    const double e = kPi * double(to_xyz(L, lambda).y);
    if (!std::isfinite(e)) continue;  // counted as a sample of 0
    sums.e += e;
    sums.e2 += e * e;
    for (int i = 0; i < kLanes && bins; ++i) {
      const int bin = options.bins.find(lambda[i]);
      if (bin >= 0 && lambda.pdf()[i] > 0)
        sums.spectral[bin] += kPi * double(L[i]) / (double(lambda.pdf()[i]) * kLanes) / options.bins.width(bin);
    }
  }
}

}  // namespace

std::vector<MeterReading> measure(const World& world, const std::vector<MeterPoint>& points,
                                  const MeterOptions& options) {
  if (options.spp <= 0) fail("samples per point must be positive (got {})", options.spp);
  if (!(options.rel_error >= 0 && options.rel_error < 1))
    fail("the relative error must be in (0, 1) (got {})", options.rel_error);
  cie();  // the colour tables before the threads start
  const RadianceFn<kLanes> radiance =
      integrator(IntegratorKind::path).radiance.make<kLanes>(path_features(world.features()));
  std::vector<Sums> sums(points.size());
  for (Sums& s : sums) s.spectral.assign(options.bins.count(), 0.0);
  ThreadLimit limit(options.threads);
  // With a target error, passes over the points not there yet: 16 samples, then as many as the
  // point's error predicts (it falls as 1/√n), 10% over and at most 4 times those it has, up to
  // spp; otherwise one pass of spp.
  const bool targeted = options.rel_error > 0;
  std::vector<int> end(points.size(), targeted ? std::min(16, options.spp) : options.spp);
  for (int pass = 1;; ++pass) {
    // Each open point's next samples in chunks, summed per chunk and then in chunk order: the same
    // sums at any thread count, and a single point still keeps every thread busy.
    struct Task {
      size_t point;
      int from, to;
    };
    std::vector<Task> tasks;
    for (size_t i = 0; i < points.size(); ++i)
      for (int from = sums[i].samples; from < end[i]; from += kChunk)
        tasks.push_back({i, from, std::min(from + kChunk, end[i])});
    if (tasks.empty()) break;
    std::vector<Sums> partial(tasks.size(), Sums{0, 0, std::vector<double>(options.bins.count(), 0.0), 0});
    Progress progress(fmt::format("measure (pass {})", pass), int64_t(tasks.size()), options.progress);
    parallel_for(int64_t(tasks.size()), [&](int64_t k) {
      const Task& t = tasks[k];
      sample_point(world, points[t.point], t.point, t.from, t.to, options, radiance, partial[k]);
      progress.advance();
    });
    progress.finish();
    for (size_t k = 0; k < tasks.size(); ++k) sums[tasks[k].point].add(partial[k]);
    for (size_t i = 0; i < points.size(); ++i) {
      Sums& s = sums[i];
      s.samples = end[i];
      if (targeted && s.samples < options.spp && !s.converged(options.rel_error)) {
        const double predicted = s.samples * sqr(s.std_error() / (options.rel_error * s.mean())) * 1.1;
        end[i] = int(std::min<double>(options.spp, std::clamp(predicted, s.samples + 1.0, 4.0 * s.samples)));
      }
    }
  }
  std::vector<MeterReading> readings(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Sums& s = sums[i];
    readings[i] = {s.mean(), s.samples >= 2 ? s.std_error() : 0.0, s.samples, {}};
    for (double v : s.spectral) readings[i].spectral.push_back(s.samples > 0 ? v / s.samples : 0);
  }
  return readings;
}

}  // namespace prism
