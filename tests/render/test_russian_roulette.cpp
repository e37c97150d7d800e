// Russian roulette's termination probability (core/render/russian_roulette.h); that it leaves
// the estimate unbiased is the furnace tests' (test_furnace.cpp) end to end.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/render/russian_roulette.h"

using namespace prism;

TEST_CASE(
    "Russian roulette leaves a path alone until its throughput halves, then continues with probability sqrt(2t)") {
  for (const float t : {0.5f, 0.75f, 1.f, 3.f, INFINITY, NAN}) CHECK(roulette_termination(t) == 0);
  for (const float t : {1e-6f, 0.02f, 0.125f, 0.3f, 0.49f}) {
    INFO(t);
    const float q = roulette_termination(t);
    CHECK(1 - q == Approx(std::sqrt(2 * t)).epsilon(1e-4));  // 1 - q rounded in float
    CHECK(q < 1);  // a path that survives is divided by 1 - q: the estimate stays unbiased
  }
  CHECK(roulette_termination(0) == 1);  // nothing left to carry
}
