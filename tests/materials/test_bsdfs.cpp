// BSDF lobes: energy (R + T = 1 for clear dielectrics), reciprocity, sampling against pdf.

#include <catch2/catch.hpp>
#include <limits>

#include "core/base/rng.h"
#include "core/base/warp.h"
#include "materials/make_bsdf.h"
#include "tests/support/chi2.h"

using namespace prism;

TEST_CASE("smooth dielectric: R + T = 1 over angles, indices and wavelengths, with radiance scaling") {
  for (float eta : {1.0f, 1.0001f, 1.33f, 1.5f, 2.42f, 4.f, 1 / 1.5f})
    for (float c = -1; c <= 1; c += 0.05f) {
      if (c == 0) continue;
      const Vec3f wo(std::sqrt(std::max(0.f, 1 - c * c)), 0, c);
      const DielectricBsdf<4> bsdf(TrowbridgeReitz(0.f), eta, SampledSpectrum<4>(1.f), false);
      const float R = bsdf.reflectance(wo)[0];
      const auto t = bsdf.transmission(wo);
      const float T = t ? t->weight[0] * sqr(t->eta) : 0.f;  // undo the 1/η² radiance scaling
      INFO("eta " << eta << " cos " << c);
      CHECK(R + T == Approx(1).margin(1e-6));
      // Sampling: reflection with probability R, transmission with 1 − R, weights f·|cos|/pdf.
      const auto r = bsdf.sample_f(wo, 0.f, {});
      REQUIRE(r);
      if (R > 0) CHECK(r->f[0] * abs_cos_theta(r->wi) / r->pdf == Approx(1).epsilon(1e-5));
      if (const float uc = R + 0.5f * (1 - R); t && uc > R && uc < 1) {
        const auto s = bsdf.sample_f(wo, uc, {});
        REQUIRE(s);
        CHECK(s->transmission);
        CHECK(s->f[0] * abs_cos_theta(s->wi) / s->pdf * sqr(s->eta) == Approx(1).epsilon(1e-5));
      }
    }
  // Thin wall: the sheet's R' + T' = 1 too, and light goes straight through.
  const DielectricBsdf<4> thin(TrowbridgeReitz(0.f), 1.5f, SampledSpectrum<4>(1.f), true);
  const Vec3f wo = normalize(Vec3f(0.5f, 0.1f, 0.8f));
  const auto t = thin.transmission(wo);
  REQUIRE(t);
  CHECK(thin.reflectance(wo)[0] + t->weight[0] == Approx(1).margin(1e-6));
  CHECK(length(t->wi + wo) == Approx(0).margin(1e-6));
  CHECK(thin.reflectance(wo)[0] > fresnel_dielectric(wo.z, 1.5f));  // two interfaces reflect more
  // Each polarisation's inter-reflections summed apart: T' = ½ Σ (1 − R_x) / (1 + R_x), x = s, p.
  for (const float c : {1.f, 0.8f, 0.5f, 0.3f, 0.1f}) {
    const Vec3f w(std::sqrt(1 - c * c), 0, c);
    const FresnelReflectance F = fresnel_dielectric_polarized(c, 1.5f);
    const double expected = ((1.0 - F.Rs) / (1.0 + F.Rs) + (1.0 - F.Rp) / (1.0 + F.Rp)) / 2;
    INFO("cos " << c);
    CHECK(thin.transmission(w)->weight[0] == Approx(expected).margin(1e-6));
  }
}

TEST_CASE("refraction is reciprocal: the same share both ways, radiance weights differ by eta squared") {
  for (float eta : {1.33f, 1.5f, 2.42f}) {
    const DielectricBsdf<1> bsdf(TrowbridgeReitz(0.f), eta, SampledSpectrum<1>(1.f), false);
    const Vec3f wo = normalize(Vec3f(0.4f, 0.2f, 0.7f));  // outside (n = 1)
    const auto t = bsdf.transmission(wo);
    REQUIRE(t);
    const auto back = bsdf.transmission(t->wi);  // from inside (n = η) back out
    REQUIRE(back);
    CHECK(length(back->wi - wo) == Approx(0).margin(1e-5));  // the optical path reverses
    // Stokes: T(θ_o) = T(θ_t); Veach 1997 §5.2: radiance gains η² entering, loses it leaving.
    CHECK(t->weight[0] * sqr(eta) == Approx(back->weight[0] / sqr(eta)).epsilon(1e-5));
    CHECK(t->eta == Approx(eta));
    CHECK(back->eta == Approx(1 / eta));
  }
}

TEST_CASE("Lambertian BSDF: reciprocal, albedo R, sampling follows its pdf (chi-square)") {
  const DiffuseBsdf<4> bsdf(SampledSpectrum<4>(0.6f));
  Rng rng(3, 0);
  for (int i = 0; i < 100; ++i) {
    const Vec3f a = sample_uniform_hemisphere({rng.uniform(), rng.uniform()});
    const Vec3f b = sample_uniform_hemisphere({rng.uniform(), rng.uniform()});
    CHECK(bsdf.f(a, b)[0] == bsdf.f(b, a)[0]);
  }
  for (const Vec3f wo : {Vec3f(0, 0, 1), normalize(Vec3f(1, 0, 0.2f)), normalize(Vec3f(0.3f, 0.3f, -0.5f))}) {
    const auto result = test::chi2_test(
        [&](float u1, float u2, float u3) -> std::optional<Vec3f> {
          const auto s = bsdf.sample_f(wo, u1, {u2, u3});
          return s ? std::optional<Vec3f>(s->wi) : std::nullopt;
        },
        [&](const Vec3f& wi) { return double(bsdf.pdf(wo, wi)); });
    INFO("wo " << wo.x << "," << wo.y << "," << wo.z << " chi2 " << result.statistic << " dof "
               << result.degrees_of_freedom << " p " << result.p_value);
    CHECK(result.passed);
  }
  // Albedo by Monte Carlo with the lobe's own sampling: exactly R for every sample.
  const auto s = bsdf.sample_f(Vec3f(0, 0, 1), 0.5f, {0.3f, 0.7f});
  REQUIRE(s);
  CHECK(s->f[0] * abs_cos_theta(s->wi) / s->pdf == Approx(0.6f));
}

TEST_CASE("the chi-square test accepts a sampler with its own pdf and rejects it with another") {
  const auto uniform = [](float, float u2, float u3) -> std::optional<Vec3f> {
    return sample_uniform_hemisphere({u2, u3});
  };
  CHECK(
      test::chi2_test(uniform, [](const Vec3f& w) { return w.z > 0 ? double(uniform_hemisphere_pdf()) : 0.0; }).passed);
  CHECK_FALSE(test::chi2_test(uniform, [](const Vec3f& w) {
                return w.z > 0 ? double(cosine_hemisphere_pdf(w.z)) : 0.0;
              }).passed);
}

TEST_CASE("smooth conductor reflects the exact Fresnel reflectance per wavelength") {
  SampledSpectrum<4> n, k;
  for (int i = 0; i < 4; ++i) n[i] = 0.2f + 0.3f * i, k[i] = 3.f + i;
  const ConductorBsdf<4> bsdf(TrowbridgeReitz(0.f), n, k);
  const Vec3f wo = normalize(Vec3f(0.6f, 0, 0.8f));
  const auto s = bsdf.sample_f(wo, 0.5f, {});
  REQUIRE(s);
  CHECK(s->specular);
  for (int i = 0; i < 4; ++i)
    CHECK(s->f[i] * abs_cos_theta(s->wi) / s->pdf == Approx(fresnel_conductor(0.8f, n[i], k[i])));
}

TEST_CASE("a metal made from a colour reflects that colour at normal incidence") {
  // Every lane its own reflectance, from black to nearly white (lanes are found all at once).
  const SampledSpectrum<8> r(std::array{0.f, 0.01f, 0.2f, 0.455f, 0.7f, 0.9f, 0.99f, 0.999f});
  const MetalIndex<8> lanes = metal_nk_from_reflectance(r);
  for (int i = 0; i < 8; ++i) CHECK(fresnel_conductor(1, lanes.n[i], lanes.k[i]) == Approx(r[i]).margin(1e-4));
  // Out of range, and NaN, as black or the brightest metal, never outside the edge-tint table.
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const MetalIndex<8> clamped =
      metal_nk_from_reflectance(SampledSpectrum<8>(std::array{-1.f, 2.f, kNaN, 0.5f, 0.f, 0.f, 0.f, 0.f}));
  CHECK(fresnel_conductor(1, clamped.n[0], clamped.k[0]) == Approx(0).margin(1e-4));
  CHECK(fresnel_conductor(1, clamped.n[1], clamped.k[1]) == Approx(0.999).margin(1e-4));
  CHECK(fresnel_conductor(1, clamped.n[2], clamped.k[2]) == Approx(0).margin(1e-4));
  const float n = lanes.n[4], k = lanes.k[4];
  // Its directional albedo matches glTF's reference (Schlick) metal of the same colour.
  double exact = 0, schlick = 0;
  for (int i = 0; i < 1000; ++i) {
    const double c = (i + 0.5) / 1000;
    exact += fresnel_conductor(float(c), n, k) * 2 * c / 1000;
    schlick += (0.7 + 0.3 * std::pow(1 - c, 5)) * 2 * c / 1000;
  }
  CHECK(exact == Approx(schlick).margin(2e-3));
}

TEST_CASE("a compensated rough lobe samples again where a visible normal fails, and its weight stays near 1") {
  // Inside rough glass (η = 1/1.5, α = 1) a third of the visible normals send wo to the wrong side;
  // compensated, the lobe tries again, so that hardly a sample is lost and the sampled weights
  // f cos / pdf (about 1 for a lossless lobe) vary far less than with one try.
  const TrowbridgeReitz rough(1.f);
  const auto stats = [&](const auto& bsdf, const Vec3f& wo) {
    Rng rng(5, 0);
    int lost = 0;
    double sum = 0, sum_sq = 0;
    constexpr int kSamples = 100000;
    for (int i = 0; i < kSamples; ++i) {
      const auto s = bsdf.sample_f(wo, rng.uniform(), {rng.uniform(), rng.uniform()});
      double w = 0;
      if (s && s->pdf > 0)
        w = s->f[0] * abs_cos_theta(s->wi) / s->pdf * (same_hemisphere(wo, s->wi) ? 1 : sqr(wo.z > 0 ? 1.5 : 1 / 1.5));
      else
        ++lost;
      sum += w, sum_sq += w * w;
    }
    const double mean = sum / kSamples;
    return std::array<double, 3>{double(lost) / kSamples, mean, sum_sq / kSamples / (mean * mean) - 1};
  };
  for (const float mu : {-0.9f, -0.5f, -0.1f}) {
    const Vec3f wo(std::sqrt(1 - mu * mu), 0, mu);
    const auto [lost_once, mean_once, relvar_once] =
        stats(DielectricBsdf<1>(rough, 1.5f, SampledSpectrum<1>(1.f), false, 1, 1, false), wo);
    const auto [lost, mean, relvar] = stats(DielectricBsdf<1>(rough, 1.5f, SampledSpectrum<1>(1.f), false), wo);
    INFO("cos θo " << mu << ": lost " << lost << " (one try " << lost_once << "), albedo " << mean
                   << ", relative variance " << relvar << " (one try, uncompensated " << relvar_once << ")");
    CHECK(lost_once > 0.2);
    CHECK(lost < 0.01);
    CHECK(mean == Approx(1).margin(0.01));
    CHECK(relvar < relvar_once / 3);
  }
  // A rough white metal (n = k = 0: F = 1), half of whose visible normals reflect below it.
  const ConductorBsdf<1> metal(rough, SampledSpectrum<1>(0.f), SampledSpectrum<1>(0.f));
  const auto [lost, mean, relvar] = stats(metal, Vec3f(0, 0, 1));
  INFO("white metal: lost " << lost << ", albedo " << mean);
  CHECK(lost < 0.01);
  CHECK(mean == Approx(1).margin(0.01));
}
