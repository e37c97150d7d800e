// albedo_tables: computes the directional albedos of the GGX and sheen lobes and the thin film's
// reflectance excess (materials/albedo_tables.h) and writes them as C++ source,
// albedo_tables_data.cpp. The build runs it once (a few seconds on 2 cores; see
// materials/CMakeLists.txt) and compiles the result into prism::materials.

#include "materials/albedo_tables.h"

#include <fmt/format.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "core/base/parallel.h"
#include "core/base/sampler.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "materials/sheen_bsdf.h"
#include "materials/thin_film.h"

namespace {

using namespace prism;
using namespace prism::albedo_tables;

// The albedos of one direction: reflection with Fresnel, reflection + transmission, reflection with F = 1; and the
// probabilities that a sampled visible normal gives a direction on the intended side: the interface's (reflection
// chosen with probability F, refraction otherwise) and the reflection's alone.
struct Albedos {
  float r, rt, white, valid, white_valid;
};

// E(μ) = ∫ f(wo, wi) |cos θ_i| dω_i by quasi-Monte Carlo visible-normal sampling over a
// Hammersley set (Heitz 2018: f |cos θ_i| / pdf is F G(wo, wi)/G1(wo) for reflection,
// (1 − F) G(wo, wt)/G1(wo) for transmission). 1024 points reach 10⁻³; a 24 × 24 grid of strata
// missed by up to 5% where few normals send light below the horizon.
Albedos directional_albedos(float mu, float alpha, float eta) {
  if (TrowbridgeReitz::effectively_smooth(alpha)) return {fresnel_dielectric(mu, eta), 1, 1, 1, 1};
  const TrowbridgeReitz d(alpha);
  const Vec3f wo(std::sqrt(std::max(0.f, 1 - mu * mu)), 0, mu);
  constexpr int kPoints = 1024;
  double r = 0, t = 0, white = 0, valid = 0, white_valid = 0;
  for (uint32_t i = 0; i < kPoints; ++i) {
    // Both coordinates at the middle of their strata: (i + ½)/n and the van der Corput radical inverse + ½/n.
    const float radical_inverse = float(sobol::reverse_bits(i)) * 0x1p-32f + 0.5f / kPoints;
    const Vec3f wm = d.sample_visible_normal(wo, {(float(i) + 0.5f) / kPoints, radical_inverse});
    const float F = fresnel_dielectric(dot(wo, wm), eta);
    if (const Vec3f wi = reflect(wo, wm); wi.z > 0) {
      const double g = d.G(wo, wi) / d.G1(wo);
      r += F * g, white += g;
      valid += F, white_valid += 1;
    }
    if (eta == 1) {
      t += 1, valid += 1;  // index-matched: the interface is not there
    } else if (const auto refraction = refract(wo, wm, eta); refraction && refraction->wt.z < 0) {
      t += (1 - F) * d.G(wo, refraction->wt) / d.G1(wo);
      valid += 1 - F;
    }
  }
  constexpr double n = kPoints;
  return {float(r / n), float((r + t) / n), float(white / n), float(valid / n), float(white_valid / n)};
}

// E_avg of exactly the function the renderer reads (`smooth` below the roughness the microfacet
// code treats as a mirror, the interpolated grid otherwise), so that a coupled diffuse lobe's
// albedo is exactly (1 − E(μ_o)) ρ.
void fill_averages(Grid& g, const std::function<float(float mu)>& smooth) {
  constexpr int kSteps = 1024;
  for (int a = 0; a < kAlpha; ++a) {
    const float alpha = alpha_of(a);
    double sum = 0;
    for (int k = 0; k < kSteps; ++k) {
      const float mu = (k + 0.5f) / kSteps;
      const float e = TrowbridgeReitz::effectively_smooth(alpha) ? smooth(mu) : g.at(point(mu, alpha));
      sum += 2.0 * e * mu / kSteps;
    }
    g.avg[a] = float(sum);
  }
}

void fill_slice(Slice& s, int h) {
  const float eta = eta_of(h);
  for (int a = 0; a < kAlpha; ++a)
    for (int m = 0; m < kMu; ++m) {
      const Albedos e = directional_albedos(mu_of(m), alpha_of(a), eta);
      const int i = a * kMu + m;
      s.r.e[i] = e.r, s.rt.e[i] = e.rt, s.r_compensated.e[i] = e.r / e.rt, s.valid.e[i] = e.valid;
    }
  const auto fresnel = [eta](float mu) { return fresnel_dielectric(mu, eta); };
  fill_averages(s.r, fresnel);
  fill_averages(s.r_compensated, fresnel);
  fill_averages(s.rt, [](float) { return 1.f; });
}

void fill_white(Grid& g, Table& valid) {
  for (int a = 0; a < kAlpha; ++a)
    for (int m = 0; m < kMu; ++m) {
      const Albedos e = directional_albedos(mu_of(m), alpha_of(a), 1.5f);
      g.e[a * kMu + m] = e.white, valid.e[a * kMu + m] = e.white_valid;
    }
  fill_averages(g, [](float) { return 1.f; });
}

// ∫ D G / (4 μ_o μ_i) μ_i dω_i of the Charlie sheen by the midpoint rule in (x, φ), μ_i = x² (dense
// at grazing, where the lobe of low roughness lies), φ over [0, π] by symmetry.
float sheen_albedo(const CharlieSheen& sheen, float mu) {
  const Vec3f wo(std::sqrt(std::max(0.f, 1 - mu * mu)), 0, mu);
  constexpr int kX = 192, kPhi = 96;
  double sum = 0;
  for (int i = 0; i < kX; ++i) {
    const float x = (i + 0.5f) / kX, mu_i = x * x, sin_i = std::sqrt(1 - mu_i * mu_i);
    for (int j = 0; j < kPhi; ++j) {
      const float phi = kPi * (j + 0.5f) / kPhi;
      const Vec3f wi(sin_i * std::cos(phi), sin_i * std::sin(phi), mu_i);
      sum += sheen.value(wo, wi) * mu_i * 2 * x;  // dμ = 2x dx
    }
  }
  return float(sum * 2 * kPi / (kX * kPhi));  // dω = dμ dφ; two halves of φ
}

// One roughness row of the sheen table, divided by its peak when that exceeds 1 (the fitted lobe
// reflects more than it receives at grazing angles and low roughness); returns the scale.
float fill_sheen_row(float* e, int a) {
  const CharlieSheen sheen(sheen_alpha_of(a));
  float peak = 1;
  for (int m = 0; m < kSheenMu; ++m) peak = std::max(peak, e[m] = sheen_albedo(sheen, sheen_mu_of(m)));
  for (int m = 0; m < kSheenMu; ++m) e[m] /= peak;
  return 1 / peak;
}

// One film index's row of the film excess at the nodes, over the base's index.
void fill_film_row(float* film, int a) {
  for (int b = 0; b <= kFilmSteps; ++b)
    film[a * (kFilmSteps + 1) + b] = film_reflectance_excess_exact(film_index_of(a), film_index_of(b));
}
// Each cell's largest corner, from the nodes: what a lookup anywhere in the cell reads.
void fill_film_cells(const float* film, float* cells) {
  for (int a = 0; a < kFilmSteps; ++a)
    for (int b = 0; b < kFilmSteps; ++b) {
      const float* e = film + a * (kFilmSteps + 1) + b;
      cells[a * kFilmSteps + b] = std::max(std::max(e[0], e[1]), std::max(e[kFilmSteps + 1], e[kFilmSteps + 2]));
    }
}

// Floats as hexadecimal literals: exact.
std::string array(const float* v, int n) {
  std::string s = "{";
  for (int i = 0; i < n; ++i) s += fmt::format("{}{:a}f", i % 8 ? " " : "\n", v[i]) + (i + 1 < n ? "," : "");
  return s + "}";
}
std::string table(const Table& t) { return fmt::format("{{{}}}", array(t.e, kAlpha * kMu)); }
std::string grid(const Grid& g) { return fmt::format("{{{},\n{}}}", table(g), array(g.avg, kAlpha)); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: albedo_tables OUTPUT.cpp\n");
    return 2;
  }
  const auto slices = std::make_unique<Slice[]>(kEta);
  const auto white = std::make_unique<Grid>();
  const auto white_valid = std::make_unique<Table>();
  float sheen_e[kSheenAlpha * kSheenMu], sheen_scale[kSheenAlpha];
  float film[(kFilmSteps + 1) * (kFilmSteps + 1)];
  parallel_for(kEta + 1 + kSheenAlpha + kFilmSteps + 1, [&](int64_t i) {
    if (i < kEta)
      fill_slice(slices[i], int(i));
    else if (i == kEta)
      fill_white(*white, *white_valid);
    else if (i < kEta + 1 + kSheenAlpha)
      sheen_scale[i - kEta - 1] = fill_sheen_row(sheen_e + (i - kEta - 1) * kSheenMu, int(i - kEta - 1));
    else
      fill_film_row(film, int(i - kEta - 1 - kSheenAlpha));
  });
  float film_cells[kFilmSteps * kFilmSteps];
  fill_film_cells(film, film_cells);

  std::string out =
      "// Generated by apps/albedo_tables.cpp at build time; see materials/albedo_tables.h.\n"
      "#include \"materials/albedo_tables.h\"\n\nnamespace prism::albedo_tables {\n\nconst Slice specular[kEta] = {";
  for (int h = 0; h < kEta; ++h)
    out +=
        fmt::format("\n// eta {}\n{{{},\n{},\n{},\n{}}}{}", eta_of(h), grid(slices[h].r), grid(slices[h].r_compensated),
                    grid(slices[h].rt), table(slices[h].valid), h + 1 < kEta ? "," : "");
  out += "};\n\nconst Grid specular_white = " + grid(*white) +
         ";\n\nconst Table specular_white_valid = " + table(*white_valid) +
         ";\n\nconst float sheen_e[kSheenAlpha * kSheenMu] = " + array(sheen_e, kSheenAlpha * kSheenMu) +
         ";\n\nconst float sheen_scale[kSheenAlpha] = " + array(sheen_scale, kSheenAlpha) +
         ";\n\nconst float film_excess[kFilmSteps * kFilmSteps] = " + array(film_cells, kFilmSteps * kFilmSteps) +
         ";\n\n}  // namespace prism::albedo_tables\n";
  const std::string tmp = std::string(argv[1]) + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f || std::fwrite(out.data(), 1, out.size(), f) != out.size() || std::fclose(f) != 0 ||
      std::rename(tmp.c_str(), argv[1]) != 0) {
    std::fprintf(stderr, "albedo_tables: cannot write %s\n", argv[1]);
    return 1;
  }
  return 0;
}
