// `prism converge SCENE --reference REF.exr --out DIR`: the error of several rendering
// configurations against a reference image as their sample budgets double, written as
// DIR/convergence.csv, DIR/convergence.png (error against seconds, log-log) and DIR/summary.md
// (the time each configuration needs to reach a stated error). With --seconds S, each renders
// for S seconds instead and DIR/equal_time.csv and DIR/summary.md compare their errors then.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include "apps/prism/commands.h"
#include "apps/prism/image_errors.h"
#include "apps/prism/plot.h"
#include "apps/prism/scene_setup.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

struct ConvergeArgs {
  SceneArgs scene;
  std::string reference, out;
  int max_spp = 256, reference_spp = 4096, max_depth = 16, threads = 0;
  uint64_t seed = 0;
  std::vector<std::string> integrators;     // one configuration each (default: the baseline and its variations)
  std::vector<std::string> light_samplers;  // or one configuration each, path traced
  std::string reference_integrator = "path";
  double seconds = 0;     // equal-time comparison: each configuration renders this long
  bool relative = false;  // the error to reach: relative MSE's root instead of RMSE
};

struct Configuration {
  std::string name;
  RenderOptions options;
  std::optional<LightSamplerKind> light_sampler = std::nullopt;  // the scene options' if none
};

// The baseline (the defaults: path tracing, 8 wavelengths, NEE + MIS, Sobol samples) and one change
// of it per question the report answers.
std::vector<Configuration> configurations(const ConvergeArgs& args) {
  RenderOptions base;
  base.path.max_depth = args.max_depth;
  base.threads = args.threads;
  base.seed = args.seed;
  base.progress = false;
  if (!args.light_samplers.empty()) {
    std::vector<Configuration> c;
    for (const std::string& name : args.light_samplers)
      c.push_back({"path, light sampler " + name, base, find_light_sampler(name)->kind});
    return c;
  }
  if (!args.integrators.empty()) {
    std::vector<Configuration> c;
    for (const std::string& name : args.integrators) {
      c.push_back({name, base});
      c.back().options.integrator = find_integrator(name)->kind;
    }
    return c;
  }
  std::vector<Configuration> c(5, {"", base});
  c[0].name = "path, 8 wavelengths, NEE+MIS, Sobol";
  c[1].name = "1 wavelength per path";
  c[1].options.wavelengths = 1;
  c[2].name = "4 wavelengths per path";
  c[2].options.wavelengths = 4;
  c[3].name = "BSDF sampling only";
  c[3].options.path.next_event = false;
  c[4].name = "independent sampler";
  c[4].options.sampler = SamplerKind::independent;
  for (const Integrator& i : integrators())  // and every other integrator that renders images
    if (i.kind != base.integrator && !i.check_only) {
      c.push_back({std::string(i.name), base});
      c.back().options.integrator = i.kind;
    }
  return c;
}

// The scene made ready with each light sampler a configuration asks for (the scene options' is p's).
class Worlds {
 public:
  Worlds(const PreparedScene& p, const SceneArgs& args) : p_(p), args_(args) {}
  const World& operator()(const Configuration& c) {
    if (!c.light_sampler || *c.light_sampler == args_.light_sampler) return *p_.world;
    auto& w = made_[*c.light_sampler];
    if (!w) w = std::make_unique<World>(p_.gltf->scene(), AccelOptions{}, *c.light_sampler);
    return *w;
  }

 private:
  const PreparedScene& p_;
  const SceneArgs& args_;
  std::map<LightSamplerKind, std::unique_ptr<World>> made_;
};

std::vector<float> render_rgb(const World& world, const PreparedScene& p, const RenderOptions& options,
                              RenderStats* stats = nullptr) {
  const RenderResult r = render(world, *p.camera, options);
  std::vector<float> rgb = r.state.film.xyz_image();
  ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, rgb.data(), rgb.size() / 3);
  if (stats) *stats = r.stats();
  return rgb;
}

std::vector<float> reference_image(const ConvergeArgs& args, const PreparedScene& p) {
  const Camera& camera = *p.camera;
  if (std::filesystem::exists(args.reference)) {
    RgbImage ref = read_exr(args.reference);
    if (ref.width != camera.width() || ref.height != camera.height())
      fail("{}: the reference is {}x{}, the renders {}x{} (set --width/--height to match)", args.reference, ref.width,
           ref.height, camera.width(), camera.height());
    log::info("reference {} ({}x{})", args.reference, ref.width, ref.height);
    return ref.rgb;
  }
  RenderOptions options = configurations(args)[0].options;
  options.integrator = find_integrator(args.reference_integrator)->kind;
  options.spp = args.reference_spp;
  options.progress = true;
  options.seed = args.seed + 1;  // independent of the series' noise
  log::info("rendering the reference {} at {} spp ({})", args.reference, args.reference_spp, args.reference_integrator);
  RenderStats stats;
  std::vector<float> rgb = render_rgb(*p.world, p, options, &stats);
  write_exr(args.reference,
            {camera.width(),
             camera.height(),
             rgb,
             ColorPipeline::standard().chromaticities(ColorPipeline::kDefaultOutput),
             {{"software", std::string("Prism " PRISM_VERSION)},
              {"prism.spp", args.reference_spp},
              {"prism.seconds", stats.seconds}}},
            false);
  return rgb;
}

struct Point {
  int spp;
  double seconds;
  ImageErrors e;
  double error;  // the one the summary compares: RMSE, or the root of the relative MSE
};

// Seconds to reach an error of `target`, interpolating log(seconds) against log(error) between
// budgets; nothing if the series never gets there.
std::optional<double> time_to_reach(const std::vector<Point>& series, double target) {
  for (size_t i = 0; i < series.size(); ++i) {
    if (series[i].error > target) continue;
    if (i == 0) return series[0].seconds;
    const Point &a = series[i - 1], &b = series[i];
    const double t = (std::log(target) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    return std::exp(std::log(a.seconds) + t * (std::log(b.seconds) - std::log(a.seconds)));
  }
  return std::nullopt;
}

// MSE of the largest budget over that of the one before: 1/2 for an unbiased estimator, whose
// variance halves with each doubling of spp; near 1 once the error is bias.
double mse_per_doubling(const std::vector<Point>& series) {
  if (series.size() < 2) return 0.5;
  const double r = series.back().error / series[series.size() - 2].error;
  return r * r;
}

// Each configuration for args.seconds, its error then: relative RMSE (RMSE over the reference's
// mean), also scaled to exactly args.seconds (an unbiased estimator's MSE falls as 1 / time), and
// which configuration to use for this scene.
void run_equal_time(const ConvergeArgs& args, const PreparedScene& p, const std::vector<float>& reference,
                    double reference_mean) {
  const auto configs = configurations(args);
  Worlds worlds(p, args.scene);
  for (const Configuration& config : configs) worlds(config);  // built before any timing
  RenderOptions warm_up = configs[0].options;
  warm_up.spp = 1;
  render_rgb(worlds(configs[0]), p, warm_up);  // untimed: one-time set-up (tables, threads) is no configuration's cost
  std::ofstream csv(std::filesystem::path(args.out) / "equal_time.csv");
  csv << "configuration,seconds,spp,relative_rmse,relative_rmse_at_budget,mean_error\n";
  const double pixels = double(p.camera->width()) * p.camera->height();
  std::vector<double> scaled;
  std::ofstream md(std::filesystem::path(args.out) / "summary.md");
  md << "# Equal time: " << std::filesystem::path(args.scene.scene).filename().string() << "\n\n"
     << "Image " << p.camera->width() << "x" << p.camera->height() << ", " << args.seconds
     << " s per configuration, reference `" << args.reference << "` (mean " << reference_mean << "), max depth "
     << args.max_depth << ". Relative RMSE: RMSE over all pixels and channels (linear Rec.709) over the "
     << "reference's mean; at budget: scaled by sqrt(seconds / " << args.seconds << ").\n\n"
     << "| configuration | seconds | samples per pixel | relative RMSE | at budget | x " << configs[0].name
     << " | mean error |\n|---|---|---|---|---|---|---|\n";
  for (const Configuration& config : configs) {
    RenderOptions options = config.options;
    options.spp = 1 << 20;
    options.time_limit = args.seconds;
    RenderStats stats;
    const ImageErrors e = image_errors(render_rgb(worlds(config), p, options, &stats), reference);
    const double relative = e.rmse / reference_mean;
    scaled.push_back(relative * std::sqrt(stats.seconds / args.seconds));
    const double spp = double(stats.samples) / pixels;
    csv << '"' << config.name << "\"," << stats.seconds << ',' << spp << ',' << relative << ',' << scaled.back() << ','
        << e.mean_error << '\n';
    log::info("{:<44} {:>8.3f} s {:>8.1f} spp  relative RMSE {:.4f} ({:.4f} at budget)  mean error {:+.5f}",
              config.name, stats.seconds, spp, relative, scaled.back(), e.mean_error);
    md << "| " << config.name << " | " << fmt::format("{:.1f}", stats.seconds) << " | " << fmt::format("{:.0f}", spp)
       << " | " << fmt::format("{:.4f}", relative) << " | " << fmt::format("{:.4f}", scaled.back()) << " | "
       << fmt::format("{:.3f}", scaled.back() / scaled[0]) << " | " << fmt::format("{:+.3g}", e.mean_error) << " |\n";
  }
  const size_t best = size_t(std::min_element(scaled.begin(), scaled.end()) - scaled.begin());
  md << "\nUse **" << configs[best].name << "** for this scene: the lowest error in " << args.seconds << " s ("
     << fmt::format("{:.3f}", scaled[best] / scaled[0]) << "x the error of " << configs[0].name << ").\n";
  std::printf("wrote %s/equal_time.csv, summary.md\n", args.out.c_str());
}

void run(const ConvergeArgs& args) {
  const PreparedScene p = prepare_scene(args.scene);
  std::filesystem::create_directories(args.out);
  const std::vector<float> reference = reference_image(args, p);
  double reference_mean = 0;
  for (float v : reference) reference_mean += v;
  reference_mean /= double(reference.size());
  if (args.seconds > 0) return run_equal_time(args, p, reference, reference_mean);

  std::ofstream csv(std::filesystem::path(args.out) / "convergence.csv");
  csv << "configuration,spp,seconds,rmse,relative_mse,mean_error\n";
  std::vector<std::vector<Point>> series;
  const auto configs = configurations(args);
  Worlds worlds(p, args.scene);
  for (const Configuration& config : configs) worlds(config);  // built before any timing
  render_rgb(worlds(configs[0]), p,
             configs[0].options);  // untimed: one-time set-up (tables, threads) is no configuration's cost
  for (const Configuration& config : configs) {
    series.emplace_back();
    for (int spp = 1; spp <= args.max_spp; spp *= 2) {
      RenderOptions options = config.options;
      options.spp = spp;
      RenderStats stats;
      const ImageErrors e = image_errors(render_rgb(worlds(config), p, options, &stats), reference);
      series.back().push_back({spp, stats.seconds, e, args.relative ? std::sqrt(e.relative_mse) : e.rmse});
      csv << '"' << config.name << "\"," << spp << ',' << stats.seconds << ',' << e.rmse << ',' << e.relative_mse << ','
          << e.mean_error << '\n';
      log::info("{:<44} {:>5} spp {:>8.3f} s  RMSE {:.5f}  relMSE {:.3e}  mean error {:+.5f}", config.name, spp,
                stats.seconds, e.rmse, e.relative_mse, e.mean_error);
    }
  }
  csv.close();

  const std::string error_name = args.relative ? "relative RMSE" : "RMSE";
  Plot plot{error_name + " against render time", "seconds", error_name, true, true, {}};
  for (size_t c = 0; c < configs.size(); ++c) {
    PlotSeries s{configs[c].name, {}, {}};
    for (const Point& pt : series[c]) s.x.push_back(pt.seconds), s.y.push_back(pt.error);
    plot.series.push_back(std::move(s));
  }
  write_plot_png(std::filesystem::path(args.out) / "convergence.png", plot);

  // The stated error: what the baseline reaches with its largest budget.
  const double target = series[0].back().error;
  std::ofstream md(std::filesystem::path(args.out) / "summary.md");
  md << "# Convergence: " << std::filesystem::path(args.scene.scene).filename().string() << "\n\n"
     << "Image " << p.camera->width() << "x" << p.camera->height() << ", reference `" << args.reference << "`"
     << " (mean " << reference_mean << "), max depth " << args.max_depth << ", budgets 1 to " << args.max_spp
     << " spp. Error: "
     << (args.relative ? "relative RMSE, the root of the mean over all pixels and channels (linear Rec.709) of "
                         "d² / (reference² + 0.01)"
                       : "RMSE over all pixels and channels (linear Rec.709)")
     << ".\n\n"
     << "Stated error: " << error_name << " " << target << " (the baseline at " << args.max_spp << " spp).\n\n"
     << "| configuration | seconds to reach it | speed-up over the baseline | " << error_name << " at " << args.max_spp
     << " spp | mean error at " << args.max_spp << " spp | MSE per doubling of spp |\n|---|---|---|---|---|---|\n";
  const auto baseline_time = time_to_reach(series[0], target);
  for (size_t c = 0; c < configs.size(); ++c) {
    const auto t = time_to_reach(series[c], target);
    const Point& last = series[c].back();
    const double doubling = mse_per_doubling(series[c]);
    const bool biased = doubling > 0.8 || std::abs(last.e.mean_error) > 0.02 * reference_mean;
    md << "| " << configs[c].name << " | " << (t ? fmt::format("{:.3g}", *t) : std::string("not reached")) << " | "
       << (t && baseline_time && !biased ? fmt::format("{:.2f}x", *baseline_time / *t) : std::string("-")) << " | "
       << fmt::format("{:.4g}", last.error) << " | " << fmt::format("{:+.3g}", last.e.mean_error) << " | "
       << fmt::format("x{:.2f}{}", doubling, biased ? " (biased)" : "") << " |\n";
  }
  md << "\nAn unbiased configuration's MSE halves with each doubling of the sample budget (x0.50). One whose MSE "
        "stops falling (above x0.80), or whose mean error exceeds 2% of the image mean, is biased for this scene (the "
        "Whitted tracer omits "
        "indirect diffuse light and rough reflection), and its time to an error it only passes on the way to its "
        "bias is no speed-up.\n";
  md.close();
  std::printf("wrote %s/convergence.csv, convergence.png, summary.md\n", args.out.c_str());
}

}  // namespace

void add_converge_command(CLI::App& app) {
  auto args = std::make_shared<ConvergeArgs>();
  CLI::App* cmd =
      app.add_subcommand("converge", "Error against render time of several configurations, against a reference image");
  add_scene_options(cmd, args->scene);
  cmd->add_option("--reference", args->reference,
                  "Reference OpenEXR (linear Rec.709, same size); rendered at --reference-spp and written if absent")
      ->required();
  cmd->add_option("--out", args->out, "Folder for convergence.csv, convergence.png and summary.md")->required();
  cmd->add_option("--max-spp", args->max_spp, "Largest sample budget (budgets double from 1)")
      ->default_val(256)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--reference-spp", args->reference_spp, "Samples per pixel of a reference this command renders")
      ->default_val(4096)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-depth", args->max_depth, "Maximum path length in bounces")
      ->default_val(16)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")->default_val(0);
  cmd->add_option("--integrators", args->integrators,
                  "Compare these integrators (comma-separated names, e.g. path,bdpt,vcm) instead of the "
                  "baseline and its variations")
      ->delimiter(',')
      ->check(integrator_validator(false));
  std::string samplers;
  for (const LightSamplerInfo& l : kLightSamplers) samplers += (samplers.empty() ? "" : ", ") + std::string(l.name);
  CLI::Option* light_samplers =
      cmd->add_option("--light-samplers", args->light_samplers,
                      "Compare these light samplers (comma-separated: " + samplers + "), path traced, instead")
          ->delimiter(',')
          ->check([](const std::string& name) {
            return find_light_sampler(name) ? std::string() : fmt::format("unknown light sampler '{}'", name);
          });
  light_samplers->excludes(cmd->get_option("--integrators"));
  cmd->add_option("--reference-integrator", args->reference_integrator,
                  "Integrator of a reference this command renders (vcm for caustics)")
      ->default_val("path")
      ->check(integrator_validator(false));
  cmd->add_option("--seconds", args->seconds,
                  "Equal time: render each configuration this many seconds and compare the errors")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", args->seed, "Random seed")->default_val(0)->check(seed_value());
  cmd->add_option_function<std::string>(
         "--error", [args](const std::string& e) { args->relative = e == "relative"; },
         "The error whose time to reach the summary compares: rmse (over all pixels and channels; bright pixels "
         "weigh most) or relative (each pixel's error over its reference value, the root of the relative MSE: dark "
         "and bright pixels weigh alike)")
      ->default_str("rmse")
      ->check(CLI::IsMember({"rmse", "relative"}))
      ->excludes(cmd->get_option("--seconds"));
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
