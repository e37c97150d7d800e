// `prism fresnel`: reflectance of catalogue materials, or of an n,k pair or index, versus angle
// and wavelength (exact Fresnel equations), the colour of metals at 0° and 60° in an output
// colour space, and a plot of R(λ).

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/prism/commands.h"
#include "apps/prism/plot.h"
#include "core/base/error.h"
#include "core/base/number_list.h"
#include "core/scene/refractive_index_file.h"
#include "materials/catalogue.h"
#include "materials/fresnel.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"

namespace prism {

namespace {

struct FresnelArgs {
  std::vector<std::string> materials, nk_files;
  std::string nk, wavelengths = "450,550,650", angles = "0,45,60,80,89", format = "table", plot;
  std::string colorspace = ColorPipeline::kDefaultOutput;
};

// A material as the command sees it: R (with Rs, Rp) at an angle and wavelength, in air.
struct Reflector {
  std::string label;
  std::function<FresnelReflectance(float cos_theta, float lambda)> reflectance;
  bool metal;
};

std::vector<float> parse_list(const std::string& text, const char* option) {
  std::vector<float> values = parse_floats(text, option);
  if (values.empty()) fail("{} needs at least one number", option);
  return values;
}

std::vector<Reflector> reflectors(const FresnelArgs& args) {
  std::vector<Reflector> out;
  const MaterialCatalogue& catalogue = MaterialCatalogue::standard();
  for (const std::string& key : args.materials) {
    if (catalogue.entry(key).metal) {
      const MeasuredMetal m = catalogue.metal(key);
      out.push_back(
          {key, [m](float c, float l) { return fresnel_conductor_polarized(c, evaluate(m.n, l), evaluate(m.k, l)); },
           true});
    } else {
      const IorModel ior_model = catalogue.dielectric(key);
      out.push_back(
          {key, [ior_model](float c, float l) { return fresnel_dielectric_polarized(c, ior(ior_model, l)); }, false});
    }
  }
  if (!args.nk.empty()) {
    const auto nk = parse_list(args.nk, "--nk");
    if (nk.size() != 2 || nk[0] < 0 || nk[1] < 0) fail("--nk '{}': expected two non-negative numbers N,K", args.nk);
    out.push_back({fmt::format("n={:g} k={:g}", nk[0], nk[1]),
                   [n = nk[0], k = nk[1]](float c, float) { return fresnel_conductor_polarized(c, n, k); }, nk[1] > 0});
  }
  for (const std::string& file : args.nk_files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) fail("--nk-file {}: cannot read it", file);
    std::stringstream text;
    text << in.rdbuf();
    const OpticalConstants c = read_refractive_index(text.str(), file);
    const std::string label = std::filesystem::path(file).filename().string();
    if (c.k) {  // a conductor (or an absorbing dielectric): n + ik
      const Spectrum n = index_spectrum(c.n), k = *c.k;
      out.push_back(
          {label,
           [n, k](float cos, float l) { return fresnel_conductor_polarized(cos, evaluate(n, l), evaluate(k, l)); },
           true});
    } else {
      out.push_back(
          {label, [n = c.n](float cos, float l) { return fresnel_dielectric_polarized(cos, ior(n, l)); }, false});
    }
  }
  if (out.empty()) fail("name a catalogue --material, give --nk N,K or --nk-file FILE (see --list)");
  return out;
}

// Colour of the reflectance at one angle under D65, in the output space.
Rgb reflectance_color(const Reflector& r, float angle_deg, const std::string& colorspace) {
  std::vector<float> lit;
  const float c = std::cos(radians(angle_deg));
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
    lit.push_back(r.reflectance(c, float(l)).R * cie().d65(float(l)));
  const Xyz xyz = spectrum_to_xyz(DenselySampledSpectrum(int(kLambdaMin), lit));
  float px[3] = {xyz.x, xyz.y, xyz.z};
  ColorPipeline::standard().convert(ColorPipeline::kXyz, colorspace, px, 1);
  return {px[0], px[1], px[2]};
}

void plot_curves(const std::vector<Reflector>& rs, const std::string& file) {
  Plot plot{"Fresnel reflectance (solid: normal incidence, dashed: 60 deg)", "wavelength [nm]", "R", false, false, {}};
  for (size_t i = 0; i < rs.size(); ++i)
    for (float angle : {0.f, 60.f}) {
      const Reflector& r = rs[i];
      PlotSeries s{angle == 0 ? r.label : r.label + " 60 deg", {}, {}, angle != 0, int(i)};
      for (int l = int(kLambdaMin); l <= int(kLambdaMax); l += 2) {
        s.x.push_back(l);
        s.y.push_back(r.reflectance(std::cos(radians(angle)), float(l)).R);
      }
      plot.series.push_back(std::move(s));
    }
  write_plot_png(file, plot);
  std::printf("wrote %s\n", file.c_str());
}

void run(const FresnelArgs& args) {
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  const auto rs = reflectors(args);
  const auto wavelengths = parse_list(args.wavelengths, "--wavelengths");
  const auto angles = parse_list(args.angles, "--angles");
  for (float l : wavelengths)
    if (l < kLambdaMin || l > kLambdaMax) fail("--wavelengths: {} nm is outside {}-{} nm", l, kLambdaMin, kLambdaMax);
  for (float a : angles)
    if (a < 0 || a > 90) fail("--angles: {} is outside 0-90 degrees", a);

  const bool csv = args.format == "csv";
  std::printf(csv ? "material,wavelength_nm,angle_deg,R,Rs,Rp\n" : "%-14s %8s %7s %8s %8s %8s\n", "material", "lambda",
              "angle", "R", "Rs", "Rp");
  for (const Reflector& r : rs)
    for (float l : wavelengths)
      for (float a : angles) {
        const FresnelReflectance f = r.reflectance(std::cos(radians(a)), l);
        std::printf(csv ? "%s,%g,%g,%.6f,%.6f,%.6f\n" : "%-14s %8g %7g %8.4f %8.4f %8.4f\n", r.label.c_str(), l, a, f.R,
                    f.Rs, f.Rp);
      }
  if (!csv) {
    std::printf("\ncolour of the reflectance under D65, %s:\n%-14s %5s %8s %8s %8s\n", colorspace.c_str(), "material",
                "angle", "R", "G", "B");
    for (const Reflector& r : rs)
      for (float a : {0.f, 60.f}) {
        const Rgb c = reflectance_color(r, a, colorspace);
        std::printf("%-14s %5g %8.4f %8.4f %8.4f\n", r.label.c_str(), a, c.r, c.g, c.b);
      }
  }
  if (!args.plot.empty()) plot_curves(rs, args.plot);
}

void list_catalogue() {
  for (const CatalogueEntry& e : MaterialCatalogue::standard().entries())
    std::printf("%-14s %-10s %s (%s)\n", e.key.c_str(), e.metal ? "metal" : "dielectric", e.name.c_str(),
                e.source.c_str());
}

}  // namespace

void add_fresnel_command(CLI::App& app) {
  auto args = std::make_shared<FresnelArgs>();
  auto list = std::make_shared<bool>(false);
  CLI::App* cmd =
      app.add_subcommand("fresnel", "Fresnel reflectance of catalogue materials versus angle and wavelength");
  cmd->add_option("-m,--material", args->materials, "Catalogue materials (repeat or comma-separate), e.g. Cu,Au,N-BK7")
      ->delimiter(',');
  cmd->add_option("--nk", args->nk, "A complex index N,K instead of (or besides) catalogue materials");
  cmd->add_option("--nk-file", args->nk_files,
                  "Optical constants in a refractiveindex.info file (its CSV or YAML download; repeat for more)");
  cmd->add_option("--wavelengths", args->wavelengths, "Wavelengths in nm, comma-separated")->default_val("450,550,650");
  cmd->add_option("--angles", args->angles, "Angles of incidence in degrees, comma-separated")
      ->default_val("0,45,60,80,89");
  cmd->add_option("--format", args->format, "table (with metal colours) or csv")
      ->check(CLI::IsMember({"table", "csv"}))
      ->default_val("table");
  cmd->add_option("--colorspace", args->colorspace, "Colour space of the printed colours")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_option("--plot", args->plot, "Write a PNG plot of R(λ) at 0° and 60°");
  cmd->add_flag("--list", *list, "List the catalogue's materials and their sources");
  cmd->callback([args, list] { *list ? list_catalogue() : run(*args); });
}

}  // namespace prism
