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
template <typename V = f8>
V broadcast(float x) {
  if constexpr (sizeof(V) == sizeof(f4))
    return V{x, x, x, x};
  else
    return V{x, x, x, x, x, x, x, x};
}

// Four lanes then four more as one eight-lane vector (from memory: one load into the upper half).
inline f8 join(f4 lo, f4 hi) { return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7); }

// |x| lane by lane: the sign bit cleared (one AND, where x < 0 ? −x : x costs a compare and a blend).
template <typename V>
V abs(V x) {
  using I = decltype(x < x);  // the integer vector of V's width
  return V(I(x) & (I{} + 0x7FFFFFFF));
}

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
