// Energy conservation and sampling of every BSDF lobe and glTF material combination, at a grid
// of incident angles and at all of a path's wavelengths:
//   * directional albedo ∫ f |cos θ_i| dω_i (transmission counted as energy: times η'², undoing
//     the radiance scaling across the interface) by Monte Carlo with the lobe's own sampling and,
//     separately, with uniform sphere sampling: ≤ 1, equal to each other, and = 1 for lossless
//     lobes (albedo-1 Lambert, clear smooth dielectric R + T);
//   * χ² goodness of fit of each non-delta lobe's sampling against its pdf.
// Tolerances are 4 standard errors of the estimates (from their sample variance), not tuned.

#include <bit>
#include <catch2/catch.hpp>
#include <functional>

#include "core/base/rng.h"
#include "materials/catalogue.h"
#include "materials/make_bsdf.h"
#include "tests/support/chi2.h"

using namespace prism;

namespace {

constexpr int N = 4;

struct Case {
  std::string name;
  std::function<Bsdf<N>()> make;
  bool lossless = false;
  float eta = 1;       // relative index of a solid dielectric (transmission scales radiance by 1/η'²)
  bool sharp = false;  // lobes of roughness < 0.2 are too narrow for uniform sampling to resolve
  // What the albedo may exceed 1 by beyond noise: anisotropic lobes' multiple-scattering
  // compensation uses the isotropic table at √(α_x α_y) (as Cycles does), an approximation.
  float slack = 0;
};

SampledWavelengths<N> wavelengths() { return SampledWavelengths<N>::sample({0.48f, 0.37f}); }

Bsdf<N> bsdf_of(const PbrMaterial& m, float front_ior = 1, const SurfacePoint& at = {}) {
  auto lambda = wavelengths();
  const Dielectric front(ConstantIor{front_ior});
  return make_bsdf(Material{"m", m, {}, false}, at, lambda, front_ior == 1 ? nullptr : &front);
}

Clearcoat clearcoat(float factor, float roughness) {
  Clearcoat c;
  c.factor = factor, c.roughness = roughness;
  return c;
}
Sheen sheen(Rgb color, float roughness) {
  Sheen s;
  s.color = color, s.roughness = roughness;
  return s;
}
Iridescence iridescence(float factor, float ior, float thickness) {  // no texture: the maximum thickness
  Iridescence i;
  i.factor = factor, i.ior = ior, i.thickness_max = thickness;
  return i;
}
DiffuseTransmission diffuse_transmission(float factor, Rgb color) {
  DiffuseTransmission d;
  d.factor = factor, d.color = color;
  return d;
}

// The KHR extensions' lobes (clearcoat, sheen, specular colour, thin film, diffuse transmission),
// each over a base that leaves room to see it, at the given roughness (the layer's and the base's).
std::vector<Case> layered_cases(float roughness, bool compensated = true) {
  const auto of = [compensated](PbrMaterial m) {
    m.energy_compensation = compensated;
    return bsdf_of(m);
  };
  const std::string r = " roughness " + std::to_string(roughness).substr(0, 4);
  const bool sharp = roughness < 0.2f;
  const auto plastic = [](Rgb color, float rough) { return PbrMaterial::plastic(color, rough); };
  std::vector<Case> c;
  c.push_back({"clearcoat over red plastic" + r,
               [=] {
                 PbrMaterial m = plastic({0.8f, 0.1f, 0.1f}, 0.5f);
                 m.clearcoat = clearcoat(1, roughness);
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"half clearcoat over rough gold" + r,
               [=] {
                 PbrMaterial m = PbrMaterial::metal_of(Rgb{1, 0.78f, 0.34f}, 0.6f);
                 m.clearcoat = clearcoat(0.5f, roughness);
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"sheen over white plastic" + r,
               [=] {
                 PbrMaterial m = plastic({1, 1, 1}, 0.7f);
                 m.sheen = sheen({1, 0.7f, 0.4f}, roughness);
                 return of(m);
               },
               false, 1, false});
  c.push_back({"specular colour (3, 0.5, 1) plastic" + r,
               [=] {
                 PbrMaterial m = plastic({1, 1, 1}, roughness);
                 m.specular_color = {3, 0.5f, 1};
                 return of(m);
               },
               false, 1, sharp});
  // A film of higher index than the base (n_f² > η), whose reflectance near grazing rises above
  // that of any single interface: coupled as the quarter-wave interface alone, the white diffuse
  // under it reflected 0.9% more than it received at 87°.
  c.push_back({"thin film n 1.8, 450 nm, over white plastic" + r,
               [=] {
                 PbrMaterial m = plastic({1, 1, 1}, roughness);
                 m.iridescence = iridescence(1, 1.8f, 450);
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"thin film n 1.3, 450 nm, over white plastic" + r,
               [=] {
                 PbrMaterial m = plastic({1, 1, 1}, roughness);
                 m.iridescence = iridescence(1, 1.3f, 450);
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"thin film n 1.8, 300 nm, over Cu" + r,
               [=] {
                 PbrMaterial m = PbrMaterial::metal_of(MaterialCatalogue::standard().metal("Cu"), roughness);
                 m.iridescence = iridescence(1, 1.8f, 300);
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"thin film over glass" + r,
               [=] {
                 PbrMaterial m = PbrMaterial::glass(Dielectric(ConstantIor{1.5f}), roughness);
                 m.iridescence = iridescence(0.7f, 1.33f, 500);
                 return of(m);
               },
               false, 1.5f, sharp});
  // The layers over the compensated, anisotropic base lobes (the coat stays its own isotropic GGX).
  c.push_back({"clearcoat over brushed Al" + r,
               [=] {
                 PbrMaterial m = PbrMaterial::metal_of(MaterialCatalogue::standard().metal("Al"), 0.4f);
                 m.anisotropy_strength = 0.8f;
                 m.clearcoat = clearcoat(0.7f, roughness);
                 return of(m);
               },
               false, 1, sharp, 0.03f});
  c.push_back({"diffuse transmission 0.6" + r,
               [=] {
                 PbrMaterial m = plastic({0.9f, 0.9f, 0.9f}, roughness);
                 m.diffuse_transmission = diffuse_transmission(0.6f, {1, 0.6f, 0.3f});
                 return of(m);
               },
               false, 1, sharp});
  c.push_back({"all layers" + r,
               [=] {
                 PbrMaterial m = plastic({0.9f, 0.9f, 0.9f}, roughness);
                 m.metallic = 0.3f;
                 m.clearcoat = clearcoat(0.8f, roughness);
                 m.sheen = sheen({0.5f, 0.5f, 1}, 0.5f);
                 m.specular_color = {1.5f, 1, 0.5f};
                 m.iridescence = iridescence(0.5f, 1.6f, 250);
                 m.diffuse_transmission = diffuse_transmission(0.3f, {1, 1, 1});
                 return of(m);
               },
               false, 1, sharp});
  return c;
}

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"Lambert albedo 1", [] { return Bsdf<N>(DiffuseBsdf<N>(SampledSpectrum<N>(1.f))); }, true});
  c.push_back({"Lambert albedo 0.5", [] { return Bsdf<N>(DiffuseBsdf<N>(SampledSpectrum<N>(0.5f))); }});
  c.push_back(
      {"smooth glass 1.5", [] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{1.5f}))); }, true, 1.5f});
  c.push_back({"smooth glass seen from water",
               [] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{1.5f})), 1.33f); }, true, 1.5f / 1.33f});
  c.push_back(
      {"smooth thin glass", [] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{1.5f}, {}, true))); }, true});
  const MeasuredMetal cu = MaterialCatalogue::standard().metal("Cu");
  for (float roughness : {0.05f, 0.3f, 1.f}) {
    const std::string r = " roughness " + std::to_string(roughness).substr(0, 4);
    const bool sharp = roughness < 0.2f;
    c.push_back({"Cu" + r, [=] { return bsdf_of(PbrMaterial::metal_of(cu, roughness)); }, false, 1, sharp});
    c.push_back({"gold-coloured metal" + r,
                 [=] {
                   return bsdf_of(PbrMaterial::metal_of(Rgb{1, 0.78f, 0.34f}, roughness));
                 },
                 false, 1, sharp});
    c.push_back({"glass 1.5" + r, [=] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{1.5f}), roughness)); },
                 false, 1.5f, sharp});
    c.push_back({"diamond 2.42" + r,
                 [=] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{2.42f}), roughness)); }, false, 2.42f,
                 sharp});
    c.push_back({"thin glass" + r,
                 [=] { return bsdf_of(PbrMaterial::glass(Dielectric(ConstantIor{1.5f}, {}, true), roughness)); }, false,
                 1, sharp});
    c.push_back({"white plastic" + r,
                 [=] {
                   return bsdf_of(PbrMaterial::plastic(Rgb{1, 1, 1}, roughness));
                 },
                 false, 1, sharp});
    c.push_back({"half-metal" + r,
                 [=] {
                   PbrMaterial m = PbrMaterial::plastic(Rgb{0.8f, 0.5f, 0.3f}, roughness);
                   m.metallic = 0.5f;
                   return bsdf_of(m);
                 },
                 false, 1, sharp});
    c.push_back({"half-transmissive, specular 0.5" + r,
                 [=] {
                   PbrMaterial m = PbrMaterial::plastic(Rgb{0.9f, 0.9f, 0.9f}, roughness);
                   m.transmission = 0.5f;
                   m.specular = 0.5f;
                   return bsdf_of(m);
                 },
                 false, 1.5f, sharp});
  }
  // KHR_materials_anisotropy: the direction of anisotropy along local x (α_x = mix(α, 1, s²)).
  const auto brushed = [](PbrMaterial m, float strength) {
    m.anisotropy_strength = strength;
    return m;
  };
  // At roughness 0.05 a strong anisotropy makes an arc 0.1° wide, finer than the χ² cells'
  // integration resolves: there the strength is 0.1 (α_x five times α_y).
  for (float roughness : {0.05f, 0.3f, 1.f}) {
    const std::string r = " roughness " + std::to_string(roughness).substr(0, 4);
    const bool sharp = roughness < 0.2f;
    const float strong = sharp ? 0.1f : 0.8f;
    c.push_back({"anisotropic Al" + r,
                 [=] {
                   return bsdf_of(
                       brushed(PbrMaterial::metal_of(MaterialCatalogue::standard().metal("Al"), roughness), strong));
                 },
                 false, 1, sharp, 0.03f});
    c.push_back(
        {"anisotropic glass 1.5" + r,
         [=] { return bsdf_of(brushed(PbrMaterial::glass(Dielectric(ConstantIor{1.5f}), roughness), strong / 2)); },
         false, 1.5f, sharp, 0.03f});
    c.push_back({"anisotropic white plastic" + r,
                 [=] {
                   return bsdf_of(brushed(PbrMaterial::plastic(Rgb{1, 1, 1}, roughness), strong));
                 },
                 false, 1, sharp, 0.03f});
  }
  c.push_back({"white plastic smooth", [] { return bsdf_of(PbrMaterial::plastic(Rgb{1, 1, 1}, 0)); }});
  for (float roughness : {0.f, 0.05f, 0.3f, 1.f})
    for (Case& l : layered_cases(roughness)) c.push_back(std::move(l));
  // A thin wall clear on half its area: a sheet there, one interface over the white base elsewhere.
  for (float roughness : {0.05f, 0.3f, 1.f})
    c.push_back({"partly clear thin wall, transmission 0.5 roughness " + std::to_string(roughness).substr(0, 4),
                 [=] {
                   PbrMaterial m = PbrMaterial::plastic(Rgb{1, 1, 1}, roughness);
                   m.dielectric = Dielectric(ConstantIor{1.5f}, {}, true);
                   m.transmission = 0.5f;
                   return bsdf_of(m);
                 },
                 false, 1, roughness < 0.2f});
  return c;
}

struct Estimate {
  SampledSpectrum<N> mean, standard_error;
};

// Mean and standard error of per-sample spectra, summed in double (a float sum of 10⁵ values near
// 1 drifts by 10⁻⁴, more than the standard error of a nearly constant estimate).
struct Accumulator {
  std::array<double, N> sum{}, sum_sq{};
  int n = 0;
  void add(const SampledSpectrum<N>& x) {
    for (int i = 0; i < N; ++i) sum[i] += x[i], sum_sq[i] += double(x[i]) * x[i];
    ++n;
  }
  Estimate result() const {
    Estimate e;
    for (int i = 0; i < N; ++i) {
      const double mean = sum[i] / n;
      e.mean[i] = float(mean);
      e.standard_error[i] = float(std::sqrt(std::max(0.0, sum_sq[i] / n - mean * mean) / (n - 1)));
    }
    return e;
  }
};

// η'² of light going from wi's side to wo's: the factor that turns transmitted radiance into energy.
float energy_factor(const Case& c, const Vec3f& wo, const Vec3f& wi) {
  return same_hemisphere(wo, wi) ? 1.f : sqr(wo.z > 0 ? c.eta : 1 / c.eta);
}

Estimate albedo_own_sampling(const Case& c, const Bsdf<N>& b, const Vec3f& wo, int samples, Rng& rng) {
  Accumulator acc;
  for (int i = 0; i < samples; ++i) {
    const float uc = rng.uniform();
    const Vec2f u(rng.uniform(), rng.uniform());
    const auto s = bsdf_sample_f(b, wo, uc, u);
    acc.add(s && s->pdf > 0 ? s->f * (abs_cos_theta(s->wi) / s->pdf * energy_factor(c, wo, s->wi))
                            : SampledSpectrum<N>(0.f));
  }
  return acc.result();
}

Estimate albedo_uniform_sampling(const Case& c, const Bsdf<N>& b, const Vec3f& wo, int samples, Rng& rng) {
  Accumulator acc;
  for (int i = 0; i < samples; ++i) {
    const Vec3f wi = sample_uniform_sphere({rng.uniform(), rng.uniform()});
    acc.add(bsdf_f(b, wo, wi) * (abs_cos_theta(wi) / uniform_sphere_pdf() * energy_factor(c, wo, wi)));
  }
  return acc.result();
}

const float kCosines[] = {1.f, 0.7f, 0.3f, 0.05f, -0.6f};

}  // namespace

TEST_CASE("every BSDF conserves energy: albedo <= 1 by its own and by uniform sampling, and = 1 when lossless") {
  Rng rng(17, 0);
  for (const Case& c : cases()) {
    const Bsdf<N> b = c.make();
    const bool has_delta = bsdf_delta_lobes(b, Vec3f(0.3f, 0, std::sqrt(1 - 0.09f))).count > 0;
    for (float cos_o : kCosines) {
      const Vec3f wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
      const Estimate own = albedo_own_sampling(c, b, wo, 40000, rng);
      for (int i = 0; i < N; ++i) {
        INFO(c.name << ", cos θo " << cos_o << ", lane " << i << ": albedo " << own.mean[i] << " ± "
                    << own.standard_error[i]);
        REQUIRE(std::isfinite(own.mean[i]));
        CHECK(own.mean[i] <= 1 + 4 * own.standard_error[i] + 1e-6f + c.slack);
        if (c.lossless) CHECK(own.mean[i] == Approx(1).margin(4 * own.standard_error[i] + 1e-5));
      }
      if (has_delta || c.sharp) continue;  // uniform directions (almost) never meet such lobes
      const Estimate uni = albedo_uniform_sampling(c, b, wo, 40000, rng);
      for (int i = 0; i < N; ++i) {
        INFO(c.name << ", cos θo " << cos_o << ", lane " << i << ": own " << own.mean[i] << " ± "
                    << own.standard_error[i] << ", uniform " << uni.mean[i] << " ± " << uni.standard_error[i]);
        const float se = std::sqrt(sqr(own.standard_error[i]) + sqr(uni.standard_error[i]));
        CHECK(uni.mean[i] <= 1 + 4 * uni.standard_error[i] + 1e-6f + c.slack);
        CHECK(own.mean[i] == Approx(uni.mean[i]).margin(4 * se + 1e-6));
      }
    }
  }
}

TEST_CASE("every sampled BSDF lobe follows its pdf (chi-square)") {
  // Reflected and transmitted directions are tested apart, each hemisphere's cells centred on
  // its own peak.
  for (const Case& c : cases()) {
    const Bsdf<N> b = c.make();
    if (bsdf_is_specular(b)) continue;
    for (float cos_o : {0.9f, 0.4f, -0.7f})
      for (const bool reflected : {true, false}) {
        const Vec3f wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
        const auto in_part = [&](const Vec3f& wi) { return same_hemisphere(wo, wi) == reflected; };
        const auto result = test::chi2_test(
            [&](float u1, float u2, float u3) -> std::optional<Vec3f> {
              const auto s = bsdf_sample_f(b, wo, u1, {u2, u3});
              if (!s || s->specular || !in_part(s->wi)) return std::nullopt;  // delta samples carry no density
              return s->wi;
            },
            [&](const Vec3f& wi) { return in_part(wi) ? double(bsdf_pdf(b, wo, wi)) : 0.0; });
        INFO(c.name << ", cos θo " << cos_o << (reflected ? ", reflection" : ", transmission") << ": χ² "
                    << result.statistic << ", dof " << result.degrees_of_freedom << ", p " << result.p_value);
        CHECK(result.passed);
      }
  }
}

TEST_CASE(
    "the glTF base and its layers choose their lobe by u.x, not uc: a grid of u at any fixed uc gives the albedo") {
  // Half metal, half plastic: three lobes; under a clear coat and a sheen, two layers more. The
  // choice rescales u.x within the lobe's interval (within_lobe), so the points of a stratified
  // grid that choose each lobe still cover it evenly, whatever uc is (uc is left to the lobe's own
  // choice, the dielectric's reflection or transmission). With uc choosing the lobe, a fixed uc
  // would send the whole grid to one lobe. The reference samples directions uniformly, so it
  // does not share sample_f with what it checks.
  PbrMaterial m = PbrMaterial::plastic(Rgb{0.8f, 0.5f, 0.2f}, 0.4f);
  m.metallic = 0.5f;
  PbrMaterial layered = m;
  layered.clearcoat = clearcoat(0.6f, 0.3f);
  layered.sheen = sheen({0.5f, 0.5f, 1}, 0.5f);
  SurfacePoint tilted;  // a coat normal map's tilt: the coat samples in a frame of its own
  tilted.coat_normal = normalize(Vec3f(0.3f, -0.2f, 1));
  for (const Case& c : {Case{"half-metallic gold", [&] { return bsdf_of(m); }},
                        Case{"half-metallic gold under a clear coat and a sheen", [&] { return bsdf_of(layered); }},
                        Case{"the same under a tilted clear coat", [&] { return bsdf_of(layered, 1, tilted); }}}) {
    const Bsdf<N> b = c.make();
    Rng rng(41, 0);
    for (float cos_o : {0.9f, 0.4f}) {
      const Vec3f wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
      const Estimate reference = albedo_uniform_sampling(c, b, wo, 1000000, rng);
      for (float uc : {0.02f, 0.5f, 0.98f}) {
        constexpr int k = 256;
        SampledSpectrum<N> sum(0.f);
        for (int i = 0; i < k; ++i)
          for (int j = 0; j < k; ++j) {
            const auto s = bsdf_sample_f(b, wo, uc, {(float(i) + 0.5f) / k, (float(j) + 0.5f) / k});
            if (s && s->pdf > 0) sum += s->f * (abs_cos_theta(s->wi) / s->pdf);
          }
        for (int i = 0; i < N; ++i) {
          INFO(c.name << ", cos θo " << cos_o << ", uc " << uc << ", lane " << i << ": grid " << sum[i] / (k * k)
                      << ", reference " << reference.mean[i] << " ± " << reference.standard_error[i]);
          CHECK(sum[i] / (k * k) == Approx(reference.mean[i]).margin(4 * reference.standard_error[i] + 1e-3));
        }
      }
    }
  }
}

TEST_CASE("a BSDF sample and eval carry exactly what f and pdf give on their own (bit for bit)") {
  // The mixtures reuse the f and pdf their sampled lobe computed, and eval shares work between f
  // and pdf: each must give exactly what f and pdf give on their own. (A mixture's f is its eval's
  // f, so there the first check holds by construction; its pdf is summed on its own.)
  Rng rng(37, 0);
  std::vector<Case> all = cases();
  for (float roughness : {0.05f, 0.3f, 1.f})  // a coat normal map's tilt: the coat in a frame of its own
    all.push_back({"clearcoat with a tilted normal, roughness " + std::to_string(roughness), [=] {
                     PbrMaterial m = PbrMaterial::plastic({0.8f, 0.1f, 0.1f}, 0.5f);
                     m.clearcoat = clearcoat(1, roughness);
                     SurfacePoint at;
                     at.coat_normal = normalize(Vec3f(0.3f, -0.2f, 1));
                     return bsdf_of(m, 1, at);
                   }});
  for (const Case& c : all) {
    const Bsdf<N> b = c.make();
    for (int k = 0; k < 100; ++k) {
      const Vec3f wo = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const Vec3f wi = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const float uc = rng.uniform();
      const Vec2f u(rng.uniform(), rng.uniform());
      INFO(c.name << ", sample " << k);
      const BsdfEval<N> e = bsdf_eval(b, wo, wi);
      const SampledSpectrum<N> f = bsdf_f(b, wo, wi);
      for (int i = 0; i < N; ++i) CHECK(e.f[i] == f[i]);
      CHECK(e.pdf == bsdf_pdf(b, wo, wi));
      const auto s = bsdf_sample_f(b, wo, uc, u);
      if (!s || s->specular) continue;
      const SampledSpectrum<N> fs = bsdf_f(b, wo, s->wi);
      for (int i = 0; i < N; ++i) CHECK(s->f[i] == fs[i]);
      CHECK(s->pdf == bsdf_pdf(b, wo, s->wi));
    }
  }
}

TEST_CASE("the glTF base is energy-consistent: a white plastic reflects everything it does not transmit") {
  // ρ = 1 under a specular layer: albedo = E_spec(μ) + (1 − E(μ)) · 1 = 1 up to the tabulated E.
  // Also thin-walled, as every glTF material without KHR_materials_volume is: an opaque wall has no
  // far face (it reflected the thin wall's R' = 0.077 at normal incidence, 1.035 in all); a partly
  // clear one (transmission t) is a sheet on its clear share only (it returned up to
  // 1 + t(1 − t)(R' − R): 1.009 at normal incidence, 1.03 at cos θ 0.1, t = 0.5).
  Rng rng(23, 0);
  for (bool thin : {false, true})
    for (float transmission : {0.f, 0.25f, 0.5f, 0.75f}) {
      if (transmission > 0 && !thin) continue;  // a solid's transmission refracts into its volume
      for (float roughness : {0.f, 0.3f, 1.f}) {
        const Case c{"white plastic", {}, false, thin ? 1.f : 1.5f};
        PbrMaterial m = PbrMaterial::plastic(Rgb{1, 1, 1}, roughness);
        m.dielectric = Dielectric(ConstantIor{1.5f}, {}, thin);
        m.transmission = transmission;
        const Bsdf<N> b = bsdf_of(m);
        for (float cos_o : {1.f, 0.5f, 0.1f, -0.5f}) {
          if (cos_o < 0 && transmission == 0) continue;  // two-sided: the same as from the front
          const Estimate own = albedo_own_sampling(c, b, Vec3f(std::sqrt(1 - cos_o * cos_o), 0, cos_o), 100000, rng);
          INFO((thin ? "thin-walled, " : "")
               << "transmission " << transmission << ", roughness " << roughness << ", cos θo " << cos_o << ": albedo "
               << own.mean[0] << " ± " << own.standard_error[0]);
          CHECK(own.mean[0] == Approx(1).margin(4 * own.standard_error[0] + 5e-3));
        }
      }
    }
}

TEST_CASE("the extensions' lobes are reciprocal: f(wo, wi) = f(wi, wo)") {
  Rng rng(29, 0);
  for (float roughness : {0.05f, 0.3f, 1.f})
    // Single scattering: the layering is reciprocal; Turquin's compensation of the base lobes
    // (a factor in μ_o alone) is not, by design, and is checked for energy elsewhere.
    for (const Case& c : layered_cases(roughness, false)) {
      if (c.eta != 1) continue;  // refraction scales radiance by η²: not symmetric by design
      const Bsdf<N> b = c.make();
      for (int k = 0; k < 200; ++k) {
        const Vec3f wo = sample_uniform_sphere({rng.uniform(), rng.uniform()});
        const Vec3f wi = sample_uniform_sphere({rng.uniform(), rng.uniform()});
        const auto f1 = bsdf_f(b, wo, wi), f2 = bsdf_f(b, wi, wo);
        for (int i = 0; i < N; ++i) {
          INFO(c.name << " lane " << i << ": " << f1[i] << " vs " << f2[i]);
          CHECK(f1[i] == Approx(f2[i]).epsilon(1e-4).margin(1e-6));
        }
      }
    }
}

TEST_CASE("the extensions at their neutral values reproduce the base bit for bit") {
  Rng rng(31, 0);
  for (float roughness : {0.f, 0.3f, 1.f})
    for (const PbrMaterial& base : {PbrMaterial::plastic(Rgb{0.5f, 0.7f, 0.2f}, roughness),
                                    PbrMaterial::metal_of(MaterialCatalogue::standard().metal("Au"), roughness),
                                    PbrMaterial::glass(Dielectric(ConstantIor{1.5f}), roughness), [&] {
                                      PbrMaterial brushed = PbrMaterial::metal_of(Rgb{0.9f, 0.9f, 0.9f}, roughness);
                                      brushed.anisotropy_strength = 0.6f;
                                      return brushed;
                                    }()}) {
      PbrMaterial neutral = base;
      neutral.clearcoat = clearcoat(0, 0.5f);
      neutral.sheen = sheen({0, 0, 0}, 0.5f);
      neutral.iridescence = iridescence(0, 1.8f, 400);
      neutral.specular_color = {1, 1, 1};
      neutral.diffuse_transmission = diffuse_transmission(0, {0.5f, 0.5f, 0.5f});
      const Bsdf<N> a = bsdf_of(base), b = bsdf_of(neutral);
      const auto same = [](const SampledSpectrum<N>& x, const SampledSpectrum<N>& y) {
        for (int i = 0; i < N; ++i)
          if (x[i] != y[i]) return false;
        return true;
      };
      for (int k = 0; k < 200; ++k) {
        const Vec3f wo = sample_uniform_sphere({rng.uniform(), rng.uniform()});
        const Vec3f wi = sample_uniform_sphere({rng.uniform(), rng.uniform()});
        const float uc = rng.uniform();
        const Vec2f u(rng.uniform(), rng.uniform());
        INFO("roughness " << roughness << " sample " << k);
        CHECK(same(bsdf_f(a, wo, wi), bsdf_f(b, wo, wi)));
        CHECK(bsdf_pdf(a, wo, wi) == bsdf_pdf(b, wo, wi));
        const auto sa = bsdf_sample_f(a, wo, uc, u), sb = bsdf_sample_f(b, wo, uc, u);
        REQUIRE(sa.has_value() == sb.has_value());
        if (sa) CHECK((same(sa->f, sb->f) && sa->wi == sb->wi && sa->pdf == sb->pdf));
      }
    }
}

TEST_CASE("with multiple-scattering compensation, lossless rough lobes reflect and transmit everything") {
  // Turquin 2019: a white conductor (F = 1) and a clear dielectric interface (R + T, from either
  // side, solid or thin) have directional albedo 1 ± 0.01 at every roughness and angle; without
  // the compensation they lose what scatters more than once (up to ~60% at roughness 1).
  Rng rng(29, 0);
  const auto conductor = [](float roughness, bool ms) {
    return Bsdf<N>(
        ConductorBsdf<N>(TrowbridgeReitz(sqr(roughness)), SampledSpectrum<N>(0.f), SampledSpectrum<N>(0.f), ms));
  };
  const auto glass = [](float roughness, float eta, bool thin, bool ms) {
    return Bsdf<N>(
        DielectricBsdf<N>(TrowbridgeReitz(sqr(roughness)), eta, SampledSpectrum<N>(1.f), thin, 1.f, 1.f, ms));
  };
  for (float roughness : {0.05f, 0.1f, 0.2f, 0.3f, 0.45f, 0.6f, 0.75f, 0.9f, 1.f}) {
    std::vector<std::pair<Case, Bsdf<N>>> lobes;
    lobes.push_back({Case{"white conductor", {}}, conductor(roughness, true)});
    for (float eta : {1.33f, 1.5f, 2.42f})
      lobes.push_back({Case{"glass", {}, true, eta}, glass(roughness, eta, false, true)});
    lobes.push_back({Case{"thin glass", {}}, glass(roughness, 1.5f, true, true)});
    for (const auto& [c, b] : lobes)
      for (float cos_o : {1.f, 0.6f, 0.25f, 0.05f, -0.2f, -0.7f}) {
        if (cos_o < 0 && c.name == "white conductor") continue;  // two-sided: the same lobe
        const Vec3f wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
        const Estimate own = albedo_own_sampling(c, b, wo, roughness > 0.7f ? 250000 : 100000, rng);
        INFO(c.name << " η " << c.eta << ", roughness " << roughness << ", cos θo " << cos_o << ": albedo "
                    << own.mean[0] << " ± " << own.standard_error[0]);
        CHECK(own.standard_error[0] < 0.0025);
        CHECK(own.mean[0] == Approx(1).margin(0.01));
      }
  }
  // Without compensation, the white metal at roughness 1 keeps E_avg ≈ 0.41... of the light.
  const Case c{"white conductor, single scattering", {}};
  double e_avg = 0;
  constexpr int kCosines = 32;
  for (int i = 0; i < kCosines; ++i) {
    const float mu = (i + 0.5f) / kCosines;
    e_avg += 2 * mu * albedo_own_sampling(c, conductor(1, false), {std::sqrt(1 - mu * mu), 0, mu}, 4000, rng).mean[0] /
             kCosines;
  }
  WARN("E_avg of a white GGX metal at roughness 1, single scattering: " << e_avg << "; table "
                                                                        << SpecularAlbedo::table().white_average(1));
  CHECK(e_avg == Approx(SpecularAlbedo::table().white_average(1)).margin(0.01));
}

TEST_CASE("anisotropic GGX: reciprocal, isotropic at strength 0, and conserving energy at every azimuth") {
  Rng rng(31, 0);
  const SampledSpectrum<N> n(0.3f), k(3.f);
  for (float roughness : {0.05f, 0.3f, 1.f}) {
    const float alpha = sqr(roughness), alpha_x = lerp(sqr(0.7f), alpha, 1.f);
    // Single scattering is reciprocal, f(wo, wi) = f(wi, wo), for the metal and the glass's reflection.
    const ConductorBsdf<N> metal(TrowbridgeReitz(alpha_x, alpha), n, k, false);
    const DielectricBsdf<N> glass(TrowbridgeReitz(alpha_x, alpha), 1.5f, SampledSpectrum<N>(1.f), false, 1, 1, false);
    for (int i = 0; i < 200; ++i) {
      Vec3f a = sample_uniform_sphere({rng.uniform(), rng.uniform()}),
            b = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      a.z = std::abs(a.z), b.z = std::abs(b.z);
      INFO("roughness " << roughness << " wo " << a.x << "," << a.y << "," << a.z << " wi " << b.x << "," << b.y << ","
                        << b.z);
      CHECK(metal.f(a, b)[0] == Approx(metal.f(b, a)[0]).epsilon(1e-4).margin(1e-6));
      CHECK(glass.f(a, b)[0] == Approx(glass.f(b, a)[0]).epsilon(1e-4).margin(1e-6));
    }
    // Strength 0 is the isotropic lobe bit for bit.
    PbrMaterial plain = PbrMaterial::metal_of(Rgb{0.9f, 0.6f, 0.3f}, roughness), zero = plain;
    zero.anisotropy_strength = 0, zero.anisotropy_rotation = {std::cos(1.f), std::sin(1.f)};
    const Bsdf<N> p = bsdf_of(plain), z = bsdf_of(zero);
    for (int i = 0; i < 100; ++i) {
      const Vec3f wo = sample_uniform_sphere({rng.uniform(), rng.uniform()}),
                  wi = sample_uniform_sphere({rng.uniform(), rng.uniform()});
      const SampledSpectrum<N> fp = bsdf_f(p, wo, wi), fz = bsdf_f(z, wo, wi);
      for (int l = 0; l < N; ++l) CHECK(std::bit_cast<uint32_t>(fp[l]) == std::bit_cast<uint32_t>(fz[l]));
      CHECK(bsdf_pdf(p, wo, wi) == bsdf_pdf(z, wo, wi));
    }
    // Energy at azimuths off the axes (the suites above view along x): the compensation of the
    // white metal uses the isotropic albedo at √(α_x α_y) (as Cycles does), an approximation that
    // may leave some energy out on strongly stretched lobes but adds at most 3%.
    const ConductorBsdf<N> white(TrowbridgeReitz(alpha_x, alpha), SampledSpectrum<N>(0.f), SampledSpectrum<N>(0.f));
    for (float phi : {0.f, 0.5f, 1.f, 1.5707963f})
      for (float cos_o : {0.9f, 0.5f, 0.15f}) {
        const float sin_o = std::sqrt(1 - cos_o * cos_o);
        const Vec3f wo(sin_o * std::cos(phi), sin_o * std::sin(phi), cos_o);
        const Estimate e = albedo_own_sampling(Case{"white", {}}, Bsdf<N>(white), wo, 60000, rng);
        INFO("roughness " << roughness << " φ " << phi << " cos θo " << cos_o << ": albedo " << e.mean[0] << " ± "
                          << e.standard_error[0]);
        CHECK(e.mean[0] <= 1.03 + 4 * e.standard_error[0]);
        CHECK(e.mean[0] >= 0.75);
      }
  }
}
