// `prism bench rays SCENE RAYS.bin`: traces raybench's ray files (tools/raybench in the shared
// assets, PRISM_SHARED_DIR) with Prism's own loader and acceleration structure, the same code the
// renderer uses, and times it the way raybench times Embree, so that the two can be compared ray
// for ray on one machine: T threads take chunks of 4096 consecutive rays from a shared counter; a
// pass is timed from thread creation to join; the best and the median of R passes (after one
// warm-up) are reported.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "apps/prism/commands.h"
#include "apps/prism/ray_file.h"
#include "core/base/clock.h"
#include "core/base/log.h"
#include "core/base/parallel.h"
#include "core/render/world.h"
#include "core/scene/gltf_loader.h"

namespace prism {

namespace {

struct BenchArgs {
  std::string scene, rays, hits;
  int threads = 0, repeat = 5;
  bool occluded = false;
  AccelOptions accel;
};

constexpr size_t kChunk = 4096;

// One timed pass over all rays; returns its wall time in seconds.
double trace_pass(const Accel& accel, const std::vector<Ray>& rays, bool occluded, int threads,
                  std::vector<HitRecord>& hits) {
  std::atomic<size_t> next{0};
  const auto worker = [&] {
    for (size_t begin; (begin = next.fetch_add(kChunk)) < rays.size();) {
      const size_t end = std::min(begin + kChunk, rays.size());
      for (size_t i = begin; i < end; ++i) {
        if (occluded) {
          hits[i] = accel.occluded(rays[i]) ? HitRecord::occluded() : HitRecord::miss();
        } else {
          AccelHit h;
          hits[i] = accel.intersect(rays[i], h) ? HitRecord{h.t, accel.global_prim(h)} : HitRecord::miss();
        }
      }
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  return seconds_since(t0);
}

void run(const BenchArgs& args) {
  const int threads = args.threads > 0 ? args.threads : int(std::thread::hardware_concurrency());
  const Scene scene = load_gltf(args.scene);
  const std::vector<Ray> rays = read_rays(args.rays);

  // The build uses as many threads as the tracing, as raybench's Embree build does by default.
  const ThreadLimit limit(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const Accel accel = build_accel(scene, args.accel);
  const double build_ms = 1e3 * seconds_since(t0);
  log::info("{}: {} triangles in {} instances; BVH built in {:.1f} ms, {:.1f} MB", args.scene, accel.triangle_count(),
            scene.instances.size(), build_ms, accel.memory_bytes() / 1e6);

  std::vector<HitRecord> hits(rays.size());
  trace_pass(accel, rays, args.occluded, threads, hits);  // warm-up
  std::vector<double> mrays;
  for (int r = 0; r < args.repeat; ++r)
    mrays.push_back(double(rays.size()) / trace_pass(accel, rays, args.occluded, threads, hits) / 1e6);
  std::sort(mrays.begin(), mrays.end());
  const size_t hit_count =
      std::count_if(hits.begin(), hits.end(), [](const HitRecord& h) { return h.prim != HitRecord::kMiss; });
  if (!args.hits.empty()) write_hits(args.hits, hits);
  const double bytes_per_tri = accel.triangle_count() ? double(accel.memory_bytes()) / accel.triangle_count() : 0;
  std::printf("prism build_ms=%.1f mrays_best=%.3f mrays_median=%.3f hits=%zu rays=%zu threads=%d bytes_per_tri=%.1f\n",
              build_ms, mrays.back(), mrays[mrays.size() / 2], hit_count, rays.size(), threads, bytes_per_tri);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = bench->add_subcommand("rays", "Trace a raybench RAYS.bin file and report the throughput");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("rays", args->rays, "Rays in raybench's RAYS.bin format")->required();
  cmd->add_option("--threads", args->threads, "Tracing and build threads (0: all cores)")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--repeat", args->repeat, "Timed passes")->default_val(5)->check(CLI::PositiveNumber);
  cmd->add_flag("--occluded", args->occluded, "Any-hit (shadow) queries instead of closest hit");
  cmd->add_flag("--flatten", args->accel.flatten_instances,
                "Copy shared meshes into the world-space BVH instead of instancing them");
  cmd->add_option("--hits", args->hits, "Write the last pass's results in raybench's HITS.bin format");
  cmd->callback([args] { run(*args); });
  add_bench_features_command(bench);
  add_bench_instances_command(bench);
  add_bench_light_tree_command(bench);
}

}  // namespace prism
