// `prism render SCENE -o OUT.exr`: loads a glTF scene, renders it and writes a scene-referred
// OpenEXR image (and optionally an sRGB preview PNG), printing the render statistics. With
// `--frames A:B` it renders the animation's frames A to B, loading the file once.

#include "apps/prism/commands.h"
#include "apps/prism/frame_sequence.h"
#include "apps/prism/scene_setup.h"
#include "base/clock.h"
#include "base/error.h"
#include "base/log.h"
#include "render/image_output.h"

namespace prism {

namespace {

struct RenderArgs {
  SceneArgs scene;
  std::string output, preview, colorspace = ColorPipeline::kDefaultOutput;
  bool half = false, quiet = false;
  std::string frames;  // "A:B"
  double fps = 24;
  RenderOptions options;
};

// Renders the prepared scene to `output` (and `preview`); `time` is the animation time posed.
void render_image(const RenderArgs& args, const PreparedScene& prepared, const std::string& output,
                  const std::string& preview, std::optional<double> time) {
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  const Chromaticities chromaticities = ColorPipeline::standard().chromaticities(colorspace);
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
  if (time) image.metadata.push_back({"prism.time", *time});
  write_exr(output, image, args.half);
  std::printf("wrote %s (%dx%d, %s)\n", output.c_str(), result.width, result.height, colorspace.c_str());

  if (!preview.empty()) {
    std::vector<float> display = result.xyz;
    ColorPipeline::standard().xyz_to_display(ColorPipeline::kDefaultDisplay, ColorPipeline::kDefaultView,
                                             display.data(), display.size() / 3);
    write_png(preview, result.width, result.height, display);
    std::printf("wrote %s (preview, %s / %s)\n", preview.c_str(), ColorPipeline::kDefaultDisplay,
                ColorPipeline::kDefaultView);
  }
}

void run(const RenderArgs& args) {
  if (args.quiet) log::set_level(log::Level::warn);
  ColorPipeline::standard().canonical_name(args.colorspace);  // a bad name fails before any work
  if (args.frames.empty()) {
    render_image(args, prepare_scene(args.scene), args.output, args.preview, args.scene.gltf.time);
    return;
  }
  const FrameRange range = parse_frames(args.frames);
  if (!(args.fps > 0 && std::isfinite(args.fps))) fail("--fps {}: must be a positive number", args.fps);
  SceneArgs scene_args = args.scene;
  scene_args.gltf.time = range.first / args.fps;
  PreparedScene prepared = prepare_scene(scene_args, true);
  if (!prepared.gltf->animated()) log::warn("{}: nothing is animated; every frame is the same image", args.scene.scene);
  const auto t0 = std::chrono::steady_clock::now();
  for (int64_t frame = range.first; frame <= range.last; ++frame) {
    const double time = frame / args.fps;
    log::info("frame {} ({} of {}) at {:.4f} s", frame, frame - range.first + 1, range.last - range.first + 1, time);
    if (frame > range.first && !pose_scene(prepared, scene_args, time)) log::info("nothing moved: same world");
    render_image(args, prepared, frame_path(args.output, int(frame)),
                 args.preview.empty() ? "" : frame_path(args.preview, int(frame)), time);
  }
  log::info("rendered {} frames in {:.1f} s", range.last - range.first + 1, seconds_since(t0));
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF 2.0 scene to a scene-referred OpenEXR image");
  add_scene_options(cmd, args->scene);
  cmd->add_option("-o,--output", args->output,
                  "Output OpenEXR file (with --frames: a #### pattern for the frame number)")
      ->required();
  cmd->add_option("--frames", args->frames,
                  "Render the animation's frames A to B (A:B) at --fps, loading the file once")
      ->excludes("--time");
  cmd->add_option("--fps", args->fps, "Frames per second of --frames: frame N is at N / fps seconds")->default_val(24);
  add_render_options(cmd, args->options);
  cmd->add_option("--colorspace", args->colorspace, "Output colour space from data/ocio/config.ocio")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_option("--preview", args->preview, "Also write an sRGB preview PNG through the OCIO display view");
  cmd->add_flag("--half", args->half, "Write 16-bit half floats instead of 32-bit floats");
  cmd->add_flag("-q,--quiet", args->quiet, "Only warnings and errors; no progress bar");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
