#pragma once
// Sample generators for Monte Carlo integration. Every (pixel, sample index, seed) triple
// addresses its own sample, whatever the total count, so images do not depend on thread count,
// tile order or how a pixel's samples are split into passes or across machines.
//   sobol (default): the (0,2)-sequence of Sobol's first two dimensions, Owen-scrambled and with
//                its samples shuffled independently for every requested dimension ("padded"),
//                so that each 1D or 2D request is stratified over a pixel's samples and
//                different dimensions are uncorrelated (Burley 2020, "Practical Hash-based Owen
//                Scrambling", JCGT 9(4)). The shuffle is itself a nested scramble of the index,
//                so a pixel's first 2^j samples are always one aligned block of the sequence, a
//                (0,j,2)-net: any count n is the union of the nets of n's binary digits, so it is
//                stratified at every count, not only at powers of two.
//                `replicate` > 0 gives the pixel further, independently scrambled copies of its
//                sequence (randomized QMC replicates, Owen 1997, "Monte Carlo variance of
//                scrambled net quadrature"), from which the error is estimated
//                (render/error_estimate.h).
//   independent: uniform random numbers (a PCG32 stream per pixel, jumped ahead per sample).

#include <cstdint>
#include <type_traits>
#ifdef __GFNI__
#include <immintrin.h>
#endif

#include "core/base/rng.h"
#include "core/base/vec.h"

namespace prism {

enum class SamplerKind { independent, sobol };

namespace sobol {

// Bit i to bit 31 − i. With GFNI (x86), one affine transform over GF(2) reverses each byte's bits
// (the matrix of 0x8040201008040201) and a byte swap does the rest: 4 instructions for 13, on the
// path of every sampler draw (3 reversals per 2D sample).
constexpr uint32_t reverse_bits(uint32_t v) {
#ifdef __GFNI__
  if (!std::is_constant_evaluated()) {
    const __m128i bytes_reversed =
        _mm_gf2p8affine_epi64_epi8(_mm_cvtsi32_si128(int(v)), _mm_set1_epi64x(0x8040201008040201), 0);
    return __builtin_bswap32(uint32_t(_mm_cvtsi128_si32(bytes_reversed)));
  }
#endif
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

// A hash in which every bit depends only on itself and lower bits (Laine & Karras 2011).
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Owen scrambling of a base-2 fraction x (as 32 bits) is this hash of its reversed bits, reversed
// back (the nested uniform scramble); it takes x already reversed, which callers often have.
inline uint32_t owen_scramble_reversed(uint32_t reversed_x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reversed_x, seed));
}

// Sobol's first two dimensions: the van der Corput sequence (dimension 0: i's bits reversed) and
// the Pascal matrix mod 2 (dimension 1). Dimension 1 is the XOR of the direction numbers v_j (v_0 = 2^31, v_j+1 = v_j ^
// v_j >> 1) of i's set bits; tabulated per byte of i, so four lookups replace a loop over 32 bits. The table holds the
// v_j with their bits reversed, as the nested scramble takes them, which saves that reversal per sample.
struct Dimension1Table {
  uint32_t byte[4][256];
};
constexpr Dimension1Table make_reversed_dimension1_table() {
  uint32_t v[32] = {1u << 31};
  for (int j = 1; j < 32; ++j) v[j] = v[j - 1] ^ (v[j - 1] >> 1);
  Dimension1Table t{};
  for (int k = 0; k < 4; ++k)
    for (uint32_t b = 0; b < 256; ++b)
      for (int j = 0; j < 8; ++j)
        if (b >> j & 1) t.byte[k][b] ^= reverse_bits(v[8 * k + j]);
  return t;
}
inline constexpr Dimension1Table kReversedDimension1 = make_reversed_dimension1_table();
// reverse_bits(dimension 1 of i).
constexpr uint32_t reversed_dimension1(uint32_t i) {
  return kReversedDimension1.byte[0][i & 255] ^ kReversedDimension1.byte[1][i >> 8 & 255] ^
         kReversedDimension1.byte[2][i >> 16 & 255] ^ kReversedDimension1.byte[3][i >> 24];
}

constexpr float to_unit(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

}  // namespace sobol

class Sampler {
 public:
  explicit Sampler(uint64_t seed = 0, SamplerKind kind = SamplerKind::sobol) : seed_(seed), kind_(kind) {}

  void start_pixel_sample(Vec2i pixel, int64_t sample_index, int replicate = 0) {
    start_pixel(pixel, replicate);
    start_sample(sample_index);
  }
  // start_pixel_sample in two steps, for a renderer that takes many samples of one pixel: what
  // depends on the pixel (and replicate) alone once, then each sample.
  void start_pixel(Vec2i pixel, int replicate = 0) {
    pixel_hash_ = replicate == 0 ? hash_ints(pixel.x, pixel.y, seed_) : hash_ints(pixel.x, pixel.y, seed_, replicate);
    pixel_state_ = hash_ints(pixel_hash_);
  }
  void start_sample(int64_t sample_index) {
    reversed_index_ = sobol::reverse_bits(uint32_t(sample_index));
    dimension_ = 0;
    if (kind_ == SamplerKind::independent) {
      rng_.set_sequence(pixel_hash_, 0);
      rng_.advance(uint64_t(sample_index) * 65536ull);
    }
  }

  // Dimensions in a fixed layout: the camera's (pixel jitter, wavelengths) first, then a block of
  // kBounceDimensions per bounce, so each dimension serves one purpose in every sample of a pixel
  // even when a path skips a draw (no light sample at a specular vertex, no roulette at the
  // first), and stays stratified over the pixel's samples at any depth.
  static constexpr uint32_t kCameraDimensions = 2, kBounceDimensions = 8;
  void start_bounce(int depth) { dimension_ = kCameraDimensions + uint32_t(depth) * kBounceDimensions; }

  float get_1d() {
    if (kind_ == SamplerKind::independent) return rng_.uniform();
    const uint64_t h = dimension_hash();
    return sobol::to_unit(scrambled_dimension0(shuffled(h), uint32_t(h >> 32)));
  }

  Vec2f get_2d() {
    if (kind_ == SamplerKind::independent) {
      const float u = rng_.uniform();
      return {u, rng_.uniform()};
    }
    const uint64_t h = dimension_hash();
    const uint32_t i = shuffled(h), h2 = uint32_t(mix_bits(h));
    return {sobol::to_unit(scrambled_dimension0(i, uint32_t(h >> 32))), sobol::to_unit(scrambled_dimension1(i, h2))};
  }

 private:
  // hash_ints(pixel hash, dimension) for the next dimension, its first round (the pixel's) done
  // once per pixel in start_pixel.
  uint64_t dimension_hash() { return hash_continue(pixel_state_, dimension_++); }
  // This dimension's own permutation of the pixel's sample indices (padding): the nested
  // scramble of the index, with its bit reversal done once per sample.
  uint32_t shuffled(uint64_t h) const { return sobol::owen_scramble_reversed(reversed_index_, uint32_t(h)); }
  // Dimension 0 of sample i, Owen-scrambled: the nested scramble of reverse_bits(i), whose inner
  // reversals cancel.
  static uint32_t scrambled_dimension0(uint32_t i, uint32_t seed) { return sobol::owen_scramble_reversed(i, seed); }
  // Dimension 1 of sample i, Owen-scrambled: the nested scramble, its inner reversal tabulated.
  static uint32_t scrambled_dimension1(uint32_t i, uint32_t seed) {
    return sobol::owen_scramble_reversed(sobol::reversed_dimension1(i), seed);
  }

  uint64_t seed_;
  SamplerKind kind_;
  Rng rng_;
  uint64_t pixel_hash_ = 0, pixel_state_ = 0;
  uint32_t reversed_index_ = 0, dimension_ = 0;
};

}  // namespace prism
