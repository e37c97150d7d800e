#pragma once
// raybench's binary ray and hit files (tools/raybench/README.md in the shared assets,
// PRISM_SHARED_DIR: "Binary formats"), so that Prism and Embree trace the same rays and their
// answers can be compared ray for ray.
// Little-endian: a 4-byte magic, uint32 version 1, uint64 count, then the records.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/base/ray.h"

namespace prism {

// One HITS.bin record: the hit distance and raybench's global triangle id.
struct HitRecord {
  float t;
  uint32_t prim;

  static constexpr uint32_t kMiss = 0xFFFFFFFF;
  static constexpr uint32_t kOccluded = 0xFFFFFFFE;  // an any-hit query hit something
  static HitRecord miss() { return {kInfinity, kMiss}; }
  static HitRecord occluded() { return {0.f, kOccluded}; }
};

// Reads RAYS.bin. Prism's rays start at t = 0, so a ray with another tmin is refused.
std::vector<Ray> read_rays(const std::filesystem::path& file);

void write_hits(const std::filesystem::path& file, const std::vector<HitRecord>& hits);

}  // namespace prism
