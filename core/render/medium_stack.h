#pragma once
// The closed dielectrics a path is inside, innermost last, and the medium it travels through.
// Model (docs/design.md, "The dielectric interface" and "Participating media"): a refraction
// through a front face enters the material, one through a back face leaves it; the index ratio at
// a surface is the material's over that of the medium on its front side, and the medium is the
// innermost material's interior (medium.h) or, outside every closed dielectric, the scene's own
// (fog). Nested objects (a bubble in glass, a liquid in a glass) work when modelled as closed
// surfaces, the inner one inside.

#include <array>

#include "core/render/interaction.h"
#include "materials/material.h"

namespace prism {

class MediumStack {
 public:
  // `outside`: the medium around every closed dielectric (the scene's), or nullptr for vacuum.
  explicit MediumStack(const Medium* outside = nullptr) : outside_(outside && !outside->empty() ? outside : nullptr) {}

  // The innermost dielectric, or nullptr outside them all.
  const Material* innermost() const { return size_ > 0 ? stack_[size_ - 1] : nullptr; }

  // The medium the path is in, or nullptr where light travels unhindered (vacuum, clear glass).
  const Medium* medium() const {
    if (size_ == 0) return outside_;
    const Medium& m = innermost()->dielectric()->interior;
    return m.empty() ? nullptr : &m;
  }

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

  // The medium a ray leaving surface si along w (world) travels through: the path's own on the
  // side it arrived from, the one beyond the surface for a direction through it.
  const Medium* towards(const SurfaceInteraction& si, const Vec3f& w) const {
    if (dot(w, si.n) * dot(si.wo, si.n) >= 0) return medium();
    MediumStack beyond = *this;
    beyond.cross(*si.material, si.front_face());
    return beyond.medium();
  }

  // After a refraction through a surface of m: enters or leaves m if it is a closed volume.
  void cross(const Material& m, bool entering) {
    const Dielectric* d = m.dielectric();
    if (!d || d->thin_walled) return;
    entering ? enter(&m) : leave(&m);
  }

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

  const Medium* outside_;
  std::array<const Material*, 8> stack_{};
  int size_ = 0;
};

}  // namespace prism
