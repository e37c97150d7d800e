#pragma once
// What the commands that render a scene share (render, converge): their command-line options,
// and loading a scene with its environment, camera and world.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "core/render/renderer.h"
#include "core/scene/gltf_loader.h"

namespace prism {

struct SceneArgs {
  std::string scene, env, env_map, env_spectrum, fog;
  float env_rotate = 0, env_scale = 1;
  int width = 0, height = 0, camera = -1;
  GltfOptions gltf;
  double max_memory_gb = 0;         // 0: the machine's physical memory
  bool energy_compensation = true;  // off: --no-energy-compensation (single-scattering microfacets)
  LightSamplerKind light_sampler = kDefaultLightSampler;  // --light-sampler
  LensDesc lens;  // --aperture, --lens-radius, --focus-distance, …: over the camera's own
};

// Bytes Prism budgets per pixel of the image and per mesh instance (scene, BVH, world), to refuse
// work that would not fit in --max-memory before allocating it. A pixel: the film's exact sums
// (152 bytes: colour, squares, replicate sums, counts), its output copies (about 40) and room for
// a bidirectional render's splat sums; AOVs and spectral bins add to that and are not counted.
inline constexpr uint64_t kBytesPerPixel = 256, kBytesPerInstance = 512;

// Validators for positive counts up to INT_MAX (without a 309-digit range in the message) and
// for seeds (0 to 2^64 − 1, no silent wrap of −1).
const CLI::Validator& positive_count();
const CLI::Validator& seed_value();

// The scene file (positional), --env / --env-map / --env-rotate / --env-scale / --env-spectrum, --fog, --width,
// --height, --camera and its lens (add_lens_options), --no-energy-compensation, --light-sampler, and the
// glTF choices of add_gltf_options.
void add_scene_options(CLI::App* cmd, SceneArgs& args);

// --scene, --variant, --time, --animation and --allow-external-paths.
void add_gltf_options(CLI::App* cmd, GltfOptions& options);

// --aperture, --sensor-width, --lens-radius, --focus-distance, --focus-node, --blades, --blade-rotation.
void add_lens_options(CLI::App* cmd, LensDesc& lens);

// --spp, --seed, --threads, --max-depth, --integrator (its name, or "auto": resolve_integrator), --merge-radius,
// --wavelengths, --sampler, --light-sampling.
void add_render_options(CLI::App* cmd, RenderOptions& options, std::string& integrator);

// The integrator named on the command line, or for "auto" the one the world's scene needs
// (choose_integrator), for a render with these options; the choice is logged.
IntegratorKind resolve_integrator(const std::string& name, const World& world, const RenderOptions& options);

// A validator of integrator names (the table's; with `automatic`, "auto" too).
CLI::Validator integrator_validator(bool automatic);

// A scene ready to render. The world refers to the scene, so both live behind pointers.
struct PreparedScene {
  std::unique_ptr<GltfScene> gltf;
  std::unique_ptr<World> world;
  std::unique_ptr<Camera> camera;
};

// Loads and prepares the scene, logging what it found; fails with a clear message on bad input.
// Unless `keep_file` (to re-pose it with pose_scene), the parsed file is freed once loaded. With
// `keep_file` only the camera is placed: the first pose_scene builds the world, at its pose.
PreparedScene prepare_scene(const SceneArgs& args, bool keep_file = false);

// Poses the scene at `seconds` of its animations and rebuilds its world and camera, only when
// something moved or the world was not built yet; returns whether it did.
bool pose_scene(PreparedScene& prepared, const SceneArgs& args, double seconds);

const char* sampler_name(SamplerKind kind);

}  // namespace prism
