// Core utilities: transforms, frames, random numbers, warps.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <utility>
#include <vector>

#include "core/base/frame.h"
#include "core/base/math.h"
#include "core/base/rng.h"
#include "core/base/sampler.h"
#include "core/base/transform.h"
#include "core/base/warp.h"
#include "tests/support/chi2.h"

using namespace prism;

TEST_CASE("transforms compose and invert") {
  const Transform t =
      Transform::translate({1, 2, 3}) * Transform::rotate(0.1, 0.7, -0.2, 0.68) * Transform::scale({2, -0.5, 3});
  const Transform round = t * inverse(t);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) CHECK(round.m[i][j] == Approx(i == j ? 1 : 0).margin(1e-12));
  CHECK(determinant3x3(t) < 0);  // the negative scale mirrors
  const Vec3d p = t.point({1, 1, 1});
  const Vec3d back = inverse(t).point(p);
  CHECK(back.x == Approx(1));
  CHECK(back.y == Approx(1));
  CHECK(back.z == Approx(1));
  // A 90° turn about y (glTF quaternion x, y, z, w) takes +x to −z.
  const Vec3d v = Transform::rotate(0, std::sqrt(0.5), 0, std::sqrt(0.5)).vector({1, 0, 0});
  CHECK(v.z == Approx(-1));
}

TEST_CASE("frames are orthonormal and right-handed") {
  Rng rng(1, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f n = sample_uniform_sphere({rng.uniform(), rng.uniform()});
    const Frame f = Frame::from_z(n);
    CHECK(dot(f.x, f.y) == Approx(0).margin(1e-5));
    CHECK(length(f.x) == Approx(1).margin(1e-5));
    CHECK(length(cross(f.x, f.y) - n) == Approx(0).margin(1e-4));
    const Vec3f w = normalize(Vec3f(0.3f, -0.4f, 0.5f));
    CHECK(length(f.to_world(f.to_local(w)) - w) == Approx(0).margin(1e-5));
  }
}

TEST_CASE("sin_cos is within 4e-7 of sin and cos up to |x| = 10^4") {
  // Thin-film phases reach ~10² (1200 nm at n 2.5 and 360 nm); the reduction must stay exact far beyond.
  double worst = 0;
  for (int i = 0; i <= 2000000; ++i) {
    const float x = -1e4f + 2e4f * float(i) / 2000000.f;
    const SinCos sc = sin_cos(x);
    worst = std::max({worst, std::abs(sc.sin - std::sin(double(x))), std::abs(sc.cos - std::cos(double(x)))});
  }
  CHECK(worst < 4e-7);
}

TEST_CASE("PCG32 is deterministic, uniform on the unit interval and jumps ahead exactly") {
  Rng a(42, 7), b(42, 7);
  for (int i = 0; i < 100; ++i) REQUIRE(a.next_u32() == b.next_u32());
  Rng c(42, 7), d(42, 7);
  for (int i = 0; i < 1000; ++i) c.next_u32();
  d.advance(1000);
  CHECK(c.next_u32() == d.next_u32());
  Rng e(1, 0);
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const float u = e.uniform();
    REQUIRE(u >= 0.f);
    REQUIRE(u < 1.f);
    sum += u;
  }
  CHECK(sum / 100000 == Approx(0.5).margin(0.005));
}

TEST_CASE("cosine hemisphere samples have the density they report") {
  // E[g(w)/pdf(w)] = ∫ g over the hemisphere; with g = cos²θ the integral is 2π/3.
  Rng rng(2, 0);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const Vec3f w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    REQUIRE(w.z >= 0.f);
    sum += w.z * w.z / cosine_hemisphere_pdf(w.z);
  }
  CHECK(sum / n == Approx(2 * kPi / 3).epsilon(0.01));
}

TEST_CASE("the balance heuristic's weights of two strategies sum to 1, an infinite pdf takes all, zero pdfs none") {
  for (const auto& [a, b] : {std::pair{1.f, 1.f}, {0.2f, 7.f}, {1e-30f, 3.f}, {5e20f, 2e19f}, {0.f, 2.f}}) {
    INFO(a << " " << b);
    CHECK(balance_heuristic(a, b) + balance_heuristic(b, a) == Approx(1));
  }
  CHECK(balance_heuristic(1, 1) == 0.5f);
  CHECK(balance_heuristic(1, 3) == 0.25f);  // the power heuristic would give 0.1
  CHECK(balance_heuristic(INFINITY, 3) == 1);
  CHECK(balance_heuristic(0, 0) == 0);
}

TEST_CASE("uniform triangle barycentrics cover the triangle evenly") {
  Rng rng(4, 0);
  int in_corner = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const Vec3f b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
    REQUIRE(b.x >= 0.f);
    REQUIRE(b.y >= 0.f);
    REQUIRE(b.z >= -1e-6f);
    if (b.x > 0.5f) ++in_corner;  // the sub-triangle b0 > 1/2 has a quarter of the area
  }
  CHECK(double(in_corner) / n == Approx(0.25).margin(0.01));
}

TEST_CASE("reverse_bits moves bit i to bit 31 - i (the run-time path, GFNI where the build has it)") {
  const auto reversed_by_loop = [](uint32_t v) {
    uint32_t r = 0;
    for (int i = 0; i < 32; ++i) r |= (v >> i & 1u) << (31 - i);
    return r;
  };
  static_assert(sobol::reverse_bits(1u) == 0x80000000u && sobol::reverse_bits(0x12345678u) == 0x1e6a2c48u);
  Rng rng(7, 0);
  volatile uint32_t fixed[] = {0u, 1u, 0x80000000u, 0xffffffffu, 0x12345678u, 0x0000ff00u};
  for (uint32_t v : fixed) CHECK(sobol::reverse_bits(v) == reversed_by_loop(v));
  int wrong = 0;
  for (int i = 0; i < 100000; ++i) {
    const uint32_t v = rng.next_u32();
    wrong += sobol::reverse_bits(v) != reversed_by_loop(v);
  }
  CHECK(wrong == 0);
}

TEST_CASE("the Sobol sampler stratifies each dimension over a pixel's samples") {
  // With 2^k samples, every 1D request hits each of the 2^k strata exactly once, and every 2D
  // request each of the 2^(k/2) x 2^(k/2) cells (a (0,2)-net), in every dimension and pixel.
  constexpr int kSpp = 64;
  for (const Vec2i pixel : {Vec2i{0, 0}, Vec2i{17, 3}}) {
    Sampler sampler(5, SamplerKind::sobol);
    std::vector<std::vector<int>> one(6, std::vector<int>(kSpp, 0)), two(6, std::vector<int>(kSpp, 0));
    for (int s = 0; s < kSpp; ++s) {
      sampler.start_pixel_sample(pixel, s);
      for (int d = 0; d < 6; ++d) {
        const float u = sampler.get_1d();
        REQUIRE(u >= 0.f);
        REQUIRE(u < 1.f);
        ++one[d][int(u * kSpp)];
        const Vec2f v = sampler.get_2d();
        ++two[d][int(v.x * 8) * 8 + int(v.y * 8)];
      }
    }
    for (int d = 0; d < 6; ++d)
      for (int i = 0; i < kSpp; ++i) {
        INFO("dimension " << d << " stratum " << i);
        REQUIRE(one[d][i] == 1);
        REQUIRE(two[d][i] == 1);
      }
  }
  // Different pixels get different (decorrelated) points.
  Sampler a(5, SamplerKind::sobol), b(5, SamplerKind::sobol);
  a.start_pixel_sample({0, 0}, 3);
  b.start_pixel_sample({1, 0}, 3);
  CHECK(a.get_1d() != b.get_1d());
}

namespace {
// Points of one 2D request (`dimension` draws after start_bounce(bounce)) over a pixel's first n samples.
std::vector<Vec2f> sobol_points(Vec2i pixel, int n, int bounce, int dimension) {
  Sampler sampler(11, SamplerKind::sobol);
  std::vector<Vec2f> points;
  for (int s = 0; s < n; ++s) {
    sampler.start_pixel_sample(pixel, s);
    sampler.start_bounce(bounce);
    for (int d = 0; d < dimension; ++d) sampler.get_1d();
    points.push_back(sampler.get_2d());
  }
  return points;
}

// Largest and smallest number of points in the elementary intervals [a/2^j, (a+1)/2^j) x
// [b/2^(m-j), (b+1)/2^(m-j)) of area 2^-m, over every shape j = 0..m.
std::pair<int, int> elementary_interval_counts(const std::vector<Vec2f>& points, int m) {
  int lo = int(points.size()), hi = 0;
  for (int j = 0; j <= m; ++j) {
    std::vector<int> count(size_t(1) << m, 0);
    for (const Vec2f& p : points) ++count[(size_t(p.x * float(1 << j)) << (m - j)) + size_t(p.y * float(1 << (m - j)))];
    for (int c : count) lo = std::min(lo, c), hi = std::max(hi, c);
  }
  return {lo, hi};
}
}  // namespace

TEST_CASE("the Sobol sampler is a (0,2)-sequence in every 2D request, at every count and depth") {
  // Every prefix of 2^m samples is a (0,m,2)-net: each elementary interval of area 2^-m holds
  // exactly one point. Checked for the pixel jitter, a first-bounce and a deep (bounce 40) request.
  for (const int bounce : {0, 40})
    for (const int m : {0, 1, 2, 3, 4, 5, 6, 7, 8}) {
      INFO("bounce " << bounce << ", 2^" << m << " samples");
      CHECK(elementary_interval_counts(sobol_points({3, 7}, 1 << m, bounce, 3), m) == std::pair{1, 1});
    }
  // Non-powers of two: n = 2^m + 2^(m-1) is a (0,m,2)-net plus a (0,m-1,2)-net, so each interval
  // of area 2^-m holds one or two points (independent sampling leaves some empty, others with 4+).
  for (const int n : {3, 6, 12, 24, 48, 96, 192}) {
    INFO(n << " samples");
    int m = 0;
    while ((2 << m) <= n) ++m;
    CHECK(elementary_interval_counts(sobol_points({1, 2}, n, 2, 1), m) == std::pair{1, 2});
  }
}

TEST_CASE("the Sobol sampler's replicate 1 is another (0,2)-sequence, scrambled independently of replicate 0") {
  // The error estimate (render/error_estimate.h) needs a second net of the same pixel, stratified
  // like the first but with its own scramble.
  for (const int m : {2, 4, 6}) {
    std::vector<Vec2f> first, second;
    Sampler sampler(11, SamplerKind::sobol);
    for (int s = 0; s < 1 << m; ++s) {
      sampler.start_pixel_sample({3, 7}, s, 1);
      second.push_back(sampler.get_2d());
      sampler.start_pixel_sample({3, 7}, s, 0);
      first.push_back(sampler.get_2d());
    }
    INFO("2^" << m << " samples");
    CHECK(elementary_interval_counts(second, m) == std::pair{1, 1});
    int same = 0;
    for (int s = 0; s < 1 << m; ++s) same += first[s].x == second[s].x;
    CHECK(same == 0);
  }
}

TEST_CASE("the Sobol sampler's dimensions are uncorrelated: pixel jitter against a BSDF sample (chi-square)") {
  // The (jitter x, BSDF direction u) pairs of 256 pixels x 64 samples in a 16 x 16 histogram.
  // Padding shuffles each dimension's samples independently, so the pairs are uniform; without
  // it, both would be the same (scrambled) sequence and fill 16 of the 256 cells.
  constexpr int kBins = 16, kPixels = 256, kSpp = 64;
  std::vector<double> count(kBins * kBins, 0);
  Sampler sampler(2, SamplerKind::sobol);
  for (int p = 0; p < kPixels; ++p)
    for (int s = 0; s < kSpp; ++s) {
      sampler.start_pixel_sample({p % 16, p / 16}, s);
      const float jitter = sampler.get_2d().x;
      sampler.start_bounce(0);
      for (int d = 0; d < 3; ++d) sampler.get_1d();  // light choice, light point, lobe choice
      const float u = sampler.get_2d().x;            // the BSDF direction
      ++count[int(jitter * kBins) * kBins + int(u * kBins)];
    }
  const double expected = double(kPixels) * kSpp / (kBins * kBins);
  double statistic = 0;
  for (double c : count) statistic += sqr(c - expected) / expected;
  const double p_value = 1 - test::regularized_gamma_p((kBins * kBins - 1) / 2.0, statistic / 2);
  INFO("chi2 " << statistic << " for " << kBins * kBins - 1 << " degrees of freedom, p " << p_value);
  CHECK(p_value > 1e-3);
}

TEST_CASE("a pixel started once gives each sample the values of that sample started alone") {
  // The renderer calls start_pixel once per pixel and start_sample per sample: whatever the samples
  // before drew (bounces, dimensions), sample s must see what start_pixel_sample(pixel, s) gives.
  for (const SamplerKind kind : {SamplerKind::independent, SamplerKind::sobol})
    for (const int replicate : {0, 1}) {
      Sampler once(5, kind);
      once.start_pixel({6, 2}, replicate);
      for (int s = 0; s < 12; ++s) {
        Sampler alone(5, kind);
        alone.start_pixel_sample({6, 2}, s, replicate);
        once.start_sample(s);
        for (int bounce = 0; bounce < 3; ++bounce) {
          INFO("sampler " << int(kind) << ", replicate " << replicate << ", sample " << s << ", bounce " << bounce);
          const Vec2f a = once.get_2d(), b = alone.get_2d();
          CHECK(a.x == b.x);
          CHECK(a.y == b.y);
          CHECK(once.get_1d() == alone.get_1d());
          once.start_bounce(bounce);
          alone.start_bounce(bounce);
        }
      }
    }
}

TEST_CASE("samplers are deterministic per pixel and sample index") {
  for (const SamplerKind kind : {SamplerKind::independent, SamplerKind::sobol}) {
    Sampler a(9, kind), b(9, kind);
    a.start_pixel_sample({4, 5}, 11);
    a.get_2d();
    b.start_pixel_sample({4, 5}, 11);
    b.get_2d();
    CHECK(a.get_1d() == b.get_1d());
  }
}
