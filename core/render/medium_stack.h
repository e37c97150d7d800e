#pragma once
// The closed dielectrics a path is inside, innermost last. Model (docs/design.md, "The dielectric
// interface"):
// a refraction through a front face enters the material, one through a back face leaves it;
// the index ratio at a surface is the material's over that of the medium on its front side,
// and Beer–Lambert absorption applies inside the innermost material. Nested objects (a bubble
// in glass, a liquid in a glass) work when modelled as closed surfaces, the inner one inside.

#include <array>

#include "materials/material.h"

namespace prism {

class MediumStack {
 public:
  // The innermost dielectric, or nullptr in vacuum.
  const Material* innermost() const { return size_ > 0 ? stack_[size_ - 1] : nullptr; }

  // The dielectric on the front (normal) side of a surface of material m hit from the front
  // (entering) or from behind: the medium the path is in, or, leaving m, the one around m.
  const Dielectric* front_dielectric(const Material& m, bool entering) const {
    const Material* front = innermost();
    if (!entering)
      for (int i = size_ - 1; i >= 0; --i)
        if (stack_[i] == &m) {
          front = i > 0 ? stack_[i - 1] : nullptr;
          break;
        }
    return front ? front->dielectric() : nullptr;
  }

  // After a refraction through a surface of m: enters or leaves m if it is a closed volume.
  void cross(const Material& m, bool entering) {
    const Dielectric* d = m.dielectric();
    if (!d || d->thin_walled) return;
    entering ? enter(&m) : leave(&m);
  }

  // σ_a(λ) of the innermost material, or nullptr in vacuum or a clear material.
  const Spectrum* absorption() const {
    const Dielectric* d = innermost() ? innermost()->dielectric() : nullptr;
    return d && d->absorption ? &*d->absorption : nullptr;
  }

  // Beer–Lambert transmittance over a distance inside the innermost material (BeerLambert, below).
  template <int N>
  SampledSpectrum<N> transmittance(float distance, const SampledWavelengths<N>& lambda) const;

 private:
  void enter(const Material* m) {
    if (size_ < int(stack_.size())) stack_[size_++] = m;  // nesting beyond 8 levels is not tracked
  }

  void leave(const Material* m) {
    for (int i = size_ - 1; i >= 0; --i)
      if (stack_[i] == m) {
        for (int j = i; j + 1 < size_; ++j) stack_[j] = stack_[j + 1];
        --size_;
        return;
      }
  }

  std::array<const Material*, 8> stack_{};
  int size_ = 0;
};

// Beer–Lambert transmittance T = exp(−σ_a(λ) d) over a distance d inside a path's innermost
// material; 1 in vacuum or a clear material. σ_a·d → ∞ (a ray escaping an open mesh) and exp
// underflow both give exactly 0, never NaN. σ_a at the path's wavelengths is kept while the path
// stays in one material: the segments between its internal reflections reuse it.
template <int N>
class BeerLambert {
 public:
  SampledSpectrum<N> transmittance(const MediumStack& media, float distance, const SampledWavelengths<N>& lambda) {
    const Spectrum* absorption = media.absorption();
    if (!absorption) return SampledSpectrum<N>(1.f);
    if (absorption != sampled_) sigma_a_ = sample(*absorption, lambda), sampled_ = absorption;
    SampledSpectrum<N> t;
    for (int i = 0; i < N; ++i) t[i] = sigma_a_[i] > 0 ? std::exp(-sigma_a_[i] * distance) : 1.f;
    return t;
  }

 private:
  const Spectrum* sampled_ = nullptr;  // σ_a's spectrum sampled in sigma_a_, none yet
  SampledSpectrum<N> sigma_a_;
};

template <int N>
SampledSpectrum<N> MediumStack::transmittance(float distance, const SampledWavelengths<N>& lambda) const {
  return BeerLambert<N>().transmittance(*this, distance, lambda);
}

}  // namespace prism
