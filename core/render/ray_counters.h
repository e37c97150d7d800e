#pragma once
// Rays traced, counted per kind (primary = camera rays, secondary = bounce rays, shadow =
// visibility tests for light sampling).

#include <cstdint>

namespace prism {

struct RayCounters {
  uint64_t primary = 0, secondary = 0, shadow = 0;

  RayCounters& operator+=(const RayCounters& o) {
    primary += o.primary;
    secondary += o.secondary;
    shadow += o.shadow;
    return *this;
  }
};

}  // namespace prism
