#include "apps/prism/scene_setup.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <limits>

#include "core/base/clock.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/number_list.h"
#include "core/render/environment_map.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/spectrum_input.h"
#include "spectral/cie.h"

namespace prism {

namespace {

Rgb parse_rgb(const std::string& text, const char* what) {
  const std::vector<double> v = parse_numbers(text, what);
  if (v.size() != 3) fail("{} '{}': expected three numbers R,G,B", what, text);
  for (const double c : v)
    if (c < 0 || c > kMaxEmission)
      fail("{} '{}': values must be finite, non-negative and at most {:g}", what, text, kMaxEmission);
  return Rgb{float(v[0]), float(v[1]), float(v[2])};
}

// --fog SIGMA_S[,SIGMA_A[,G]]: a grey medium around everything; "0": none (vacuum).
std::optional<Medium> parse_fog(const std::string& text) {
  const std::vector<double> v = parse_numbers(text, "--fog");
  if (v.empty() || v.size() > 3) fail("--fog '{}': expected SIGMA_S[,SIGMA_A[,G]]", text);
  for (size_t i = 0; i < std::min<size_t>(v.size(), 2); ++i)
    if (!(v[i] >= 0 && v[i] <= 1e30))
      fail("--fog '{}': the coefficients must be finite and non-negative (per metre)", text);
  if (v.size() == 3 && !(std::abs(v[2]) < 1)) fail("--fog '{}': the asymmetry G must lie in (-1, 1)", text);
  Medium fog;
  if (v[0] > 0) fog.sigma_s = ConstantSpectrum{float(v[0])};
  if (v.size() > 1 && v[1] > 0) fog.sigma_a = ConstantSpectrum{float(v[1])};
  if (v.size() == 3) fog.phase.g = float(v[2]);
  if (fog.empty()) return std::nullopt;
  return fog;
}

uint64_t max_memory_bytes(const SceneArgs& args) {
  if (args.max_memory_gb > 0) return uint64_t(std::min(args.max_memory_gb * 1e9, 1.8e19));
  return uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
}

CameraDesc choose_camera(const Scene& scene, const SceneArgs& args) {
  if (args.camera >= 0) {
    if (size_t(args.camera) >= scene.cameras.size())
      fail("{}: --camera {} requested, but the scene has {} camera(s)", scene.source.string(), args.camera,
           scene.cameras.size());
    return scene.cameras[args.camera];
  }
  if (!scene.cameras.empty()) return scene.cameras[0];
  const float aspect = args.width > 0 && args.height > 0 ? float(args.width) / float(args.height) : 1.f;
  log::info("{}: no camera in the scene; using a camera that frames the whole scene", scene.source.string());
  return framing_camera(scene.world_bounds(), aspect);
}

}  // namespace

const CLI::Validator& positive_count() {
  static const CLI::Validator v = CLI::Range(1, std::numeric_limits<int>::max());
  return v;
}

const CLI::Validator& seed_value() {
  static const CLI::Validator v(
      [](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        std::strtoull(text.c_str(), &end, 10);
        if (!digits || errno == ERANGE || *end) return "a seed is an integer from 0 to 18446744073709551615";
        return {};
      },
      "UINT64");
  return v;
}

CLI::Validator integrator_validator(bool automatic) {
  return CLI::Validator(
      [automatic](std::string& name) -> std::string {
        if ((automatic && name == "auto") || find_integrator(name)) return {};
        return fmt::format("unknown integrator '{}': choose from {}{}", name, automatic ? "auto, " : "",
                           integrator_names());
      },
      "INTEGRATOR");
}

IntegratorKind resolve_integrator(const std::string& name, const World& world, const RenderOptions& options) {
  if (name != "auto") return find_integrator(name)->kind;
  // A crop window is a part of a whole render, whose parts must all choose alike: it does not
  // change the choice, and a tile of an integrator that renders the whole frame at once is refused.
  const bool per_pixel = options.noise_threshold > 0 || options.spectral_bins.count() > 0;
  const IntegratorChoice choice = choose_integrator(world.features(), per_pixel);
  const Integrator& chosen = integrator(choice.kind);
  if (!options.crop.empty() && !chosen.per_pixel())
    fail(
        "--crop: for this scene --integrator auto chooses {} ({}), which renders the whole frame at once; render "
        "tiles with --integrator path",
        chosen.name, choice.reason);
  log::info("integrator: {} (auto: {})", chosen.name, choice.reason);
  return choice.kind;
}

const char* sampler_name(SamplerKind kind) { return kind == SamplerKind::independent ? "independent" : "sobol"; }

void add_scene_options(CLI::App* cmd, SceneArgs& args) {
  cmd->add_option("scene", args.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("--width", args.width,
                  "Image width in pixels (default: 640, or from --height and the camera's aspect)")
      ->check(positive_count());
  cmd->add_option("--height", args.height, "Image height in pixels (default: from the width and the camera's aspect)")
      ->check(positive_count());
  cmd->add_option("--camera", args.camera, "Use the N-th camera in scene order (0-based; default: the first)")
      ->check(CLI::NonNegativeNumber);
  add_lens_options(cmd, args.lens);
  add_gltf_options(cmd, args.gltf);
  CLI::Option* env =
      cmd->add_option("--env", args.env, "Constant environment radiance as linear Rec.709 R,G,B (e.g. 1,1,1)");
  CLI::Option* env_map =
      cmd->add_option("--env-map", args.env_map,
                      "Environment image: equirectangular .exr or .hdr of linear Rec.709 radiance, +Y up")
          ->excludes(env);
  cmd->add_option("--env-rotate", args.env_rotate, "Rotate the environment image about +Y by DEG degrees")
      ->needs(env_map);
  cmd->add_option("--env-scale", args.env_scale, "Multiply the environment image by S")
      ->needs(env_map)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--env-spectrum", args.env_spectrum,
                  "The spectrum of the environment's white (--env or --env-map): a named illuminant (e.g. A, D50, "
                  "F11, LED-B3), blackbody:KELVIN, or a CSV file of nm,value (default: D65)");
  cmd->add_option("--fog", args.fog,
                  "Fill the space around the scene's objects with a grey medium: SIGMA_S[,SIGMA_A[,G]], scattering "
                  "and absorption per metre and the phase function's asymmetry in (-1, 1) (default 0: isotropic); "
                  "0 clears the scene's own");
  cmd->add_option("--max-memory", args.max_memory_gb,
                  "Refuse scenes and images estimated to need more than GB gigabytes (default: physical memory)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("!--no-energy-compensation", args.energy_compensation,
                "Leave out the light scattered more than once between microfacets (as single-scattering "
                "renderers do)");
  std::map<std::string, LightSamplerKind> samplers;
  std::string help = "How next-event estimation chooses a light for a point";
  for (const LightSamplerInfo& l : kLightSamplers) {
    samplers.emplace(std::string(l.name), l.kind);
    help += fmt::format("; {}: {}", l.name, l.description);
  }
  cmd->add_option("--light-sampler", args.light_sampler, help)
      ->transform(CLI::CheckedTransformer(samplers))
      ->default_str(std::string(light_sampler_name(kDefaultLightSampler)));
}

void add_lens_options(CLI::App* cmd, LensDesc& lens) {
  const auto positive = CLI::Range(1e-30, 1e30);
  CLI::Option* aperture =
      cmd->add_option("--aperture", lens.f_number,
                      "Depth of field: the aperture as an f-number (e.g. 2.8), of the focal length the field of view "
                      "makes on a --sensor-width film")
          ->check(positive);
  cmd->add_option("--sensor-width", lens.sensor_width, "The film's width in millimetres, for --aperture (default 36)")
      ->check(positive)
      ->needs(aperture);
  cmd->add_option("--lens-radius", lens.radius, "Depth of field: the lens radius in scene units (metres)")
      ->check(CLI::Range(0.0, 1e30))
      ->excludes(aperture);
  CLI::Option* distance =
      cmd->add_option("--focus-distance", lens.focus_distance,
                      "The plane in focus, this far along the view axis (default: through the centre of the scene)")
          ->check(positive);
  cmd->add_option("--focus-node", lens.focus_node, "Focus on the plane through this node's origin")->excludes(distance);
  cmd->add_option("--blades", lens.blades, "A polygonal aperture of N blades (0: round, the default)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--blade-rotation", lens.blade_rotation, "Turn the aperture polygon by DEG degrees")
      ->check(CLI::Range(-1e6, 1e6));
}

void add_gltf_options(CLI::App* cmd, GltfOptions& options) {
  cmd->add_option("--scene", options.scene,
                  "Render the file's N-th scene (0-based; default: the file's `scene`, else 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--variant", options.variant, "KHR_materials_variants: use the material variant NAME");
  cmd->add_option("--time", options.time, "Pose the animation at SECONDS (default: the file's own pose)");
  cmd->add_option("--animation", options.animation,
                  "The animation --time and --frames play: a name, a 0-based index, or all (every animation at "
                  "once; default: the first, as viewers play a file)");
  cmd->add_flag("--allow-external-paths", options.allow_external_paths,
                "Let the scene's URIs name files outside its folder (off: such files are refused)");
}

void add_render_options(CLI::App* cmd, RenderOptions& options, std::string& integrator) {
  cmd->add_option("--spp", options.spp, "Samples per pixel")->default_val(16)->check(positive_count());
  cmd->add_option("--seed", options.seed, "Random seed: the same seed gives the same image")
      ->default_val(0)
      ->check(seed_value());
  cmd->add_option("--threads", options.threads, "Worker threads (0: all cores)")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-depth", options.path.max_depth, "Maximum path length in bounces")
      ->default_val(16)
      ->check(CLI::NonNegativeNumber);
  std::string help =
      "auto: the one the scene needs (vcm for caustics through closed glass lit from inside the scene, "
      "else path)";
  for (const Integrator& i : integrators()) help += fmt::format("; {}: {}", i.name, i.description);
  cmd->add_option("--integrator", integrator, help)->check(integrator_validator(true))->default_val("auto");
  cmd->add_option("--merge-radius", options.merge_radius,
                  "vcm: initial photon merging radius in scene units (default: 0.005 x the scene's bounding radius)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--wavelengths", options.wavelengths, "Wavelengths carried per path (1, 4 or 8)")
      ->default_val(kDefaultWavelengths)
      ->check(CLI::IsMember({1, 4, 8}));
  cmd->add_option(
         "--sampler", options.sampler,
         "sobol: Owen-scrambled Sobol (0,2)-sequence, every dimension stratified over a pixel's samples at any "
         "count; independent: uniform random numbers")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, SamplerKind>{{"independent", SamplerKind::independent}, {"sobol", SamplerKind::sobol}}))
      ->default_str("sobol");
  cmd->add_option_function<std::string>(
         "--light-sampling", [&options](const std::string& v) { options.path.next_event = v == "mis"; },
         "mis: next-event estimation combined with BSDF sampling by MIS; bsdf: BSDF sampling only")
      ->check(CLI::IsMember({"mis", "bsdf"}))
      ->default_str("mis");
}

namespace {

// Each lens setting the command line gives, over the camera's own.
void over(LensDesc& lens, const LensDesc& given) {
  if (given.f_number) lens.f_number = given.f_number, lens.radius.reset();
  if (given.radius) lens.radius = given.radius, lens.f_number.reset();
  if (given.sensor_width) lens.sensor_width = given.sensor_width;
  if (given.focus_distance) lens.focus_distance = given.focus_distance, lens.focus_node.reset();
  if (given.focus_node) lens.focus_node = given.focus_node, lens.focus_distance.reset();
  if (given.blades) lens.blades = given.blades;
  if (given.blade_rotation) lens.blade_rotation = given.blade_rotation;
}

// The camera for the scene as posed: the file's (which may move), or one framing the scene, which
// stays as the first pose framed it.
void place_camera(PreparedScene& p, const SceneArgs& args) {
  const Scene& scene = p.gltf->scene();
  if (!p.camera || !scene.cameras.empty()) {
    CameraDesc camera_desc = choose_camera(scene, args);
    over(camera_desc.lens, args.lens);
    const Vec2i size = resolve_resolution(args.width, args.height, camera_desc);
    const uint64_t max_memory = max_memory_bytes(args);
    if (uint64_t(size.x) * uint64_t(size.y) > max_memory / kBytesPerPixel)
      fail("{}: a {}x{} image needs about {:.3g} GB, more than --max-memory {:.3g} GB", args.scene, size.x, size.y,
           double(size.x) * size.y * kBytesPerPixel / 1e9, max_memory / 1e9);
    const bool first = !p.camera;
    p.camera = std::make_unique<Camera>(camera_desc, size.x, size.y, thin_lens(camera_desc, scene, size));
    if (first && p.camera->has_lens()) {
      const ThinLens& l = p.camera->lens();
      log::info("depth of field: lens radius {:.4g}, in focus at {:.4g} along the view axis{}", l.radius,
                l.focus_distance, l.blades >= 3 ? fmt::format(", {} blades", l.blades) : std::string());
    }
  }
}

void build_world(PreparedScene& p, const SceneArgs& args) {
  const bool first = !p.world;
  const auto t0 = std::chrono::steady_clock::now();
  p.world.reset();
  p.world = std::make_unique<World>(p.gltf->scene(), AccelOptions{}, args.light_sampler);
  log::info("scene features: {}", p.world->features().to_string());
  log::info("built the BVH over {} triangles in {:.0f} ms ({:.1f} MB)", p.world->accel().triangle_count(),
            1e3 * seconds_since(t0), p.world->accel().memory_bytes() / 1e6);
  if (const LightTree* tree = p.world->light_sampler().tree())
    log::info("light tree: {} nodes over {} lights ({:.1f} MB)", tree->node_count(), p.world->lights().size(),
              tree->memory_bytes() / 1e6);
  if (first && p.world->lights().empty())
    log::warn("{}: the scene has no lights (the image will be black); light it with --env R,G,B", args.scene);
}

}  // namespace

bool pose_scene(PreparedScene& p, const SceneArgs& args, double seconds) {
  if (!p.gltf->pose(seconds) && p.world) return false;
  place_camera(p, args);
  build_world(p, args);  // the accel copies what moved
  return true;
}

PreparedScene prepare_scene(const SceneArgs& args, bool keep_file) {
  std::optional<Rgb> env;
  if (!args.env.empty()) env = parse_rgb(args.env, "--env");
  const std::optional<Medium> fog = args.fog.empty() ? std::nullopt : parse_fog(args.fog);
  cie();  // fail early if the data files are missing
  std::optional<EnvironmentMapDesc> env_map;
  if (!args.env_map.empty()) {
    env_map = load_environment_map(args.env_map, args.env_rotate, args.env_scale);
    log::info("environment map {}: {}x{}", env_map->file, env_map->image.width, env_map->image.height);
  }

  // The environment's white: the spectrum of RGB (1, 1, 1), at luminance 1.
  std::optional<DenselySampledSpectrum> white;
  if (!args.env_spectrum.empty()) {
    if (!env && !env_map) fail("--env-spectrum {}: needs --env or --env-map", args.env_spectrum);
    white = densely_sampled(spectrum_with_luminance(
        parse_spectrum_argument(args.env_spectrum, SpectrumUse::emission, "--env-spectrum"), 1.0));
  }
  if (env_map) env_map->white = white;

  PreparedScene p;
  auto t0 = std::chrono::steady_clock::now();
  GltfOptions gltf = args.gltf;
  gltf.max_instances = max_memory_bytes(args) / kBytesPerInstance;
  p.gltf = std::make_unique<GltfScene>(args.scene, gltf);
  Scene& scene = p.gltf->scene();
  if (env) {
    if (white)  // the colour's shape over the white, at every nm (the world reads it so anyway)
      scene.environment = densely_sampled(RgbIlluminantSpectrum(*env, &*white));
    else
      scene.environment = RgbIlluminantSpectrum(*env);
  }
  scene.environment_map = std::move(env_map);
  if (!args.fog.empty()) scene.medium = fog;
  if (!args.energy_compensation)
    for (Material& m : scene.materials)
      if (auto* pbr = std::get_if<PbrMaterial>(&m.kind)) pbr->energy_compensation = false;
  log::info(
      "loaded {} in {:.2f} s: {} triangles in {} instances, {} materials, {} point, {} spot and {} "
      "directional lights",
      args.scene, seconds_since(t0), scene.triangle_count(), scene.instances.size(), scene.materials.size(),
      scene.point_lights.size(), scene.spot_lights.size(), scene.directional_lights.size());
  if ((args.gltf.time || !args.gltf.animation.empty()) && !p.gltf->animated())
    log::info("{}: nothing is animated; --time and --animation change nothing", args.scene);
  place_camera(p, args);
  if (!keep_file) {
    p.gltf->close();
    build_world(p, args);
  }
  return p;
}

}  // namespace prism
