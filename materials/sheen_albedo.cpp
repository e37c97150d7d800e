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

float SheenAlbedo::E(float mu, float alpha) const {
  const float x = std::sqrt(std::clamp(mu, 0.f, 1.f)) * (kSheenMu - 1);
  const float y = std::sqrt(std::clamp(alpha, 0.f, 1.f)) * (kSheenAlpha - 1);
  const int i = std::min(int(x), kSheenMu - 2), j = std::min(int(y), kSheenAlpha - 2);
  const float tx = x - float(i), ty = y - float(j);
  const float* e = sheen_e + j * kSheenMu + i;
  return (1 - ty) * ((1 - tx) * e[0] + tx * e[1]) + ty * ((1 - tx) * e[kSheenMu] + tx * e[kSheenMu + 1]);
}

}  // namespace prism
