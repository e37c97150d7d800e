#pragma once
// FNV-1a, 64 bits (Fowler, Noll, Vo; IETF draft-eastlake-fnv): a fast checksum of bytes, for
// detecting damaged files and telling scene files apart (not against deliberate tampering).

#include <cstdint>
#include <string_view>

namespace prism {

struct Checksum {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* p, uint64_t n) {
    for (const auto* b = static_cast<const unsigned char*>(p); n--; ++b) h = (h ^ *b) * 0x100000001b3ull;
  }
  void add(std::string_view s) { add(s.data(), s.size()); }
};

}  // namespace prism
