#pragma once
// Sample generators for Monte Carlo integration. Every (pixel, sample index) pair starts its own
// deterministic stream, so images do not depend on thread count or tile order.

#include <cstdint>

#include "base/rng.h"
#include "base/vec.h"

namespace prism {

// Independent uniform random samples (PCG32 stream per pixel, jumped ahead per sample index).
class IndependentSampler {
 public:
  explicit IndependentSampler(uint64_t seed = 0) : seed_(seed) {}

  void start_pixel_sample(Vec2i pixel, int64_t sample_index) {
    rng_.set_sequence(hash_ints(pixel.x, pixel.y, seed_), 0);
    rng_.advance(uint64_t(sample_index) * 65536ull);
  }
  float get_1d() { return rng_.uniform(); }
  Vec2f get_2d() {
    const float u = rng_.uniform();
    return {u, rng_.uniform()};
  }

 private:
  uint64_t seed_;
  Rng rng_;
};

}  // namespace prism
