#pragma once
// The frame cut into squares of kTileSize pixels (the last row and column cut short), numbered row
// by row: the renderer's unit of parallel work.

#include <algorithm>
#include <cstdint>

#include "core/render/camera.h"

namespace prism {

struct TileGrid {
  static constexpr int kTileSize = 16;

  int width, height, across, down;
  explicit TileGrid(const Camera& camera)
      : width(camera.width()),
        height(camera.height()),
        across((width + kTileSize - 1) / kTileSize),
        down((height + kTileSize - 1) / kTileSize) {}
  int64_t count() const { return int64_t(across) * down; }
  struct Tile {
    int x0, y0, x1, y1;  // its pixels x0 ≤ x < x1, y0 ≤ y < y1
  };
  Tile operator[](int64_t t) const {
    const int x0 = int(t % across) * kTileSize, y0 = int(t / across) * kTileSize;
    return {x0, y0, std::min(x0 + kTileSize, width), std::min(y0 + kTileSize, height)};
  }
};

}  // namespace prism
