#pragma once
// Small SIMD vectors for the BVH: GCC vector extensions, so that the box and triangle tests read
// like their scalar formulas and compile to SSE, AVX or AVX-512 code for whatever -march allows.

#include <cstdint>

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace prism::simd {

using f4 = float __attribute__((vector_size(16)));
using i4 = int32_t __attribute__((vector_size(16)));
using f8 = float __attribute__((vector_size(32)));
using i8 = int32_t __attribute__((vector_size(32)));

// Eight floats from or to memory, no alignment assumed: one (unaligned) move through a type that
// may alias float. (A memcpy made GCC 12 copy the vector through the stack once more.)
using f8_unaligned = float __attribute__((vector_size(32), aligned(4), may_alias));
inline f8 load(const float* p) { return *reinterpret_cast<const f8_unaligned*>(p); }
inline void store(float* p, f8 v) { *reinterpret_cast<f8_unaligned*>(p) = v; }

// x in every lane. (f8{} + x would cost an addition: 0 + x is not x when x is −0.)
inline f8 broadcast(float x) { return f8{x, x, x, x, x, x, x, x}; }

// |x| lane by lane: the sign bit cleared (one AND, where x < 0 ? −x : x costs a compare and a blend).
inline f8 abs(f8 x) { return f8(i8(x) & (i8{} + 0x7FFFFFFF)); }

// The lane-wise minimum and maximum that ignore a NaN in their first argument: (p − o)/d is NaN
// when a ray lies in a slab's plane, and such a slab must not limit the interval.
template <typename V>
V min_ignore_nan(V candidate, V acc) {
  return candidate < acc ? candidate : acc;
}
template <typename V>
V max_ignore_nan(V candidate, V acc) {
  return candidate > acc ? candidate : acc;
}

// Bit i set when lane i of the comparison result `m` is true.
inline uint32_t bits(i4 m) {
#if defined(__SSE__)
  return uint32_t(_mm_movemask_ps(__m128(m)));
#else
  uint32_t b = 0;
  for (int i = 0; i < 4; ++i) b |= uint32_t(m[i] != 0) << i;
  return b;
#endif
}
inline uint32_t bits(i8 m) {
#if defined(__AVX__)
  return uint32_t(_mm256_movemask_ps(__m256(m)));
#else
  uint32_t b = 0;
  for (int i = 0; i < 8; ++i) b |= uint32_t(m[i] != 0) << i;
  return b;
#endif
}

}  // namespace prism::simd
