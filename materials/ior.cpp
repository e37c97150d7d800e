#include "materials/ior.h"

namespace prism {

bool is_dispersive(const IorModel& model) {
  if (std::holds_alternative<ConstantIor>(model)) return false;
  if (const auto* a = std::get_if<AbbeIor>(&model)) return std::isfinite(a->vd) && a->vd > 0;
  const float n0 = ior(model, kLambdaMin);
  for (float l = kLambdaMin; l <= kLambdaMax; l += 1.f)
    if (ior(model, l) != n0) return true;
  return false;
}

float abbe_number(const IorModel& model) {
  constexpr float kD = 587.56f, kF = 486.13f, kC = 656.27f;  // Fraunhofer lines [nm]
  return (ior(model, kD) - 1) / (ior(model, kF) - ior(model, kC));
}

}  // namespace prism
