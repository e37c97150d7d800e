#pragma once
// The passes of a progressive render: pass k takes every pixel from the samples it has up to
// pass_end(k). The ends are fixed (1, 2, 4, 8, 16, then every 16 more), whatever the total,
// so a render stopped after any pass, or a sample range [pass_end(a), pass_end(b)) rendered
// elsewhere, is made of the same samples as a straight render with that many samples.

#include <algorithm>

namespace prism {

constexpr int kPassStride = 16;  // samples per pass once the first passes have doubled up to it

// Samples every pixel has after pass k (k = 0, 1, ...), for a render of at most `spp`.
constexpr int pass_end(int k, int spp) {
  const int end = k < 4 ? 1 << k : kPassStride * (k - 3);
  return std::min(end, spp);
}

// Passes a render of `spp` samples takes.
constexpr int pass_count(int spp) {
  int k = 0;
  while (pass_end(k, spp) < spp) ++k;
  return k + 1;
}

}  // namespace prism
