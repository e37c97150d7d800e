#pragma once
// The last few results of a function of one float, kept per thread: for set-ups that depend on a
// material's parameter alone (a roughness's place on a table, a lobe's fitted constants), which a
// path repeats at every hit of the material and which cost more than a look through a few keys.

#include <array>
#include <limits>
#include <optional>

namespace prism {

// compute(key), or its result kept from an earlier call with the same key (in this thread, for the
// same compute: each lambda type has its own store). Exact: a key is found only if equal.
template <int Kept = 8, class Compute>
auto kept_per_thread(float key, const Compute& compute) {
  using Value = decltype(compute(key));
  thread_local std::array<float, Kept> keys = [] {
    std::array<float, Kept> k;
    k.fill(std::numeric_limits<float>::quiet_NaN());  // equal to no key
    return k;
  }();
  thread_local std::array<std::optional<Value>, Kept> values;
  thread_local int next = 0;
  for (int i = 0; i < Kept; ++i)
    if (keys[i] == key) return *values[i];
  keys[next] = key;
  values[next] = compute(key);
  const Value& v = *values[next];
  next = (next + 1) % Kept;
  return v;
}

}  // namespace prism
