#include "spectral/white_balance.h"

#include "spectral/cie.h"

namespace prism {

namespace {

using Mat3 = std::array<double, 9>;

// XYZ to the Bradford cone space (Lam 1985) and back.
constexpr Mat3 kBradford = {0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296};

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
  return r;
}

Mat3 inverse(const Mat3& m) {
  const double det =
      m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  return {(m[4] * m[8] - m[5] * m[7]) / det, (m[2] * m[7] - m[1] * m[8]) / det, (m[1] * m[5] - m[2] * m[4]) / det,
          (m[5] * m[6] - m[3] * m[8]) / det, (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
          (m[3] * m[7] - m[4] * m[6]) / det, (m[1] * m[6] - m[0] * m[7]) / det, (m[0] * m[4] - m[1] * m[3]) / det};
}

std::array<double, 3> times(const Mat3& m, const Xyz& v) {
  return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
          m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

}  // namespace

WhiteBalance WhiteBalance::to_d65(std::string name, const Xyz& from) {
  // Both whites at Y = 1: the balance changes colours, never the exposure.
  const Xyz to = spectrum_to_xyz(cie().d65), source{from.x / from.y, 1.f, from.z / from.y};
  const std::array<double, 3> cone_from = times(kBradford, source), cone_to = times(kBradford, to);
  Mat3 scale{};
  for (int i = 0; i < 3; ++i) scale[i * 4] = cone_to[i] / cone_from[i];
  const Mat3 m = multiply(inverse(kBradford), multiply(scale, kBradford));
  WhiteBalance wb{std::move(name), source, {}};
  for (int i = 0; i < 9; ++i) wb.m[i] = float(m[i]);
  return wb;
}

Xyz WhiteBalance::operator()(const Xyz& v) const {
  return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
          m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

void WhiteBalance::apply(float* xyz, size_t n) const {
  for (size_t i = 0; i < n; ++i) {
    const Xyz a = (*this)({xyz[i * 3], xyz[i * 3 + 1], xyz[i * 3 + 2]});
    xyz[i * 3] = a.x, xyz[i * 3 + 1] = a.y, xyz[i * 3 + 2] = a.z;
  }
}

}  // namespace prism
