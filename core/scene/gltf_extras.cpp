// Prism's own keys in a glTF file's extras, {"prism": {…}} (README, "Spectral inputs"): catalogue
// metals and glasses by name, and measured spectra and optical constants, read with the SPECTRUM
// syntax of spectrum_input.h. A material or light without them is read exactly as before. They are
// read from the file's JSON itself (nlohmann), not tinygltf's values, which drop empty arrays and
// objects: an empty table must be refused, not ignored.

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/scene/gltf_import.h"
#include "core/scene/refractive_index_file.h"
#include "core/scene/spectrum_input.h"
#include "materials/catalogue.h"

namespace prism {

namespace {

using Json = nlohmann::json;

// The extras.prism object at `path` of the document (none: null).
const Json* prism_extras(const Json& doc, std::initializer_list<std::string> path, const std::string& what) {
  const Json* node = &doc;
  for (const std::string& key : path) {
    if (node->is_object() && node->contains(key)) {
      node = &(*node)[key];
    } else if (node->is_array() && !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit) &&
               std::stoul(key) < node->size()) {
      node = &(*node)[std::stoul(key)];
    } else {
      return nullptr;
    }
  }
  if (!node->is_object() || !node->contains("extras") || !(*node)["extras"].is_object() ||
      !(*node)["extras"].contains("prism"))
    return nullptr;
  const Json& prism = (*node)["extras"]["prism"];
  if (!prism.is_object()) fail("{}: extras.prism must be an object", what);
  return &prism;
}

std::vector<double> numbers(const Json& v, const char* field, const std::string& what) {
  if (!v.is_array()) fail("{}: \"{}\" must be an array of numbers", what, field);
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number()) fail("{}: \"{}\"[{}] is not a number", what, field, i);
    out.push_back(v[i].get<double>());
  }
  return out;
}

// The spectrum a SPECTRUM value gives, for `use` (spectrum_input.h); {"file": …} is read through
// `files`, under the scene's file policy and into its content hash.
Spectrum parse_spectrum(const Json& value, SpectrumUse use, SceneFiles& files, const std::string& what) {
  if (value.is_string()) return checked_spectrum(named_spectrum(value.get<std::string>(), use, what), use, what);
  if (!value.is_object())
    fail(
        "{}: a spectrum is a name, {{\"blackbody\": K}}, {{\"wavelengths\": […], \"values\": […]}} or "
        "{{\"file\": \"name.csv\"}}",
        what);
  if (value.contains("blackbody")) {
    if (!value["blackbody"].is_number()) fail("{}: \"blackbody\" must be a temperature in kelvin", what);
    return checked_spectrum(blackbody_spectrum(value["blackbody"].get<double>(), use, what), use, what);
  }
  if (value.contains("wavelengths") || value.contains("values")) {
    if (!value.contains("wavelengths") || !value.contains("values"))
      fail("{}: a table needs both \"wavelengths\" and \"values\"", what);
    return checked_spectrum(checked_table(numbers(value["wavelengths"], "wavelengths", what),
                                          numbers(value["values"], "values", what), use, what),
                            use, what);
  }
  if (value.contains("file")) {
    const Json& f = value["file"];
    if (!f.is_string() || f.get<std::string>().empty()) fail("{}: \"file\" must name a file", what);
    const std::string uri = f.get<std::string>();
    const std::vector<unsigned char> bytes = files.read(uri, what);
    return checked_spectrum(
        parse_spectrum_csv({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, use, what + " (" + uri + ")"),
        use, what);
  }
  fail("{}: a spectrum object needs \"blackbody\", \"wavelengths\" and \"values\", or \"file\"", what);
}

// A medium's coefficient: a plain number (per scene unit, the same at every wavelength) or a
// SPECTRUM of them.
Spectrum parse_coefficient(const Json& value, SceneFiles& files, const std::string& what) {
  if (!value.is_number()) return parse_spectrum(value, SpectrumUse::coefficient, files, what);
  const double c = value.get<double>();
  if (!(c >= 0 && c <= 1e30)) fail("{}: must be a finite, non-negative number per scene unit (got {})", what, c);
  return ConstantSpectrum{float(c)};
}

}  // namespace

Medium GltfLoader::medium_extras(const Json& v, const std::string& what) {
  if (!v.is_object()) fail("{}: a medium is {{\"sigma_a\": SPECTRUM, \"sigma_s\": SPECTRUM, \"g\": NUMBER}}", what);
  Medium medium;
  for (const auto& [key, value] : v.items()) {
    if (key == "sigma_a") {
      medium.sigma_a = parse_coefficient(value, files_, what + ".sigma_a");
      if (value == 0) medium.sigma_a.reset();  // 0: none (a medium that scatters nothing is no scattering medium)
    } else if (key == "sigma_s") {
      medium.sigma_s = parse_coefficient(value, files_, what + ".sigma_s");
      if (value == 0) medium.sigma_s.reset();
    } else if (key == "g") {
      if (!value.is_number() || !(std::abs(value.get<double>()) < 1))
        fail("{}.g: the phase function's asymmetry must be a number in (-1, 1)", what);
      medium.phase.g = float(value.get<double>());
    } else {
      fail("{}: unknown key \"{}\" (a medium has sigma_a, sigma_s and g)", what, key);
    }
  }
  return medium;
}

OpticalConstants GltfLoader::optical_constants_file(const nlohmann::json& v, const std::string& what) {
  if (!v.is_string() || v.get<std::string>().empty()) fail("{}: \"nk\" must name a refractiveindex.info file", what);
  const std::string uri = v.get<std::string>();
  const std::vector<unsigned char> bytes = files_.read(uri, what);
  return read_refractive_index({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, what + " (" + uri + ")");
}

void GltfLoader::material_extras(const tinygltf::Material& m, int index, Material& out, const std::string& context) {
  const std::string where = fmt::format("{}: {}", file_, context);
  const Json* prism = prism_extras(document_, {"materials", std::to_string(index)}, where);
  if (!prism) return;
  PbrMaterial& p = std::get<PbrMaterial>(out.kind);
  for (const auto& [key, v] : prism->items()) {
    const std::string what = where + ": extras.prism." + key;
    if (key == "metal") {
      if (prism->contains("medium") || prism->contains("subsurface"))
        fail("{}: a metal has no medium inside it (\"medium\", \"subsurface\")", what);
      if (v.is_string()) {
        p.metal = MaterialCatalogue::standard().metal(v.get<std::string>());
      } else if (v.is_object() && v.contains("nk")) {
        const OpticalConstants c = optical_constants_file(v["nk"], what);
        if (!c.k) fail("{}: the file gives no extinction coefficient k, which a metal needs", what);
        p.metal = MeasuredMetal{index_spectrum(c.n), *c.k, v["nk"].get<std::string>()};
      } else if (v.is_object() && v.contains("n") && v.contains("k")) {
        p.metal = MeasuredMetal{parse_spectrum(v["n"], SpectrumUse::index, files_, what + ".n"),
                                parse_spectrum(v["k"], SpectrumUse::extinction, files_, what + ".k"), key};
      } else {
        fail("{}: a metal is a catalogue name, {{\"nk\": \"file\"}} or {{\"n\": SPECTRUM, \"k\": SPECTRUM}}", what);
      }
      p.metallic = 1;
    } else if (key == "glass") {
      IorModel n = ConstantIor{1.5f};
      if (v.is_string()) {
        n = MaterialCatalogue::standard().dielectric(v.get<std::string>());
      } else if (v.is_object() && v.contains("sellmeier")) {
        // n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ), λ in µm, Cᵢ in µm² (the glass makers' form).
        const std::vector<double> c = numbers(v["sellmeier"], "sellmeier", what);
        if (c.size() != 6 || !std::all_of(c.begin(), c.end(), [](double x) { return std::isfinite(x); }))
          fail("{}: \"sellmeier\" must be [B1, B2, B3, C1, C2, C3]", what);
        SellmeierIor s;
        for (int i = 0; i < 3; ++i) s.b.push_back(float(c[i])), s.c.push_back(float(c[i + 3]));
        for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
          if (!(s(float(l)) > 0)) fail("{}: the Sellmeier formula gives no index at {} nm", what, l);
        n = std::move(s);
      } else if (v.is_object() && v.contains("nk")) {
        n = optical_constants_file(v["nk"], what).n;
      } else if (v.is_object() && v.contains("n") && v["n"].is_string()) {
        n = MaterialCatalogue::standard().dielectric(v["n"].get<std::string>());
      } else if (v.is_object() && v.contains("n")) {
        n = TabulatedIor{std::get<TabulatedSpectrum>(parse_spectrum(v["n"], SpectrumUse::index, files_, what + ".n"))};
      } else {
        fail("{}: a glass is a catalogue name, {{\"sellmeier\": [...]}}, {{\"n\": SPECTRUM}} or {{\"nk\": \"file\"}}",
             what);
      }
      p.dielectric = Dielectric(std::move(n), p.dielectric.interior, p.dielectric.thin_walled);
      p.metallic = 0;
      p.transmission = 1;
    } else if (key == "reflectance") {
      p.base_reflectance = parse_spectrum(v, SpectrumUse::reflectance, files_, what);
      p.base_color = {1, 1, 1};  // the texture and vertex colour still multiply (base_spectrum)
    } else if (key == "attenuation") {
      // The transmittance T(λ) reached at attenuationDistance d: σ_a(λ) = −ln T(λ) / d, at every nm.
      const double d = extension_number(m, "KHR_materials_volume", "attenuationDistance", INFINITY);
      if (p.dielectric.thin_walled || !(d > 0 && std::isfinite(d)))
        fail("{}: needs KHR_materials_volume with thicknessFactor > 0 and a finite attenuationDistance", what);
      const Spectrum t = parse_spectrum(v, SpectrumUse::transmittance, files_, what);
      std::vector<float> sigma;
      for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
        sigma.push_back(float(-std::log(std::max(double(evaluate(t, float(l))), 1e-30)) / d));
      p.dielectric.interior.sigma_a = DenselySampledSpectrum(int(kLambdaMin), std::move(sigma));
    } else if (key == "medium") {
      // Fills the closed volume: its sigma_a, if given, is the absorption in place of the volume
      // extension's attenuation, which may not give it too.
      if (p.dielectric.thin_walled || !(p.transmission > 0) || !(p.metallic < 1))
        fail(
            "{}: needs a closed transmissive volume: KHR_materials_transmission, KHR_materials_volume with "
            "thicknessFactor > 0, and metallicFactor < 1",
            what);
      Medium medium = medium_extras(v, what);
      if (medium.sigma_a && std::isfinite(extension_number(m, "KHR_materials_volume", "attenuationDistance", INFINITY)))
        fail("{}: sigma_a and KHR_materials_volume's attenuation both give the absorption; give one", what);
      if (!medium.sigma_a) medium.sigma_a = p.dielectric.interior.sigma_a;
      p.dielectric.interior = std::move(medium);
    } else if (key == "subsurface") {
      // Subsurface scattering as a random walk (Cycles' method): the surface becomes the
      // material's dielectric interface (its index and roughness), and the closed mesh fills with
      // a medium of mean free path 1/σ_t whose multiple-scattering albedo is the base colour (or
      // the reflectance spectrum), wavelength by wavelength (medium_of_albedo).
      if (!v.is_object() || !v.contains("mean_free_path"))
        fail("{}: subsurface is {{\"mean_free_path\": METRES, \"g\": NUMBER}}", what);
      if (prism->contains("medium")) fail("{}: a material takes \"medium\" or \"subsurface\", not both", what);
      float mfp = 0, g = 0;
      for (const auto& [field, x] : v.items()) {
        if (field == "mean_free_path" && x.is_number() && x.get<double>() > 0 && x.get<double>() < 1e30)
          mfp = float(x.get<double>());
        else if (field == "g" && x.is_number() && std::abs(x.get<double>()) < 1)
          g = float(x.get<double>());
        else
          fail("{}.{}: {}", what, field,
               field == "mean_free_path" ? "must be a positive number of metres"
               : field == "g"            ? "the phase function's asymmetry must be a number in (-1, 1)"
                                         : "unknown key (subsurface has mean_free_path and g)");
      }
      if (p.base_color_texture)
        warn_once(fmt::format("{}: the base colour texture is ignored under subsurface (the factor colours the medium)",
                              context));
      const Spectrum albedo = p.base_reflectance ? *p.base_reflectance : Spectrum(RgbAlbedoSpectrum(p.base_color));
      p.dielectric = Dielectric(p.dielectric.ior, medium_of_albedo(ConstantSpectrum{1 / mfp}, albedo, g), false);
      p.metallic = 0;
      p.transmission = 1;
      p.base_color = {1, 1, 1};  // the colour is the medium's: the surface is clear
      p.base_reflectance.reset();
      p.base_color_texture.reset();
    } else if (key == "emission") {
      const Spectrum s = parse_spectrum(v, SpectrumUse::emission, files_, what);
      const float y = luminance(out.emission_rgb);
      if (!(y > 0)) {
        warn_once(fmt::format("{}: extras.prism.emission ignored: the material's emissive factor is 0", context));
        continue;
      }
      out.emission = spectrum_with_luminance(s, y);
      out.spectral_emission = true;
    } else {
      warn_once(fmt::format("{}: unknown key extras.prism.{} ignored", context, key));
    }
  }
}

Spectrum GltfLoader::light_emission(const tinygltf::Light& light, Rgb rgb, const std::string& context) {
  const int index = int(&light - model_.lights.data());
  const std::string where = fmt::format("{}: light '{}'", context, light.name);
  const Json* prism =
      prism_extras(document_, {"extensions", "KHR_lights_punctual", "lights", std::to_string(index)}, where);
  if (!prism || !prism->contains("emission") || !(luminance(rgb) > 0)) return RgbIlluminantSpectrum(rgb);
  for (const auto& [key, v] : prism->items())
    if (key != "emission") warn_once(fmt::format("{}: unknown key extras.prism.{} ignored", where, key));
  auto it = light_spectra_.find(index);
  if (it == light_spectra_.end())  // read once, whatever the poses
    it = light_spectra_
             .emplace(index, parse_spectrum((*prism)["emission"], SpectrumUse::emission, files_,
                                            where + ": extras.prism.emission"))
             .first;
  return spectrum_with_luminance(it->second, luminance(rgb));
}

void GltfLoader::scene_extras() {
  if (model_.scenes.empty()) return;
  const std::string where = fmt::format("{}: scene {}", file_, scene_index_);
  const Json* prism = prism_extras(document_, {"scenes", std::to_string(scene_index_)}, where);
  if (!prism) return;
  for (const auto& [key, v] : prism->items()) {
    if (key == "medium")
      scene_.medium = medium_extras(v, where + ": extras.prism.medium");
    else
      warn_once(fmt::format("{}: unknown key extras.prism.{} ignored", where, key));
  }
}

LensDesc GltfLoader::camera_lens(const tinygltf::Camera& camera, const std::string& context) {
  const std::string where = fmt::format("{}: camera '{}'", context, camera.name);
  const Json* prism = prism_extras(document_, {"cameras", std::to_string(&camera - model_.cameras.data())}, where);
  LensDesc lens;
  if (!prism) return lens;
  const auto number = [&](const std::string& key, const Json& v, bool positive) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 1e30 ||
        (positive && !(v.get<double>() > 0)))
      fail("{}: extras.prism.{} must be a {}finite number", where, key, positive ? "positive, " : "");
    return float(v.get<double>());
  };
  for (const auto& [key, v] : prism->items()) {
    if (key == "aperture") {
      lens.f_number = number(key, v, true);
    } else if (key == "sensor_width") {
      lens.sensor_width = number(key, v, true);
    } else if (key == "lens_radius") {
      lens.radius = number(key, v, false);
      if (*lens.radius < 0) fail("{}: extras.prism.lens_radius must not be negative", where);
    } else if (key == "focus_distance") {
      lens.focus_distance = number(key, v, true);
    } else if (key == "focus_node") {
      if (!v.is_string()) fail("{}: extras.prism.focus_node must be a node's name", where);
      lens.focus_node = v.get<std::string>();
    } else if (key == "blades") {
      if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > 1000)
        fail("{}: extras.prism.blades must be a whole number from 0 to 1000", where);
      lens.blades = int(v.get<int64_t>());
    } else if (key == "blade_rotation") {
      lens.blade_rotation = number(key, v, false);
    } else {
      warn_once(fmt::format("{}: unknown key extras.prism.{} ignored", where, key));
    }
  }
  if (lens.f_number && lens.radius) fail("{}: extras.prism gives both aperture and lens_radius", where);
  if (lens.focus_distance && lens.focus_node) fail("{}: extras.prism gives both focus_distance and focus_node", where);
  return lens;
}

}  // namespace prism
