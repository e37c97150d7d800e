// `prism render SCENE -o OUT.exr`: loads a glTF scene, renders it and writes a scene-referred
// OpenEXR image (and optionally an sRGB preview PNG), printing the render statistics.

#include "apps/prism/commands.h"
#include "apps/prism/scene_setup.h"
#include "base/error.h"
#include "base/log.h"
#include "render/image_output.h"

namespace prism {

namespace {

struct RenderArgs {
  SceneArgs scene;
  std::string output, preview, colorspace = ColorPipeline::kDefaultOutput;
  bool half = false, quiet = false;
  RenderOptions options;
};

// An output path must be a regular file or not exist yet, in a folder (made if missing): never a
// device, a folder or anything else the final rename would replace. Checked before rendering.
void check_output(const std::string& path, const char* option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    fail("{}: {} names something other than a regular file; refusing to replace it", path, option);
  for (fs::path dir = fs::path(path).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::exists(dir, ec)) {
      if (!fs::is_directory(dir, ec)) fail("{}: {} lies under {}, which is not a folder", path, option, dir.string());
      break;
    }
    if (dir == dir.parent_path()) break;
  }
}

void run(const RenderArgs& args) {
  check_output(args.output, "-o");
  if (!args.preview.empty()) check_output(args.preview, "--preview");
  if (args.quiet) log::set_level(log::Level::warn);
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  const Chromaticities chromaticities = ColorPipeline::standard().chromaticities(colorspace);
  const PreparedScene prepared = prepare_scene(args.scene);
  const Camera& camera = *prepared.camera;

  log::info("rendering {}x{} at {} spp, {} wavelengths per path", camera.width(), camera.height(), args.options.spp,
            args.options.wavelengths);
  RenderOptions options = args.options;
  options.progress = !args.quiet;
  const RenderResult result = render(*prepared.world, camera, options);
  log::info("{}", result.stats.summary());

  ExrImage image{result.width, result.height, result.xyz, chromaticities, {}};
  ColorPipeline::standard().convert(ColorPipeline::kXyz, colorspace, image.rgb.data(), image.rgb.size() / 3);
  image.metadata = {
      {"software", std::string("Prism " PRISM_VERSION)},
      {"prism.scene", args.scene.scene},
      {"prism.integrator", std::string(integrator_name(options.integrator))},
      {"prism.sampler", std::string(sampler_name(options.sampler))},
      {"prism.lightSampling", std::string(options.path.next_event ? "mis" : "bsdf")},
      {"prism.spp", options.spp},
      {"prism.seconds", result.stats.seconds},
      {"prism.seed", std::to_string(options.seed)},
      {"prism.wavelengthsPerPath", options.wavelengths},
      {"prism.maxDepth", options.path.max_depth},
      {"prism.colorSpace", colorspace},
      {"prism.sceneFeatures", prepared.world->features().to_string()},
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
  add_scene_options(cmd, args->scene);
  cmd->add_option("-o,--output", args->output, "Output OpenEXR file")->required();
  add_render_options(cmd, args->options);
  cmd->add_option("--colorspace", args->colorspace, "Output colour space from data/ocio/config.ocio")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_option("--preview", args->preview, "Also write an sRGB preview PNG through the OCIO display view");
  cmd->add_flag("--half", args->half, "Write 16-bit half floats instead of 32-bit floats");
  cmd->add_flag("-q,--quiet", args->quiet, "Only warnings and errors; no progress bar");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
