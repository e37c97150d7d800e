#pragma once
// Bsdf<N>: the closed set of BSDF lobes, and the calls the integrators make on any of them.
// Every lobe offers f (value), pdf, sample_f and is_specular, in the local shading frame.

#include <optional>
#include <variant>

#include "materials/conductor_bsdf.h"
#include "materials/dielectric_bsdf.h"
#include "materials/diffuse_bsdf.h"

namespace prism {

template <int N>
using Bsdf = std::variant<DiffuseBsdf<N>, ConductorBsdf<N>, DielectricBsdf<N>>;

template <int N>
SampledSpectrum<N> bsdf_f(const Bsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return std::visit([&](const auto& lobe) { return lobe.f(wo, wi); }, b);
}

template <int N>
float bsdf_pdf(const Bsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return std::visit([&](const auto& lobe) { return lobe.pdf(wo, wi); }, b);
}

template <int N>
std::optional<BsdfSample<N>> bsdf_sample_f(const Bsdf<N>& b, const Vec3f& wo, float uc, Vec2f u) {
  return std::visit([&](const auto& lobe) { return lobe.sample_f(wo, uc, u); }, b);
}

template <int N>
bool bsdf_is_specular(const Bsdf<N>& b) {
  return std::visit([](const auto& lobe) { return lobe.is_specular(); }, b);
}

}  // namespace prism
