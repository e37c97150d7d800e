#pragma once
// The last few results of a function of one float, kept per thread: for set-ups that depend on a
// material's parameter alone (a roughness's place on a table, a lobe's fitted constants), which a
// path repeats at every hit of the material and which cost more than a look through a few keys.

#include <array>
#include <limits>
#include <optional>
#include <type_traits>

namespace prism {

template <class Value, int Kept>
struct PerThreadCache {
  std::array<float, Kept> keys;
  std::array<std::optional<Value>, Kept> values{};
  int next = 0;

  static constexpr std::array<float, Kept> none = [] {
    std::array<float, Kept> k{};
    k.fill(std::numeric_limits<float>::quiet_NaN());  // equal to no key
    return k;
  }();

  // A new key's value, kept in place of the oldest (out of line: the look-up stays small).
  template <class Compute>
  [[gnu::noinline]] const Value& keep(float key, const Compute& compute) {
    const int i = next;
    keys[i] = key;
    values[i].emplace(compute(key));
    next = (i + 1) % Kept;
    return *values[i];
  }
};

// compute(key), or its result kept from an earlier call with the same key (in this thread, for the
// same compute: each lambda type has its own store). Exact: a key is found only if equal, so
// compute must be a function of the key alone (a lambda without captures), giving the same for −0
// as for +0 (equal keys). NaN keys are never found, so always computed (the build has no
// -ffinite-math-only, which would break the NaN marking an empty place).
// per_thread_cached_ref returns the kept value itself, valid until the next call with the same
// compute in this thread (for values too large to copy at each call).
template <int Kept = 8, class Compute>
const auto& per_thread_cached_ref(float key, const Compute& compute) {
  static_assert(std::is_empty_v<Compute>, "per_thread_cached: compute must depend on the key alone");
  using Store = PerThreadCache<decltype(compute(key)), Kept>;
  // Initialised as a constant, so that no guard is tested at each call; one store per Compute type.
  constinit thread_local Store kept{Store::none};
  for (int i = 0; i < Kept; ++i)
    if (kept.keys[i] == key) return *kept.values[i];
  return kept.keep(key, compute);
}
template <int Kept = 8, class Compute>
auto per_thread_cached(float key, const Compute& compute) {
  return per_thread_cached_ref<Kept>(key, compute);
}

}  // namespace prism
