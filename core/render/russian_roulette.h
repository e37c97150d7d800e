#pragma once
// Russian roulette (Arvo & Kirk 1990): a path whose throughput, relative to where it started, has
// fallen to t ends with probability q and otherwise is divided by 1 − q, so the estimate stays
// unbiased. It continues with probability min(1, √(2t)): no roulette until the throughput has
// halved, and then later than Cycles' min(1, √t): less variance per sample (the most through
// absorbing glass) for few more rays (docs/performance.md, "Sampling choices"). The path tracer
// decides it where the path meets its next surface, never on a ray that leaves for the sky.

#include <algorithm>
#include <cmath>

namespace prism {

// q for relative throughput t (0 at t ≥ 1/2, and for a NaN t).
inline float roulette_termination(float t) { return std::max(0.f, 1.f - std::sqrt(2 * t)); }

}  // namespace prism
