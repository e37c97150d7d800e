#include "core/base/distribution.h"

#include <algorithm>

#include "core/base/error.h"

namespace prism {

PiecewiseConstant1D::PiecewiseConstant1D(std::span<const float> f) : f_(f.begin(), f.end()), cdf_(f.size() + 1) {
  if (f_.empty()) fail("a piecewise-constant distribution needs at least one bucket");
  const size_t n = f_.size();
  double sum = 0;  // in double: a long run of small values must not stall the running sum
  for (size_t i = 0; i < n; ++i) {
    if (!(f_[i] >= 0 && std::isfinite(f_[i]))) fail("a piecewise-constant distribution needs finite values ≥ 0");
    sum += f_[i];
  }
  integral_ = float(sum / double(n));
  double acc = 0;
  for (size_t i = 0; i < n; ++i) {
    acc += sum > 0 ? f_[i] / sum : 1.0 / double(n);
    cdf_[i + 1] = float(acc);
  }
  cdf_.back() = 1.f;
}

PiecewiseConstant1D::Sample PiecewiseConstant1D::sample(float u) const {
  // The bucket with cdf[o] ≤ u < cdf[o + 1]; empty buckets have no such u.
  const int n = size();
  const int o = std::clamp(int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1, 0, n - 1);
  const float width = cdf_[o + 1] - cdf_[o];
  const float du = width > 0 ? clamp((u - cdf_[o]) / width, 0.f, 1.f) : 0.f;
  const float x = std::min(float((double(o) + du) / n), 0x1.fffffep-1f);
  return {x, pdf(o), o, du};
}

PiecewiseConstant2D::PiecewiseConstant2D(std::span<const float> f, int nu, int nv) {
  if (nu <= 0 || nv <= 0 || f.size() != size_t(nu) * nv)
    fail("2D distribution of {}x{} has {} values", nu, nv, f.size());
  std::vector<float> row_integrals(nv);
  conditional_.reserve(nv);
  for (int v = 0; v < nv; ++v) {
    conditional_.emplace_back(f.subspan(size_t(v) * nu, nu));
    row_integrals[v] = conditional_.back().integral();
  }
  marginal_ = PiecewiseConstant1D(row_integrals);
}

PiecewiseConstant2D::Sample PiecewiseConstant2D::sample(Vec2f u) const {
  const auto row = marginal_.sample(u.y);
  const auto column = conditional_[row.bucket].sample(u.x);
  return {{column.x, row.x}, column.pdf * row.pdf};
}

float PiecewiseConstant2D::pdf(Vec2f p) const {
  const int nv = marginal_.size(), nu = conditional_[0].size();
  const int v = std::clamp(int(p.y * float(nv)), 0, nv - 1), u = std::clamp(int(p.x * float(nu)), 0, nu - 1);
  return conditional_[v].pdf(u) * marginal_.pdf(v);
}

}  // namespace prism
