#pragma once
// The directional-albedo tables of the specular and sheen lobes (specular_albedo.h,
// sheen_albedo.h), and the thin film's reflectance excess (thin_film.h): their layout, their interpolation, and the
// data. The data are computed by the project at build time (apps/albedo_tables.cpp writes albedo_tables_data.cpp,
// compiled into prism::materials), so no render pays for them and every run reads the same numbers.

#include <algorithm>
#include <cmath>

namespace prism::albedo_tables {

// Specular: E over (α, μ) on nodes uniform in ∛α and √μ, one table per index η on nodes uniform in
// x = (η − 1)/(η + 1) ∈ [−1/2, 1/2] (η ∈ [1/3, 3]).
constexpr int kMu = 32, kAlpha = 32, kEta = 31;
constexpr float kMaxX = 0.5f;

// Linear interpolation weights of v on a uniform grid of n nodes over [0, hi].
struct Lerp {
  int i;
  float t;
};
inline Lerp locate(float v, float hi, int n) {
  const float x = std::clamp(v / hi, 0.f, 1.f) * float(n - 1);
  const int i = std::min(int(x), n - 2);
  return {i, x - float(i)};
}
// The same for η, without branches, so that a loop over a path's lanes runs on all of them at once
// (SpecularAlbedo::Lanes; clamping x before converting it, GCC would branch): (η − 1)/(η + 1) ∈ [−1, 1]
// for any η ≥ 0, so x lies within the grid's span either side of it and converts exactly.
inline Lerp locate_eta(float eta) {
  const float x = ((eta - 1) / (eta + 1) + kMaxX) / (2 * kMaxX) * float(kEta - 1);
  const int i = std::clamp(int(x), 0, kEta - 2);
  return {i, std::min(std::max(x - float(i), 0.f), 1.f)};
}
inline float eta_of(int h) {
  const float x = 2 * kMaxX * float(h) / (kEta - 1) - kMaxX;
  return (1 + x) / (1 - x);
}
inline float alpha_of(int a) { return float(std::pow(float(a) / (kAlpha - 1), 3)); }
// Nodes uniform in √μ, dense where E changes fastest (grazing); μ = 0 itself is never met, a
// grazing neighbour stands in.
inline float mu_of(int m) {
  const float s = float(m) / (kMu - 1);
  return std::max(s * s, 1e-4f);
}

// Where (μ, α) falls on the grids' axes (∛α, √μ): cell and weights, shared by the grids read.
struct Point {
  int a, m;
  float ta, tm;
};
inline Lerp alpha_node(float alpha) { return locate(std::cbrt(alpha), 1, kAlpha); }
// Where μ falls on a table's n nodes uniform in √μ (the specular tables' and the sheen's).
inline Lerp mu_node(float mu, int n = kMu) { return locate(std::sqrt(std::max(mu, 0.f)), 1, n); }
inline Point point(float mu, const Lerp& a) {
  const Lerp m = mu_node(mu);
  return {a.i, m.i, a.t, m.t};
}
inline Point point(float mu, float alpha) { return point(mu, alpha_node(alpha)); }

// One quantity over (α, μ).
struct Table {
  float e[kAlpha * kMu];

  float at(const Point& p) const {  // bilinear
    float r = 0;
    for (int k = 0; k < 4; ++k) {
      const int da = k & 1, dm = k >> 1;
      r += (da ? p.ta : 1 - p.ta) * (dm ? p.tm : 1 - p.tm) * e[(p.a + da) * kMu + (p.m + dm)];
    }
    return r;
  }
};

// One table of E over (α, μ) and its cosine-weighted averages E_avg = 2∫ E(μ) μ dμ, per α.
struct Grid : Table {
  float avg[kAlpha];

  float average(const Lerp& a) const { return (1 - a.t) * avg[a.i] + a.t * avg[a.i + 1]; }  // a: where ∛α falls
};

// An η slice: reflection, reflection compensated (divided by reflection + transmission), reflection + transmission,
// and the probability that the interface's sampling (a visible normal, then reflection with probability F, else
// refraction) finds a direction on the side it meant to.
struct Slice {
  Grid r, r_compensated, rt;
  Table valid;
};

// Sheen: E over (α, μ) on nodes uniform in √α and √μ, and the scale that keeps the lobe's albedo ≤ 1.
constexpr int kSheenMu = 32, kSheenAlpha = 32;
inline float sheen_alpha_of(int a) {
  const float s = float(a) / (kSheenAlpha - 1);
  return s * s;
}
inline Lerp sheen_alpha_node(float alpha) { return locate(std::sqrt(std::clamp(alpha, 0.f, 1.f)), 1, kSheenAlpha); }
inline float sheen_mu_of(int m) {
  const float s = float(m) / (kSheenMu - 1);
  return std::max(s * s, 1e-4f);
}

// Thin film: the most its reflectance exceeds its coupling interface's (film_reflectance_excess,
// thin_film.h), on nodes 0.05 apart in the film's and the base's indices n_f, η ∈ [1, 3], kept as
// each cell's largest corner (one read bounds the excess anywhere in the cell).
constexpr int kFilmSteps = 40;
constexpr float kFilmStep = 2.f / kFilmSteps;
inline float film_index_of(int a) { return 1 + float(a) * kFilmStep; }

// The data (albedo_tables_data.cpp, generated).
extern const Slice specular[kEta];
extern const Grid specular_white;         // reflection with F = 1
extern const Table specular_white_valid;  // the probability that a visible normal reflects wo above the surface
extern const float sheen_e[kSheenAlpha * kSheenMu];
extern const float sheen_scale[kSheenAlpha];
extern const float film_excess[kFilmSteps * kFilmSteps];  // [n_f cell][η cell]

}  // namespace prism::albedo_tables
