#include "core/render/sky.h"

#include "core/base/parallel.h"
#include "core/render/tile_grid.h"
#include "spectral/cie.h"

namespace prism {

std::optional<Xyz> sky_xyz(const World& world, bool first_hit, bool spectral_bins) {
  const auto* sky = world.environment() ? std::get_if<EnvironmentLight>(world.environment()) : nullptr;
  if (!sky || !first_hit || spectral_bins || world.scene_medium())
    return std::nullopt;  // fog: no ray sees it unhindered
  return sampled_xyz_mean(*sky->radiance);
}

std::vector<uint8_t> sky_pixels(const World& world, const Camera& camera) {
  std::vector<uint8_t> sky(size_t(camera.width()) * camera.height(), 0);
  if (camera.has_lens()) return sky;  // its rays leave the whole aperture: none is known to miss
  const TileGrid grid(camera);
  parallel_for(grid.count(), [&](int64_t t) {
    const TileGrid::Tile tile = grid[t];
    const bool whole_tile = !world.accel().may_meet(camera.frustum(tile.x0, tile.y0, tile.x1, tile.y1));
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        sky[size_t(y) * camera.width() + x] = whole_tile || !world.accel().may_meet(camera.frustum(x, y, x + 1, y + 1));
  });
  return sky;
}

}  // namespace prism
