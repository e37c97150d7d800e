#pragma once
// Exact sums for the film: a value v is rounded once to the integer round(v · 2^bits) and kept
// in 128 bits. Integer addition is associative, so sums of the same samples in any grouping
// (threads, passes, sample ranges and tiles rendered on other machines) have the same bits.
//
// Range: |v| < kFixedLimit = 2^31 and at most 2^32 samples per pixel keep every sum below
// 2^(31+56+32) = 2^119 at kFixedBits, and Σ v² below 2^(62+32+32) = 2^126 at kFixedSquareBits.
// Resolution: 2^-56 ≈ 1.4e-17 for values, 2^-32 ≈ 2.3e-10 for squares (the error estimate only).

#include <cmath>
#include <cstdint>

namespace prism {

using Fixed = __int128;

constexpr int kFixedBits = 56;
constexpr int kFixedSquareBits = 32;
constexpr double kFixedLimit = 2147483648.0;  // 2^31

// Whether v can be summed exactly (finite and |v| < kFixedLimit).
inline bool fixed_in_range(double v) { return std::fabs(v) < kFixedLimit; }  // false for NaN too

// v · 2^bits is exact (a power of two) like ldexp(v, bits), which costs a call per sample; most values
// fit in 64 bits, whose conversion needs no 128-bit library routine.
inline Fixed to_fixed(double v, int bits = kFixedBits) {
  const double r = std::nearbyint(v * double(uint64_t(1) << bits));
  return std::fabs(r) < 0x1p63 ? Fixed(int64_t(r)) : Fixed(r);
}

inline double to_double(Fixed f, int bits = kFixedBits) { return std::ldexp(double(f), -bits); }

}  // namespace prism
