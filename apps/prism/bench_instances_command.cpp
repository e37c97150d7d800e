// `prism bench instances`: a forest of N instances (default 10⁶) of one mesh of T triangles
// (default 10,000), built in code, then made ready to render (World: accel and lights) and traced
// by a few camera rays. Prints the build's seconds and memory: the scene's instance array, the
// accel, and the process's peak resident set, so that instancing is seen to cost memory per
// instance, not per triangle. The target: 10⁶ × 10k triangles in < 2 s and < 150 MB.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "apps/prism/commands.h"
#include "apps/prism/resident_memory.h"
#include "core/base/clock.h"
#include "core/base/log.h"
#include "core/base/parallel.h"
#include "core/base/rng.h"
#include "core/render/world.h"

namespace prism {

namespace {

struct InstancesArgs {
  size_t count = 1'000'000;
  int triangles = 10'000, threads = 0;
};

// A closed, bumpy sphere of about `triangles` triangles (a latitude–longitude grid), radius ~1.
Mesh tree_mesh(int triangles) {
  const int rows = std::max(2, int(std::sqrt(triangles / 4.0))), cols = std::max(3, triangles / (2 * rows));
  Mesh m;
  m.name = "tree";
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const float theta = kPi * float(r) / float(rows), phi = 2 * kPi * float(c) / float(cols);
      const float radius = 1 + 0.1f * std::sin(7 * theta) * std::cos(5 * phi);
      m.positions.push_back(Vec3f(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)) *
                            radius);
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const uint32_t a = uint32_t(r * cols + c), b = uint32_t(r * cols + (c + 1) % cols);
      const uint32_t d = a + uint32_t(cols), e = b + uint32_t(cols);
      for (uint32_t i : {a, d, b, b, d, e}) m.indices.push_back(i);
    }
  return m;
}

void run(const InstancesArgs& args) {
  const ThreadLimit limit(args.threads);
  Scene scene;
  scene.materials.push_back({.name = "bark", .kind = DiffuseMaterial{}});
  scene.meshes.push_back(tree_mesh(args.triangles));
  // A square forest on a jittered grid, each tree turned and scaled at random.
  const size_t side = size_t(std::ceil(std::sqrt(double(args.count))));
  Rng rng(1, 0);
  scene.instances.reserve(args.count);
  for (size_t i = 0; i < args.count; ++i) {
    const double x = 4.0 * double(i % side) + 2 * rng.uniform(), z = 4.0 * double(i / side) + 2 * rng.uniform();
    const double angle = 2 * kPi * rng.uniform(), s = 0.5 + rng.uniform();
    scene.instances.push_back(
        {0, Transform::translate({x, s, z}) * Transform::rotate(0, std::sin(angle / 2), 0, std::cos(angle / 2)) *
                Transform::scale({s, s, s})});
  }
  scene.environment = ConstantSpectrum{1.f};
  const auto [before_mb, before_peak_mb] = resident_mb();

  const auto t0 = std::chrono::steady_clock::now();
  const World world(scene);
  const double build_s = seconds_since(t0);
  const auto [after_mb, peak_mb] = resident_mb();

  // A few rays down onto the forest, to see the structure answer.
  size_t hits = 0;
  const double extent = 4.0 * double(side);
  Rng ray_rng(2, 0);
  for (int i = 0; i < 100'000; ++i) {
    const Vec3f o(float(extent * ray_rng.uniform()), 50.f, float(extent * ray_rng.uniform()));
    hits += world.intersect({o, normalize(Vec3f(0.3f, -1, 0.2f)), kInfinity}).has_value();
  }
  const double instances_mb = double(scene.instances.size() * sizeof(Instance)) / 1e6;
  log::info("{} instances of a {}-triangle mesh ({:.3g} triangles): World built in {:.2f} s", scene.instances.size(),
            scene.meshes[0].indices.size() / 3, double(scene.triangle_count()), build_s);
  log::info(
      "memory: instances {:.1f} MB, accel {:.1f} MB; resident {:.0f} MB before the build, {:.0f} MB after, "
      "peak {:.0f} MB; {} of 100000 rays hit",
      instances_mb, world.accel().memory_bytes() / 1e6, before_mb, after_mb, peak_mb, hits);
  std::printf(
      "instances count=%zu triangles=%zu build_s=%.3f instances_mb=%.1f accel_mb=%.1f rss_before_mb=%.0f "
      "rss_after_mb=%.0f peak_mb=%.0f hits=%zu\n",
      scene.instances.size(), scene.meshes[0].indices.size() / 3, build_s, instances_mb,
      world.accel().memory_bytes() / 1e6, before_mb, after_mb, peak_mb, hits);
}

}  // namespace

void add_bench_instances_command(CLI::App* bench) {
  auto args = std::make_shared<InstancesArgs>();
  CLI::App* cmd =
      bench->add_subcommand("instances", "Build a forest of instances of one mesh; report build seconds and memory");
  cmd->add_option("--count", args->count, "Instances")
      ->default_val(1'000'000)
      ->check(CLI::Range(size_t(1), size_t(100'000'000)));
  cmd->add_option("--triangles", args->triangles, "Triangles of the instanced mesh (about)")
      ->default_val(10'000)
      ->check(CLI::Range(12, 10'000'000));
  cmd->add_option("--threads", args->threads, "Build threads (0: all cores)")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
