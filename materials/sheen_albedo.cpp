#include "materials/sheen_albedo.h"

#include "core/base/math.h"

namespace prism {

using namespace albedo_tables;

float SheenAlbedo::scale(float alpha) {
  const Lerp a = sheen_alpha_node(alpha);
  return lerp(a.t, sheen_scale[a.i], sheen_scale[a.i + 1]);
}

SheenAlbedo::Curve SheenAlbedo::curve(float alpha) {
  const Lerp a = sheen_alpha_node(alpha);
  const float* below = sheen_e + a.i * kSheenMu;
  Curve c;
  for (int m = 0; m < kSheenMu; ++m) c.e[m] = (1 - a.t) * below[m] + a.t * below[kSheenMu + m];
  return c;
}

}  // namespace prism
