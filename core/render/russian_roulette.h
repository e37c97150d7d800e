#pragma once
// Russian roulette (Arvo & Kirk 1990): a path whose throughput, relative to where it started, has
// fallen to t ends with probability q and otherwise is divided by 1 − q, so the estimate stays
// unbiased. It continues with probability min(1, √t), as Cycles does: paths end later than with
// min(1, t), for less roulette noise at little more time (measured in issue 10). The path tracer
// decides it where the path meets its next surface, never on a ray that leaves for the sky.

#include <algorithm>
#include <cmath>

namespace prism {

// q for relative throughput t (0 at t ≥ 1, and for a NaN t).
inline float roulette_termination(float t) { return std::max(0.f, 1.f - std::sqrt(t)); }

}  // namespace prism
