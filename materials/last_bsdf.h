#pragma once
// The BSDF of a path's last scattering point, made again only where the next point's would differ:
// a path inside a closed translucent object (diffuse transmission) meets the same untextured
// material hit after hit, and a layered BSDF (LayeredBsdf) costs about as much to build as to
// sample; the others are made at every point, cheaper than comparing. The key is
// all that make_bsdf reads: the material, the front medium, the material's inputs at the point
// and the point's other attributes (make_bsdf reads the texture coordinates only through the
// inputs). For one path: its wavelengths must not change between calls.

#include <cstddef>
#include <new>
#include <optional>
#include <type_traits>

#include "materials/bsdf.h"
#include "materials/material.h"

namespace prism {

template <int N>
class LastBsdf {
 public:
  LastBsdf() = default;
  LastBsdf(const LastBsdf&) = delete;  // bsdf_ points into storage_
  LastBsdf& operator=(const LastBsdf&) = delete;

  // Inlined into the path's loop, what only layered BSDFs need kept out of line (kept small, it
  // leaves GCC's inlining budget to the rest of the loop).
  [[gnu::always_inline]] const Bsdf<N>& of(const Material& m, const SurfacePoint& at,
                                           const SampledWavelengths<N>& lambda, const Dielectric* front) {
    if (key_ && key_->material == &m && same_key(m, at, front)) return *bsdf_;
    // Built where it is kept (a prvalue initialises the object in place): a copy cost as much as building it.
    bsdf_ = std::launder(::new (storage_) Bsdf<N>(make_bsdf(m, at, lambda, front)));
    if (std::holds_alternative<LayeredBsdf<N>>(*bsdf_))
      keep(m, at, front);
    else  // cheaper to build again than to compare
      key_.reset();
    return *bsdf_;
  }

 private:
  struct Key {
    const Material* material;
    const Dielectric* front;
    SurfaceInputs inputs;
    SurfacePoint at;  // without its texture coordinates
    bool operator==(const Key&) const = default;
  };
  static Key key_of(const Material& m, const SurfacePoint& at, const Dielectric* front) {  // m: a PbrMaterial
    Key key{&m, front, std::get<PbrMaterial>(m.kind).inputs(at), at};
    key.at.uv = {};
    return key;
  }
  [[gnu::noinline]] bool same_key(const Material& m, const SurfacePoint& at, const Dielectric* front) const {
    return key_of(m, at, front) == *key_;
  }
  [[gnu::noinline]] void keep(const Material& m, const SurfacePoint& at, const Dielectric* front) {
    key_ = key_of(m, at, front);
  }
  static_assert(std::is_trivially_destructible_v<Bsdf<N>>);  // replaced without being destroyed
  alignas(Bsdf<N>) std::byte storage_[sizeof(Bsdf<N>)];
  const Bsdf<N>* bsdf_ = nullptr;  // none yet
  std::optional<Key> key_;         // the kept BSDF's, when it is a LayeredBsdf
};

}  // namespace prism
