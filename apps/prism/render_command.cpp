// `prism render SCENE -o OUT.exr`: loads a glTF scene, renders it in progressive passes and writes
// a scene-referred OpenEXR image (with AOV layers and spectral bins on request, and optionally an
// sRGB preview PNG), printing the render statistics and the image's estimated error. Stops early
// on --time-limit or a first SIGINT/SIGTERM (writing what it has), keeps a checkpoint to
// --resume from, and aborts without output on a second signal. With `--frames A:B` it renders the
// animation's frames A to B, loading the file once.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/prism/commands.h"
#include "apps/prism/film_image.h"
#include "apps/prism/frame_sequence.h"
#include "apps/prism/scene_setup.h"
#include "core/base/checksum.h"
#include "core/base/clock.h"
#include "core/base/error.h"
#include "core/base/interrupt.h"
#include "core/base/log.h"
#include "core/render/checkpoint.h"
#include "core/render/error_estimate.h"
#include "core/render/image_output.h"
#include "core/render/pass_schedule.h"

namespace prism {

namespace {

struct RenderArgs {
  SceneArgs scene;
  std::string output, preview, colorspace = ColorPipeline::kDefaultOutput, aovs, spectral_bins, samples, crop;
  std::string integrator = "auto", white_balance = "none";
  bool half = false, quiet = false, verbose = false, resume = false;
  double checkpoint = 0;
  std::string frames;  // "A:B"
  double fps = 24;
  RenderOptions options;
};

uint32_t parse_aovs(const std::string& text) {
  const std::pair<const char*, Aov> names[] = {{"albedo", kAovAlbedo},
                                               {"normal", kAovNormal},
                                               {"depth", kAovDepth},
                                               {"variance", kAovVariance},
                                               {"spp", kAovSpp}};
  uint32_t aovs = 0;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    const auto* it = std::find_if(std::begin(names), std::end(names), [&](const auto& n) { return cell == n.first; });
    if (it == std::end(names))
      fail("--aov '{}': unknown AOV '{}'; choose from albedo, normal, depth, variance, spp", text, cell);
    aovs |= it->second;
  }
  return aovs;
}

// `--samples A:B` and `--crop x0,y0,x1,y1`.
void parse_part(const RenderArgs& args, RenderOptions& o) {
  if (!args.samples.empty()) {
    char colon = 0, rest = 0;
    if (std::sscanf(args.samples.c_str(), "%d%c%d%c", &o.sample_begin, &colon, &o.sample_end, &rest) != 3 ||
        colon != ':')
      fail("--samples '{}': expected A:B (sample indices A to B-1 of the --spp render)", args.samples);
  }
  if (!args.crop.empty()) {
    PixelWindow& c = o.crop;
    char rest = 0;
    if (std::sscanf(args.crop.c_str(), "%d,%d,%d,%d%c", &c.x0, &c.y0, &c.x1, &c.y1, &rest) != 4 || c.empty())
      fail("--crop '{}': expected x0,y0,x1,y1 with x0 < x1 and y0 < y1 (pixels, top row 0, ends exclusive)", args.crop);
  }
}

// The environment's spectra as rendered (its white's, with --env-spectrum): what a file it names holds.
uint64_t environment_hash(const Scene& scene) {
  Checksum sum;
  const auto add = [&](const DenselySampledSpectrum& s) {
    sum.add(s.values().data(), s.values().size() * sizeof(float));
  };
  if (scene.environment) add(densely_sampled(*scene.environment));
  if (scene.environment_map && scene.environment_map->white) add(*scene.environment_map->white);
  return sum.h;
}

// Everything that shapes the image but the sample count: a checkpoint resumes, and parts merge,
// only with these. The scene and the environment map are named by their file names and the hash
// of their content (the scene's file and those it reads; the map's values), not by their paths:
// parts rendered on nodes that mount the shared folder at other paths still merge, and a file
// changed in place does not.
std::string fingerprint(const RenderArgs& args, const Scene& scene, const Camera& camera, const RenderOptions& o,
                        std::optional<double> time) {
  const SceneArgs& s = args.scene;
  const std::optional<EnvironmentMapDesc>& env_map = scene.environment_map;
  return fmt::format(
      "scene={} scene-hash={:016x} time={} env={} env-map={} env-map-hash={:016x} env-rotate={} env-scale={} "
      "env-spectrum={} env-white-hash={:016x} fog={} camera={} "
      "camera-hash={:016x} size={}x{} "
      "integrator={} merge-radius={} "
      "seed={} sampler={} "
      "wavelengths={} max-depth={} light-sampling={} light-sampler={} noise-threshold={} noise-channels={} aovs={} "
      "spectral-bins={} "
      "energy-compensation={} gltf-scene={} variant={} animation={}",
      scene.source.filename().string(), scene.source_hash, time ? fmt::format("{}", *time) : "-", s.env,
      std::filesystem::path(s.env_map).filename().string(), env_map ? env_map->hash : 0, s.env_rotate, s.env_scale,
      std::filesystem::path(s.env_spectrum).filename().string(), environment_hash(scene), s.fog.empty() ? "-" : s.fog,
      s.camera, camera.hash(), camera.width(), camera.height(), integrator(o.integrator).name, o.merge_radius, o.seed,
      sampler_name(o.sampler), o.wavelengths, o.path.max_depth, o.path.next_event ? "mis" : "bsdf",
      light_sampler_name(s.light_sampler), o.noise_threshold,
      o.noise_threshold > 0  // the output space's channels steer adaptive sampling
          ? fmt::format("{}/{}", ColorPipeline::standard().canonical_name(args.colorspace), args.white_balance)
          : "-",
      o.aovs, o.spectral_bins.to_string(), s.energy_compensation, s.gltf.scene ? fmt::format("{}", *s.gltf.scene) : "-",
      s.gltf.variant, s.gltf.animation);
}

// The image's error as the log and the header state it.
std::string error_summary(const Film& film, const OutputChannels& output) {
  const ErrorEstimate error(film, output);
  return fmt::format(
      "estimated relative RMSE {:.4g} of luminance (per pixel: median {:.3g}, 90th percentile {:.3g}), {:.4g} of RGB",
      error.rel_rmse(), error.pixel_rel_rmse_quantile(0.5), error.pixel_rel_rmse_quantile(0.9),
      error.output_rel_rmse());
}

struct SampleCounts {
  uint32_t min = ~0u, max = 0;
  double mean = 0;
};
SampleCounts sample_counts(const Film& film) {
  SampleCounts c;
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    c.min = std::min(c.min, film.samples(p));
    c.max = std::max(c.max, film.samples(p));
    c.mean += film.samples(p);
  }
  c.mean /= double(film.pixel_count());
  return c;
}

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

// Renders the prepared scene to `output` (and `preview`); `time` is the animation time posed.
// With --samples/--crop it writes a part file instead. Returns false if a signal interrupted it.
bool render_image(const RenderArgs& args, const PreparedScene& prepared, const std::string& output,
                  const std::string& preview, std::optional<double> time) {
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  RenderOptions options = args.options;
  options.progress = !args.quiet;
  options.aovs = parse_aovs(args.aovs);
  if (!args.spectral_bins.empty()) options.spectral_bins = SpectralBins::parse(args.spectral_bins);
  parse_part(args, options);
  const std::optional<WhiteBalance> balance = white_balance_option(args.white_balance);
  const OutputChannels channels = output_channels(colorspace, balance ? &*balance : nullptr);
  options.noise_channels = channels;
  const bool part = !args.samples.empty() || !args.crop.empty();
  const std::filesystem::path checkpoint = output + ".checkpoint";

  options.integrator = resolve_integrator(args.integrator, *prepared.world, options);
  const Camera& camera = *prepared.camera;
  const std::string print = fingerprint(args, prepared.gltf->scene(), camera, options, time);
  std::optional<RenderState> resume;
  if (args.resume) {
    resume = load_checkpoint(checkpoint, print);
    const RenderPart& r = resume->part;
    if (r.sample_begin != options.sample_begin ||
        r.sample_end != (options.sample_end ? options.sample_end : options.spp) || r.crop != options.crop)
      fail("{}: the checkpoint holds samples {}:{} of window {},{},{},{}, not the part asked for", checkpoint.string(),
           r.sample_begin, r.sample_end, r.crop.x0, r.crop.y0, r.crop.x1, r.crop.y1);
    log::info("resuming {} after pass {} ({} samples)", checkpoint.string(), resume->passes, resume->stats.samples);
  }

  log::info("rendering {}x{} at {} spp{}, {} wavelengths per path", camera.width(), camera.height(), options.spp,
            options.noise_threshold > 0 ? fmt::format(" at most (noise threshold {})", options.noise_threshold) : "",
            options.wavelengths);
  auto last_checkpoint = std::chrono::steady_clock::now();
  RenderControl control{&interrupt::requested(), [&](const PassReport& pass, const RenderState& state) {
                          if (log::level() >= log::Level::verbose)  // the error summary sorts the pixels
                            log::verbose("pass {}: {} spp, {} pixels sampled, {:.1f} s; {}", pass.pass + 1,
                                         pass.samples_end, pass.active_pixels, state.stats.seconds,
                                         error_summary(state.film, channels));
                          if (args.checkpoint > 0 && seconds_since(last_checkpoint) >= args.checkpoint) {
                            save_checkpoint(checkpoint, state, print);
                            last_checkpoint = std::chrono::steady_clock::now();
                          }
                        }};
  const RenderResult result = render(*prepared.world, camera, options, control, std::move(resume));
  const Film& film = result.state.film;
  log::info("{}", result.stats().summary());
  log::info("{}", error_summary(film, channels));
  const RenderPart& done = result.state.part;
  const bool complete = result.state.passes >= pass_count(done.sample_end - done.sample_begin);
  if (result.interrupted) log::warn("interrupted after pass {}: writing what it has", result.state.passes);
  if (result.timed_out) log::info("time limit reached after pass {}", result.state.passes);

  if (part) {
    // A part file holds the exact sums `prism merge` needs; an unfinished part stays a checkpoint.
    if (!complete) {
      save_checkpoint(checkpoint, result.state, print);
      fail("the part stopped before its last sample; {} keeps it: continue with --resume", checkpoint.string());
    }
    save_checkpoint(output, result.state, print);
    std::error_code ec;
    std::filesystem::remove(checkpoint, ec);
    std::printf("wrote %s (part: samples %d:%d of %d, merge with `prism merge`)\n", output.c_str(),
                result.state.part.sample_begin, result.state.part.sample_end, options.spp);
    return true;
  }
  const SampleCounts counts = sample_counts(film);
  const ErrorEstimate error(film, channels);
  ExrImage image = film_image(film, colorspace, balance ? &*balance : nullptr);
  image.metadata = {
      {"software", std::string("Prism " PRISM_VERSION)},
      {"prism.scene", args.scene.scene},
      {"prism.integrator", std::string(integrator(options.integrator).name)},
      {"prism.sampler", std::string(sampler_name(options.sampler))},
      {"prism.lightSampling", std::string(options.path.next_event ? "mis" : "bsdf")},
      {"prism.lightSampler", std::string(light_sampler_name(args.scene.light_sampler))},
      {"prism.spp", int(counts.max)},
      {"prism.sppMin", int(counts.min)},
      {"prism.sppMean", counts.mean},
      {"prism.sppRequested", options.spp},
      {"prism.passes", result.state.passes},
      {"prism.seconds", result.stats().seconds},
      {"prism.seed", std::to_string(options.seed)},
      {"prism.wavelengthsPerPath", options.wavelengths},
      {"prism.maxDepth", options.path.max_depth},
      {"prism.colorSpace", colorspace},
      {"prism.sceneFeatures", prepared.world->features().to_string()},
      {"prism.samples", std::to_string(result.stats().samples)},  // with the error estimate's replicates
      {"prism.invalidSamples", std::to_string(result.stats().invalid_samples)},
      {"prism.estimatedRelRmse", error.rel_rmse()},
      {"prism.estimatedRelRmseRGB", error.output_rel_rmse()},
      {"prism.interrupted", int(result.interrupted)},
  };
  if (balance) image.metadata.push_back({"prism.whiteBalance", balance->name});
  if (options.noise_threshold > 0) image.metadata.push_back({"prism.noiseThreshold", options.noise_threshold});
  if (options.time_limit > 0) image.metadata.push_back({"prism.timeLimit", options.time_limit});
  if (time) image.metadata.push_back({"prism.time", *time});
  if (camera.has_lens()) {
    image.metadata.push_back({"prism.lensRadius", double(camera.lens().radius)});
    image.metadata.push_back({"prism.focusDistance", double(camera.lens().focus_distance)});
    if (camera.lens().blades >= 3) image.metadata.push_back({"prism.apertureBlades", camera.lens().blades});
  }
  if (options.spectral_bins.count() > 0) {
    image.metadata.push_back({"spectralLayoutVersion", std::string("1.0")});
    image.metadata.push_back({"emissiveUnits", std::string("W.m^-2.sr^-1")});
  }
  // A second signal from here on removes what this run wrote, as it would have before.
  std::vector<std::unique_ptr<interrupt::RemoveOnAbort>> written;
  write_exr(output, image, args.half);
  written.push_back(std::make_unique<interrupt::RemoveOnAbort>(output));
  std::printf("wrote %s (%dx%d, %s)\n", output.c_str(), film.width(), film.height(), colorspace.c_str());

  if (!preview.empty()) {
    std::vector<float> display = film.xyz_image();
    if (balance) balance->apply(display.data(), display.size() / 3);
    ColorPipeline::standard().xyz_to_display(ColorPipeline::kDefaultDisplay, ColorPipeline::kDefaultView,
                                             display.data(), display.size() / 3);
    write_png(preview, film.width(), film.height(), display);
    written.push_back(std::make_unique<interrupt::RemoveOnAbort>(preview));
    std::printf("wrote %s (preview, %s / %s)\n", preview.c_str(), ColorPipeline::kDefaultDisplay,
                ColorPipeline::kDefaultView);
  }
  if (args.checkpoint > 0 && !complete) {
    save_checkpoint(checkpoint, result.state, print);
    std::printf("wrote %s (resume with --resume)\n", checkpoint.string().c_str());
  } else if (complete) {
    std::error_code ec;
    std::filesystem::remove(checkpoint, ec);  // the render is done: nothing to resume
  }
  written.clear();
  return !result.interrupted;
}

void run(const RenderArgs& args) {
  if (args.quiet) log::set_level(log::Level::warn);
  if (args.verbose) log::set_level(log::Level::verbose);
  interrupt::install();
  ColorPipeline::standard().canonical_name(args.colorspace);                 // a bad name fails before any work
  white_balance_option(args.white_balance);                                  // so does a bad white balance
  if (!args.spectral_bins.empty()) SpectralBins::parse(args.spectral_bins);  // and bad spectral bins
  if (args.frames.empty()) {
    check_output(args.output, "-o");
    if (!args.preview.empty()) check_output(args.preview, "--preview");
    render_image(args, prepare_scene(args.scene), args.output, args.preview, args.scene.gltf.time);
    return;
  }
  const FrameRange range = parse_frames(args.frames);
  if (!(args.fps > 0 && std::isfinite(args.fps))) fail("--fps {}: must be a positive number", args.fps);
  for (int64_t frame = range.first; frame <= range.last; ++frame) {
    check_output(frame_path(args.output, int(frame)), "-o");
    if (!args.preview.empty()) check_output(frame_path(args.preview, int(frame)), "--preview");
  }
  // Loaded at time 0, where a camera Prism places (the file has none) frames the scene for every
  // frame: a frame's image depends on its number alone, never on the range that renders it (so
  // the parts of a farmed frame merge into the frame of this sequence). The world is built at
  // the first frame's pose.
  SceneArgs scene_args = args.scene;
  scene_args.gltf.time = 0;
  PreparedScene prepared = prepare_scene(scene_args, true);
  if (!prepared.gltf->animated()) log::warn("{}: nothing is animated; every frame is the same image", args.scene.scene);
  const auto t0 = std::chrono::steady_clock::now();
  for (int64_t frame = range.first; frame <= range.last; ++frame) {
    const double time = frame / args.fps;
    log::info("frame {} ({} of {}) at {:.4f} s", frame, frame - range.first + 1, range.last - range.first + 1, time);
    if (!pose_scene(prepared, scene_args, time)) log::verbose("nothing moved: same world");
    if (!render_image(args, prepared, frame_path(args.output, int(frame)),
                      args.preview.empty() ? "" : frame_path(args.preview, int(frame)), time)) {
      log::warn("interrupted: frames after {} not rendered", frame);
      return;
    }
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
  add_render_options(cmd, args->options, args->integrator);
  cmd->add_option("--noise-threshold", args->options.noise_threshold,
                  "Adaptive sampling: a pixel stops when its estimated error is below T (README); --spp is then "
                  "the maximum")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--time-limit", args->options.time_limit,
                  "Stop after the pass that reaches SECONDS of rendering (the header records the samples taken)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--checkpoint", args->checkpoint,
                  "Keep a resumable state file OUTPUT.checkpoint, rewritten every SECONDS (and on interruption)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--resume", args->resume,
                "Continue the render saved in OUTPUT.checkpoint (same scene and options; --spp may grow)");
  cmd->add_option("--aov", args->aovs,
                  "Extra EXR layers, comma-separated: albedo (albedo.R/G/B), normal (N.X/Y/Z), depth (Z), "
                  "variance (variance.Y), spp");
  cmd->add_option("--spectral-bins", args->spectral_bins,
                  "Also write spectral radiance: N equal bins over 360-830 nm, or comma-separated edges in nm "
                  "(channels S0.<nm>nm, OpenEXR spectral layout)");
  cmd->add_option("--samples", args->samples,
                  "Render only sample indices A to B-1 (A:B) of the --spp render, into a part file OUTPUT for "
                  "`prism merge` (README: splitting a render)");
  cmd->add_option("--crop", args->crop,
                  "Render only the pixels x0..x1-1, y0..y1-1 (x0,y0,x1,y1) of the frame, into a part file OUTPUT "
                  "for `prism merge`");
  cmd->add_option("--colorspace", args->colorspace, "Output colour space from data/ocio/config.ocio")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_option("--preview", args->preview, "Also write an sRGB preview PNG through the OCIO display view");
  cmd->add_option("--white-balance", args->white_balance,
                  "Adapt the image so that this illuminant's white is neutral (Bradford): a named illuminant (A, "
                  "D50, F11, LED-B3, ...), a temperature in kelvin, or none (scene-referred)")
      ->default_val("none");
  cmd->add_flag("--half", args->half, "Write 16-bit half floats instead of 32-bit floats (beauty only)");
  cmd->add_flag("-q,--quiet", args->quiet, "Only warnings and errors; no progress bar");
  cmd->add_flag("-v,--verbose", args->verbose, "Also log every pass with its estimated error");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
