// `prism render SCENE -o OUT.exr`: loads a glTF scene, renders it and writes a scene-referred
// OpenEXR image (and optionally an sRGB preview PNG), printing the render statistics.

#include <chrono>
#include <sstream>

#include "apps/prism/commands.h"
#include "base/error.h"
#include "base/log.h"
#include "render/environment_map.h"
#include "render/image_output.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "spectral/cie.h"

namespace prism {

namespace {

struct RenderArgs {
  std::string scene, output, preview, env, env_map, colorspace = ColorPipeline::kDefaultOutput;
  float env_rotate = 0, env_scale = 1;
  int width = 0, height = 0, camera = -1;
  bool half = false, quiet = false;
  RenderOptions options;
};

Rgb parse_rgb(const std::string& text, const char* what) {
  Rgb rgb;
  std::stringstream ss(text);
  std::string cell;
  int i = 0;
  while (std::getline(ss, cell, ',')) {
    if (i == 3) fail("{} '{}': expected three numbers R,G,B", what, text);
    try {
      size_t used = 0;
      rgb[i] = std::stof(cell, &used);
      if (used != cell.size()) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      fail("{} '{}': '{}' is not a number", what, text, cell);
    }
    if (!std::isfinite(rgb[i]) || rgb[i] < 0) fail("{} '{}': values must be finite and non-negative", what, text);
    ++i;
  }
  if (i != 3) fail("{} '{}': expected three numbers R,G,B", what, text);
  return rgb;
}

CameraDesc choose_camera(const Scene& scene, int index, const RenderArgs& args) {
  if (index >= 0) {
    if (size_t(index) >= scene.cameras.size())
      fail("{}: --camera {} requested, but the scene has {} camera(s)", scene.source.string(), index,
           scene.cameras.size());
    return scene.cameras[index];
  }
  if (!scene.cameras.empty()) return scene.cameras[0];
  const float aspect = args.width > 0 && args.height > 0 ? float(args.width) / float(args.height) : 1.f;
  log::info("{}: no camera in the scene; using a camera that frames the whole scene", scene.source.string());
  return framing_camera(scene.world_bounds(), aspect);
}

void run(const RenderArgs& args) {
  if (args.quiet) log::set_level(log::Level::warn);
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  const Chromaticities chromaticities = ColorPipeline::standard().chromaticities(colorspace);
  std::optional<Rgb> env;
  if (!args.env.empty()) env = parse_rgb(args.env, "--env");
  cie();  // fail early if the data files are missing
  std::optional<EnvironmentMapDesc> env_map;
  if (!args.env_map.empty()) {
    env_map = load_environment_map(args.env_map, args.env_rotate, args.env_scale);
    log::info("environment map {}: {}x{}", env_map->file, env_map->image.width, env_map->image.height);
  }

  auto t0 = std::chrono::steady_clock::now();
  const auto seconds_since = [](auto t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  Scene scene = load_gltf(args.scene);
  if (env) scene.environment = RgbIlluminantSpectrum(*env);
  scene.environment_map = std::move(env_map);
  log::info("loaded {} in {:.2f} s: {} triangles in {} instances, {} materials, {} point, {} spot and {} "
            "directional lights",
            args.scene, seconds_since(t0), scene.triangle_count(), scene.instances.size(), scene.materials.size(),
            scene.point_lights.size(), scene.spot_lights.size(), scene.directional_lights.size());

  const CameraDesc camera_desc = choose_camera(scene, args.camera, args);
  const Vec2i size = resolve_resolution(args.width, args.height, camera_desc);
  const Camera camera(camera_desc, size.x, size.y);

  t0 = std::chrono::steady_clock::now();
  const World world(scene);
  log::info("scene features: {}", world.features().to_string());
  log::info("built the BVH over {} triangles in {:.0f} ms ({:.1f} MB)", world.accel().triangle_count(),
            1e3 * seconds_since(t0), world.accel().memory_bytes() / 1e6);
  if (world.lights().empty())
    log::warn("{}: the scene has no lights (the image will be black); light it with --env R,G,B", args.scene);

  log::info("rendering {}x{} at {} spp, {} wavelengths per path", size.x, size.y, args.options.spp,
            args.options.wavelengths);
  RenderOptions options = args.options;
  options.progress = !args.quiet;
  const RenderResult result = render(world, camera, options);
  log::info("{}", result.stats.summary());

  ExrImage image{result.width, result.height, result.xyz, chromaticities, {}};
  ColorPipeline::standard().convert(ColorPipeline::kXyz, colorspace, image.rgb.data(), image.rgb.size() / 3);
  image.metadata = {
      {"software", std::string("Prism " PRISM_VERSION)},
      {"prism.scene", args.scene},
      {"prism.integrator", std::string(args.options.integrator == IntegratorKind::path ? "path" : "whitted")},
      {"prism.spp", args.options.spp},
      {"prism.seconds", result.stats.seconds},
      {"prism.seed", std::to_string(args.options.seed)},
      {"prism.wavelengthsPerPath", args.options.wavelengths},
      {"prism.maxDepth", args.options.path.max_depth},
      {"prism.colorSpace", colorspace},
      {"prism.sceneFeatures", world.features().to_string()},
      {"prism.invalidSamples", std::to_string(result.stats.invalid_samples)},
  };
  write_exr(args.output, image, args.half);
  std::printf("wrote %s (%dx%d, %s)\n", args.output.c_str(), result.width, result.height, colorspace.c_str());

  if (!args.preview.empty()) {
    std::vector<float> display = result.xyz;
    ColorPipeline::standard().xyz_to_display(ColorPipeline::kDefaultDisplay, ColorPipeline::kDefaultView,
                                             display.data(), display.size() / 3);
    write_png(args.preview, result.width, result.height, display);
    std::printf("wrote %s (preview, %s / %s)\n", args.preview.c_str(), ColorPipeline::kDefaultDisplay,
                ColorPipeline::kDefaultView);
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF 2.0 scene to a scene-referred OpenEXR image");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("-o,--output", args->output, "Output OpenEXR file")->required();
  cmd->add_option("--spp", args->options.spp, "Samples per pixel")->default_val(16)->check(CLI::PositiveNumber);
  cmd->add_option("--width", args->width, "Image width in pixels (default: 640, or from --height and the camera's aspect)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--height", args->height, "Image height in pixels (default: from the width and the camera's aspect)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", args->options.seed, "Random seed: the same seed gives the same image")->default_val(0);
  cmd->add_option("--threads", args->options.threads, "Worker threads (0: all cores)")
      ->default_val(0)->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-depth", args->options.path.max_depth, "Maximum path length in bounces")
      ->default_val(16)->check(CLI::NonNegativeNumber);
  cmd->add_option("--integrator", args->options.integrator,
                  "path: unidirectional path tracing (NEE + MIS); whitted: recursive Fresnel splitting")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, IntegratorKind>{{"path", IntegratorKind::path}, {"whitted", IntegratorKind::whitted}}))
      ->default_str("path");
  cmd->add_option("--wavelengths", args->options.wavelengths, "Wavelengths carried per path (1, 4 or 8)")
      ->default_val(kDefaultWavelengths)->check(CLI::IsMember({1, 4, 8}));
  CLI::Option* env = cmd->add_option("--env", args->env,
                                     "Constant environment radiance as linear Rec.709 R,G,B (e.g. 1,1,1)");
  CLI::Option* env_map =
      cmd->add_option("--env-map", args->env_map,
                      "Environment image: equirectangular .exr or .hdr of linear Rec.709 radiance, +Y up")
          ->excludes(env);
  cmd->add_option("--env-rotate", args->env_rotate, "Rotate the environment image about +Y by DEG degrees")
      ->needs(env_map);
  cmd->add_option("--env-scale", args->env_scale, "Multiply the environment image by S")
      ->needs(env_map)->check(CLI::NonNegativeNumber);
  cmd->add_option("--colorspace", args->colorspace, "Output colour space from data/ocio/config.ocio")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_option("--camera", args->camera, "Use the N-th camera in scene order (0-based; default: the first)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--preview", args->preview, "Also write an sRGB preview PNG through the OCIO display view");
  cmd->add_flag("--half", args->half, "Write 16-bit half floats instead of 32-bit floats");
  cmd->add_flag("-q,--quiet", args->quiet, "Only warnings and errors; no progress bar");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
