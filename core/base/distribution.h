#pragma once
// Piecewise-constant distributions for sampling tabulated functions in proportion to their
// values: 1D by inverting the CDF, 2D as a marginal density over rows times a conditional one
// within the chosen row (pbrt-v4 §A.5.4 and §A.5.6).

#include <span>
#include <vector>

#include "core/base/vec.h"

namespace prism {

// A non-negative f over [0, 1) in n equal buckets. Zero everywhere is sampled uniformly, so the
// pdf stays a density and callers need no special case.
class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  explicit PiecewiseConstant1D(std::span<const float> f);

  struct Sample {
    float x;    // in [0, 1)
    float pdf;  // f(x) / ∫f
    int bucket;
    float within;  // x's place in its bucket, in [0, 1]
  };
  // Never lands in a bucket of f = 0 (unless all are).
  Sample sample(float u) const;
  float pdf(int bucket) const { return integral_ > 0 ? f_[bucket] / integral_ : 1.f; }
  int size() const { return int(f_.size()); }
  float integral() const { return integral_; }  // ∫₀¹ f = Σ f / n

 private:
  std::vector<float> f_, cdf_;
  float integral_ = 0;
};

// A non-negative f over [0, 1)² on an nu × nv grid, f[v · nu + u], row v = 0 first.
class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  PiecewiseConstant2D(std::span<const float> f, int nu, int nv);

  struct Sample {
    Vec2f p;    // in [0, 1)²
    float pdf;  // f(p) / ∫f
  };
  // u.y picks the row from the marginal, u.x the column within it.
  Sample sample(Vec2f u) const;
  float pdf(Vec2f p) const;

 private:
  std::vector<PiecewiseConstant1D> conditional_;  // one per row
  PiecewiseConstant1D marginal_;                  // over rows, of their integrals
};

}  // namespace prism
