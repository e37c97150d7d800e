#pragma once
// Exact sums for the film: a value v is rounded once to the integer round(v · 2^bits) and kept
// in 128 bits. Integer addition is associative, so sums of the same samples in any grouping
// (threads, passes, sample ranges and tiles rendered on other machines) have the same bits.
//
// Range: |v| < kFixedLimit = 2^31 and at most 2^32 samples per pixel keep every sum below
// 2^(31+56+32) = 2^119 at kFixedBits, and Σ v² below 2^(62+32+32) = 2^126 at kFixedSquareBits.
// Resolution: 2^-56 ≈ 1.4e-17 for values, 2^-32 ≈ 2.3e-10 for squares (the error estimate only).
// Larger finite values (up to the largest float, 2^128, and their squares) are rounded to
// integers and summed apart in WideSum, exactly too: a pixel that meets one keeps a few of them
// (film.h), the others pay nothing.

#include <array>
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

// An exact signed integer sum of 320 bits (two's complement in 64-bit words, least significant
// first), for values at or above kFixedLimit: each added value is rounded to an integer once, and
// 2^32 of the squares of the largest floats, below 2^288, still fit.
class WideSum {
 public:
  static constexpr int kWords = 5;

  // Adds round(v) `times` times; v finite and |v| < 2^256.
  void add(double v, uint64_t times = 1) {
    int exponent = 0;
    const double fraction = std::frexp(std::nearbyint(std::fabs(v)), &exponent);  // in [0.5, 1), or 0
    // round(|v|) = mantissa · 2^shift exactly, with a mantissa of 53 bits at most.
    unsigned __int128 mantissa = uint64_t(std::ldexp(fraction, 53));
    int shift = exponent - 53;
    for (; shift < 0 && mantissa > 0; ++shift) mantissa >>= 1;  // an integer: the bits shifted out are 0
    if (shift < 0) return;                                      // round(v) = 0
    mantissa *= times;                                          // below 2^85
    WideSum t;
    const int word = shift / 64, bit = shift % 64;
    // mantissa << bit spans at most three words from `word` (85 + 63 bits).
    const unsigned __int128 low = mantissa << bit;
    const uint64_t high = bit == 0 ? 0 : uint64_t(mantissa >> (128 - bit));
    const uint64_t parts[3] = {uint64_t(low), uint64_t(low >> 64), high};
    for (int i = 0; i < 3 && word + i < kWords; ++i) t.words_[word + i] = parts[i];
    if (v < 0) t.negate();
    *this += t;
  }

  WideSum& operator+=(const WideSum& o) {
    unsigned carry = 0;
    for (int i = 0; i < kWords; ++i) {
      const unsigned __int128 s = (unsigned __int128)words_[i] + o.words_[i] + carry;
      words_[i] = uint64_t(s);
      carry = unsigned(s >> 64);
    }
    return *this;
  }

  // The sum as a double (rounded).
  double to_double() const {
    WideSum m = *this;
    const bool negative = words_[kWords - 1] >> 63;
    if (negative) m.negate();
    double r = 0;
    for (int i = kWords - 1; i >= 0; --i) r += std::ldexp(double(m.words_[i]), 64 * i);
    return negative ? -r : r;
  }

  bool operator==(const WideSum&) const = default;
  const std::array<uint64_t, kWords>& words() const { return words_; }
  std::array<uint64_t, kWords>& words() { return words_; }

 private:
  void negate() {
    unsigned carry = 1;
    for (uint64_t& w : words_) {
      const unsigned __int128 s = (unsigned __int128)(~w) + carry;
      w = uint64_t(s);
      carry = unsigned(s >> 64);
    }
  }

  std::array<uint64_t, kWords> words_{};
};

}  // namespace prism
