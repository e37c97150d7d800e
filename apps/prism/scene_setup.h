#pragma once
// What the commands that render a scene share (render, converge): their command-line options,
// and loading a scene with its environment, camera and world.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "render/renderer.h"

namespace prism {

struct SceneArgs {
  std::string scene, env, env_map;
  float env_rotate = 0, env_scale = 1;
  int width = 0, height = 0, camera = -1;
  bool energy_compensation = true;  // off: --no-energy-compensation (single-scattering microfacets)
};

// The scene file (positional), --env / --env-map / --env-rotate / --env-scale, --width,
// --height, --camera and --no-energy-compensation.
void add_scene_options(CLI::App* cmd, SceneArgs& args);

// --spp, --seed, --threads, --max-depth, --integrator, --wavelengths, --sampler, --light-sampling.
void add_render_options(CLI::App* cmd, RenderOptions& options);

// A scene ready to render. The world refers to the scene, so both live behind pointers.
struct PreparedScene {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<World> world;
  std::unique_ptr<Camera> camera;
};

// Loads and prepares the scene, logging what it found; fails with a clear message on bad input.
PreparedScene prepare_scene(const SceneArgs& args);

const char* integrator_name(IntegratorKind kind);
const char* sampler_name(SamplerKind kind);

}  // namespace prism
