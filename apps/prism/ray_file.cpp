#include "apps/prism/ray_file.h"

#include <bit>
#include <cstring>
#include <fstream>

#include "core/base/error.h"

namespace prism {

static_assert(std::endian::native == std::endian::little, "the ray and hit files are little-endian");

namespace {

constexpr uint32_t kVersion = 1;

struct Header {
  char magic[4];
  uint32_t version;
  uint64_t count;
};
static_assert(sizeof(Header) == 16);

struct RayRecord {
  float ox, oy, oz, tmin, dx, dy, dz, tmax;
};
static_assert(sizeof(RayRecord) == 32 && sizeof(HitRecord) == 8);

}  // namespace

std::vector<Ray> read_rays(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot open", file.string());
  Header h;
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h) || std::memcmp(h.magic, "RAYS", 4) != 0)
    fail("{}: not a RAYS file", file.string());
  if (h.version != kVersion) fail("{}: RAYS version {}, expected {}", file.string(), h.version, kVersion);
  const uint64_t expected_size = sizeof(Header) + h.count * sizeof(RayRecord);
  if (h.count > (uint64_t(1) << 32) || std::filesystem::file_size(file) != expected_size)
    fail("{}: {} bytes, but a file of {} rays has {}", file.string(), std::filesystem::file_size(file), h.count,
         expected_size);
  std::vector<RayRecord> records(h.count);
  in.read(reinterpret_cast<char*>(records.data()), std::streamsize(h.count * sizeof(RayRecord)));
  if (!in) fail("{}: cannot read the rays", file.string());
  std::vector<Ray> rays;
  rays.reserve(records.size());
  for (const RayRecord& r : records) {
    if (r.tmin != 0.f) fail("{}: ray {} has tmin {}; Prism's rays start at 0", file.string(), rays.size(), r.tmin);
    rays.push_back({{r.ox, r.oy, r.oz}, {r.dx, r.dy, r.dz}, r.tmax});
  }
  return rays;
}

void write_hits(const std::filesystem::path& file, const std::vector<HitRecord>& hits) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  const Header h{{'H', 'I', 'T', 'S'}, kVersion, hits.size()};
  out.write(reinterpret_cast<const char*>(&h), sizeof h);
  out.write(reinterpret_cast<const char*>(hits.data()), std::streamsize(hits.size() * sizeof(HitRecord)));
  if (!out) fail("{}: cannot write the hits", file.string());
}

}  // namespace prism
