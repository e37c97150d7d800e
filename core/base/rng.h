#pragma once
// Random numbers: the PCG32 generator and integer hashing for deterministic seeding.

#include <cstdint>
#include <cstring>

namespace prism {

// 64-bit finaliser of SplitMix64 (Steele, Lea & Flood 2014): a fast bijective bit mixer.
constexpr uint64_t mix_bits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ull;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dull;
  v ^= v >> 33;
  return v;
}

// hash_ints(a..., b...) = hash_continue(hash_ints(a...), b...): a hash of a common prefix is
// computed once and continued (the sampler's pixel, then each dimension).
template <typename... Args>
constexpr uint64_t hash_continue(uint64_t h, Args... args) {
  ((h = mix_bits(h ^ (uint64_t(args) + 0x632be59bd9b4e019ull))), ...);
  return h;
}
// Hash of any number of integers (order-sensitive).
template <typename... Args>
constexpr uint64_t hash_ints(Args... args) {
  return hash_continue(0x9e3779b97f4a7c15ull, args...);
}

// PCG32: 64-bit LCG state, 32-bit permuted output (O'Neill 2014, "PCG: A Family of Simple Fast
// Space-Efficient Statistically Good Algorithms for Random Number Generation", XSH-RR variant).
class Rng {
 public:
  Rng() = default;
  Rng(uint64_t sequence, uint64_t offset) { set_sequence(sequence, offset); }

  void set_sequence(uint64_t sequence, uint64_t offset) {
    state_ = 0;
    inc_ = (sequence << 1u) | 1u;
    next_u32();
    state_ += offset;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }

  // Uniform float in [0, 1): 24 random mantissa bits, so never rounds up to 1.
  float uniform() { return float(next_u32() >> 8) * 0x1p-24f; }

  // Jumps ahead by delta steps in O(log delta) (Brown 1994, "Random number generation with
  // arbitrary strides").
  void advance(uint64_t delta) {
    uint64_t acc_mult = 1, acc_plus = 0, cur_mult = kMultiplier, cur_plus = inc_;
    while (delta > 0) {
      if (delta & 1) {
        acc_mult *= cur_mult;
        acc_plus = acc_plus * cur_mult + cur_plus;
      }
      cur_plus = (cur_mult + 1) * cur_plus;
      cur_mult *= cur_mult;
      delta /= 2;
    }
    state_ = acc_mult * state_ + acc_plus;
  }

 private:
  static constexpr uint64_t kMultiplier = 0x5851f42d4c957f2dull;
  uint64_t state_ = 0x853c49e6748fea9bull;
  uint64_t inc_ = 0xda3e39cb94b95bdbull;
};

}  // namespace prism
