// `prism bench light-tree`: a light tree over N emissive triangles (default 10⁶), small and facing
// every way in a cube, built from their bounds as the world builds it. Prints the build's seconds
// and memory (the tree's own, and the process's peak resident set), and what a choice costs: the
// nanoseconds of one sample and of one pmf at random points, beside power sampling's.

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "apps/prism/commands.h"
#include "apps/prism/resident_memory.h"
#include "core/base/clock.h"
#include "core/base/log.h"
#include "core/base/rng.h"
#include "core/render/light_tree.h"

namespace prism {

namespace {

struct LightTreeArgs {
  size_t lights = 1'000'000;
  int queries = 1'000'000;
};

Vec3f random_unit(Rng& rng) {
  const float z = 1 - 2 * rng.uniform(), phi = 2 * kPi * rng.uniform(), r = safe_sqrt(1 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

void run(const LightTreeArgs& args) {
  // Triangles of about 1/100 of the cube's side, anywhere in a cube of side 100, facing anywhere.
  Rng rng(1, 0);
  std::vector<std::optional<LightBounds>> bounds(args.lights);
  std::vector<float> power(args.lights);
  for (size_t i = 0; i < args.lights; ++i) {
    const Vec3f c(100 * rng.uniform(), 100 * rng.uniform(), 100 * rng.uniform());
    Bounds3f box;
    for (int k = 0; k < 3; ++k) box.extend(c + random_unit(rng) * 0.5f);
    power[i] = 0.1f + rng.uniform();
    bounds[i] = LightBounds{box, random_unit(rng), power[i], 1.f, 0.f, false};
  }
  const auto [before_mb, before_peak_mb] = resident_mb();
  const auto t0 = std::chrono::steady_clock::now();
  const LightTree tree(bounds, power);
  const double build_s = seconds_since(t0);
  const auto [after_mb, peak_mb] = resident_mb();

  // The cost of a choice, at random points with random normals (one-sided receivers).
  std::vector<ShadingPoint> points(size_t(args.queries));
  for (ShadingPoint& p : points)
    p = {Vec3f(100 * rng.uniform(), 100 * rng.uniform(), 100 * rng.uniform()), random_unit(rng), true};
  double checksum = 0;
  auto t1 = std::chrono::steady_clock::now();
  std::vector<uint32_t> chosen(points.size(), 0);
  for (size_t i = 0; i < points.size(); ++i)
    if (const auto s = tree.sample(points[i], rng.uniform())) chosen[i] = s->light, checksum += s->pmf;
  const double sample_ns = 1e9 * seconds_since(t1) / double(points.size());
  t1 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < points.size(); ++i) checksum += tree.pmf(points[i], chosen[i]);
  const double pmf_ns = 1e9 * seconds_since(t1) / double(points.size());
  const PowerLightSampler by_power(power);
  t1 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < points.size(); ++i) checksum += by_power.pmf(by_power.sample(rng.uniform()));
  const double power_ns = 1e9 * seconds_since(t1) / double(points.size());

  log::info(
      "a light tree over {} triangles: built in {:.2f} s, {} nodes, {:.1f} MB (peak resident {:.0f} MB, {:.0f} "
      "before)",
      args.lights, build_s, tree.node_count(), tree.memory_bytes() / 1e6, peak_mb, before_peak_mb);
  log::info("a choice: sample {:.0f} ns, pmf {:.0f} ns; power sampling {:.0f} ns (checksum {:.3g})", sample_ns, pmf_ns,
            power_ns, checksum);
  std::printf(
      "light-tree lights=%zu build_s=%.3f nodes=%zu tree_mb=%.1f rss_before_mb=%.0f rss_after_mb=%.0f peak_mb=%.0f "
      "sample_ns=%.0f pmf_ns=%.0f power_ns=%.0f\n",
      args.lights, build_s, tree.node_count(), tree.memory_bytes() / 1e6, before_mb, after_mb, peak_mb, sample_ns,
      pmf_ns, power_ns);
}

}  // namespace

void add_bench_light_tree_command(CLI::App* bench) {
  auto args = std::make_shared<LightTreeArgs>();
  CLI::App* cmd = bench->add_subcommand(
      "light-tree", "Build a light tree over N emissive triangles; report build seconds, memory and a choice's cost");
  cmd->add_option("--lights", args->lights, "Emissive triangles")
      ->default_val(1'000'000)
      ->check(CLI::Range(size_t(1), size_t(100'000'000)));
  cmd->add_option("--queries", args->queries, "Points a light is chosen for, to time a choice")
      ->default_val(1'000'000)
      ->check(CLI::Range(1, 100'000'000));
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
