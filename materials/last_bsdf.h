#pragma once
// The BSDF of a path's last scattering point, made again only where the next point's would differ:
// a path inside a closed translucent object (diffuse transmission) meets the same untextured
// material hit after hit, and a layered BSDF costs about as much to build as to sample. The key is
// all that make_bsdf reads: the material, the front medium, the material's inputs at the point
// and the point's other attributes (its texture coordinates reach the BSDF only through the
// inputs). For one path: its wavelengths must not change between calls.

#include <cstddef>
#include <new>
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

  [[gnu::always_inline]] const Bsdf<N>& of(const Material& m, const SurfacePoint& at, const SampledWavelengths<N>& lambda,
                    const Dielectric* front) {
    if (bsdf_ && &m == key_.material && front == key_.front) {  // the same material again: compare the rest
      const Key key = key_of(m, at, front);
      if (key == key_) return *bsdf_;
      key_ = key;
    } else {
      ::new (&key_) Key(key_of(m, at, front));
    }
    // Built where it is kept (a prvalue initialises the object in place): a copy cost as much as building it.
    const auto* pbr = std::get_if<PbrMaterial>(&m.kind);
    bsdf_ = std::launder(::new (storage_) Bsdf<N>(pbr ? make_bsdf(*pbr, key_.inputs, key_.at, lambda, front)
                                                      : make_bsdf(m, key_.at, lambda, front)));
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
  static Key key_of(const Material& m, const SurfacePoint& at, const Dielectric* front) {
    const auto* pbr = std::get_if<PbrMaterial>(&m.kind);
    Key key{&m, front, pbr ? pbr->inputs(at) : SurfaceInputs{}, at};
    key.at.uv = {};
    return key;
  }
  static_assert(std::is_trivially_destructible_v<Bsdf<N>> && std::is_trivially_destructible_v<Key>);  // replaced in place
  alignas(Bsdf<N>) std::byte storage_[sizeof(Bsdf<N>)];
  const Bsdf<N>* bsdf_ = nullptr;  // none yet
  Key key_{};
};

}  // namespace prism
