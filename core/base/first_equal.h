#pragma once
// Finding copies: for each of n items, the first item equal to it, so that copies share one
// piece of work (a mesh's BVH, its shading arrays).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/base/rng.h"

namespace prism {

// The bytes of a contiguous array (a vector, a span).
template <class Array>
std::string_view bytes_of(const Array& a) {
  const auto s = std::as_bytes(std::span(a));
  return {reinterpret_cast<const char*>(s.data()), s.size()};
}

// A hash of arrays' bytes, in order (std::hash of bytes, which hashes a large mesh's arrays many
// times faster than a byte-at-a-time FNV-1a).
template <class... Array>
uint64_t hash_bytes(const Array&... arrays) {
  uint64_t h = 0;
  ((h = hash_continue(h, std::hash<std::string_view>{}(bytes_of(arrays)))), ...);
  return h;
}

// Bit for bit (−0 ≠ +0, NaNs by their bits).
template <class Array>
bool same_bytes(const Array& a, const Array& b) {
  return a.size() == b.size() && bytes_of(a) == bytes_of(b);
}

// For every i < n, the smallest j ≤ i with equal(i, j): items grouped by hash(i), then compared in full.
template <class Hash, class Equal>
std::vector<uint32_t> first_equal(uint32_t n, Hash hash, Equal equal) {
  std::vector<uint32_t> out(n);
  std::unordered_map<uint64_t, std::vector<uint32_t>> firsts;
  for (uint32_t i = 0; i < n; ++i) {
    std::vector<uint32_t>& group = firsts[hash(i)];
    const auto first = std::find_if(group.begin(), group.end(), [&](uint32_t j) { return equal(i, j); });
    out[i] = first != group.end() ? *first : group.emplace_back(i);
  }
  return out;
}

}  // namespace prism
