// `prism bench features SCENE`: what the path tracer's optional machinery costs on a scene.
// Renders the scene with the variant the renderer picks for it, then with the medium stack and
// the dispersion check forced on in turn and together, and prints samples per second (best of
// --repeat runs, back to back in one process so that the machine's load affects all alike).

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "apps/prism/commands.h"
#include "apps/prism/scene_setup.h"
#include "core/base/log.h"

namespace prism {

namespace {

struct FeaturesArgs {
  SceneArgs scene;
  int spp = 16, repeat = 3, threads = 0;
};

double best_samples_per_second(const PreparedScene& p, RenderOptions options, int repeat) {
  double best = 0;
  for (int r = 0; r < repeat; ++r)
    best = std::max(best, render(*p.world, *p.camera, options).stats().samples_per_second());
  return best;
}

void run(const FeaturesArgs& args) {
  const PreparedScene p = prepare_scene(args.scene);
  const PathFeatures needed = path_features(p.world->features());
  RenderOptions options;
  options.spp = args.spp;
  options.threads = args.threads;
  options.progress = false;
  const auto variant = [&](bool media, bool dispersion) {
    RenderOptions o = options;
    o.features = PathFeatures{needed.media || media, needed.dispersion || dispersion};
    return best_samples_per_second(p, o, args.repeat);
  };
  const double automatic = variant(false, false), media = variant(true, false), dispersion = variant(false, true),
               full = variant(true, true);
  std::printf("%-44s %12s %9s\n", "path tracer variant", "samples/s", "vs needed");
  const auto row = [&](const char* name, double sps) {
    std::printf("%-44s %12.4g %+8.1f%%\n", name, sps, 100 * (automatic / sps - 1));
  };
  row(fmt::format("as the scene needs (media {}, dispersion {})", needed.media ? "on" : "off",
                  needed.dispersion ? "on" : "off")
          .c_str(),
      automatic);
  row("+ medium stack and Beer-Lambert", media);
  row("+ dispersion check", dispersion);
  row("+ both (all optional machinery)", full);
  std::printf("features needed_sps=%.4g media_sps=%.4g dispersion_sps=%.4g full_sps=%.4g full_cost_pct=%.1f\n",
              automatic, media, dispersion, full, 100 * (automatic / full - 1));
}

}  // namespace

void add_bench_features_command(CLI::App* bench) {
  auto args = std::make_shared<FeaturesArgs>();
  CLI::App* cmd = bench->add_subcommand("features", "Samples/s of a scene with each optional path-tracer feature on");
  add_scene_options(cmd, args->scene);
  cmd->add_option("--spp", args->spp, "Samples per pixel of each run")->default_val(16)->check(CLI::PositiveNumber);
  cmd->add_option("--repeat", args->repeat, "Runs per variant (the best counts)")
      ->default_val(3)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")->default_val(0);
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
