#include "materials/sheen_albedo.h"

#include <algorithm>
#include <cmath>

#include "base/math.h"
#include "materials/albedo_tables.h"

namespace prism {

using namespace albedo_tables;

const SheenAlbedo& SheenAlbedo::table() {
  static const SheenAlbedo t;
  return t;
}

float SheenAlbedo::scale(float alpha) const {
  const float y = std::sqrt(std::clamp(alpha, 0.f, 1.f)) * (kSheenAlpha - 1);
  const int j = std::min(int(y), kSheenAlpha - 2);
  return lerp(y - float(j), sheen_scale[j], sheen_scale[j + 1]);
}

SheenAlbedo::Roughness SheenAlbedo::roughness(float alpha) {
  const float y = std::sqrt(std::clamp(alpha, 0.f, 1.f)) * (kSheenAlpha - 1);
  const int j = std::min(int(y), kSheenAlpha - 2);
  return {j, y - float(j)};
}

float SheenAlbedo::E(float mu, const Roughness& r) const {
  const float x = std::sqrt(std::clamp(mu, 0.f, 1.f)) * (kSheenMu - 1);
  const int i = std::min(int(x), kSheenMu - 2);
  const float tx = x - float(i), ty = r.t;
  const float* e = sheen_e + r.j * kSheenMu + i;
  return (1 - ty) * ((1 - tx) * e[0] + tx * e[1]) + ty * ((1 - tx) * e[kSheenMu] + tx * e[kSheenMu + 1]);
}

}  // namespace prism
