#pragma once
// BsdfCache: a cache of the BSDFs one path makes, so that a point whose BSDF would be the same as
// one already made reuses it instead of making it again. A path inside a closed translucent object
// (diffuse transmission) meets the same untextured material hit after hit, and a layered BSDF
// (LayeredBsdf) costs about as much to make as to sample. Only layered BSDFs are kept; the others,
// and those of textured materials, are made at every point (cheaper than comparing), beside the
// kept one, which stays for a later hit on its material (a path from a sphere to the floor and
// back). The key is everything make_bsdf reads but the wavelengths: the material, the front
// medium, the material's inputs at the point and the point's other attributes (make_bsdf reads the
// texture coordinates only through the inputs). One cache per path, whose wavelengths do not
// change between calls.

#include <cstddef>
#include <new>
#include <optional>
#include <type_traits>

#include "materials/bsdf.h"
#include "materials/make_bsdf.h"

namespace prism {

template <int N>
class BsdfCache {
 public:
  BsdfCache() = default;
  BsdfCache(const BsdfCache&) = delete;  // the BSDFs returned are in storage_
  BsdfCache& operator=(const BsdfCache&) = delete;

  // The BSDF of m at `at`: the kept one when make_bsdf would make the same, else a new one. Inlined
  // into the path's loop; the comparison, which only a layered material met again needs, stays out
  // of line (same_point), so that the compiler's inlining budget goes to the rest of the loop. The
  // kept point's inputs are found only then: most layered hits are not followed by another on the
  // same material, and would pay for their inputs twice.
  [[gnu::always_inline]] const Bsdf<N>& of(const Material& m, const SurfacePoint& at,
                                           const SampledWavelengths<N>& lambda, const Dielectric* front) {
    if (kept_ && kept_->material == &m && kept_->front == front && same_point(at)) return *kept_bsdf();
    // Built where it is kept (a prvalue initialises the object in place): a copy cost as much as
    // building it. Built in the place the kept BSDF does not hold; a layered one is kept instead.
    const int slot = kept_ ? 1 - kept_slot_ : 0;
    const Bsdf<N>* bsdf = ::new (storage_[slot]) Bsdf<N>(make_bsdf(m, at, lambda, front));
    if (std::holds_alternative<LayeredBsdf<N>>(*bsdf)) {
      kept_ = Kept{&m, front, at, std::nullopt};
      kept_slot_ = slot;
    }
    return *bsdf;
  }

 private:
  // What make_bsdf read, but the wavelengths: the material, the front medium and the point; of the
  // point, the material's inputs there (once found) and its attributes but the texture coordinates.
  struct Kept {
    const Material* material;
    const Dielectric* front;
    SurfacePoint at;
    std::optional<SurfaceInputs> inputs;
  };
  static SurfacePoint without_uv(SurfacePoint at) {
    at.uv = {};
    return at;
  }
  // Whether make_bsdf at `at` reads what it read at the kept point (same material and front).
  // By value: −0 equals +0, which could build another BSDF only from a coat normal in the surface
  // (z = ±0). A textured material's inputs differ from point to point: not worth comparing. Inputs
  // read from no texture depend on the point's other attributes alone, which are equal here.
  [[gnu::noinline]] bool same_point(const SurfacePoint& at) {
    const PbrMaterial& material = std::get<PbrMaterial>(kept_->material->kind);
    if (material.textured() || !(without_uv(at) == without_uv(kept_->at))) return false;
    if (!kept_->inputs) kept_->inputs = material.inputs(kept_->at);
    return !kept_->inputs->textured || material.inputs(at) == *kept_->inputs;
  }

  const Bsdf<N>* kept_bsdf() const { return std::launder(reinterpret_cast<const Bsdf<N>*>(storage_[kept_slot_])); }

  static_assert(std::is_trivially_destructible_v<Bsdf<N>>);  // replaced without being destroyed
  // Two places: the kept layered BSDF's, and the last other BSDF's.
  alignas(Bsdf<N>) std::byte storage_[2][sizeof(Bsdf<N>)];
  int kept_slot_ = 0;         // the kept BSDF's place
  std::optional<Kept> kept_;  // what the kept BSDF was made of (a LayeredBsdf), if any
};

}  // namespace prism
