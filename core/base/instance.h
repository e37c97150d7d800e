#pragma once
// A mesh placed in the world: what a Scene lists and the accel traces (the same array, not a copy).

#include <cstdint>

#include "core/base/transform.h"

namespace prism {

struct Instance {
  uint32_t mesh;             // index into the scene's meshes
  AffineTransform to_world;  // object to world
};

}  // namespace prism
