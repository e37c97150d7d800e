#pragma once
// Bsdf<N>: the closed set of BSDFs, and the calls the integrators make on any of them. Every
// lobe offers f (value of its non-delta part), pdf, sample_f, is_specular (all delta) and
// delta_lobes (its delta directions with their weights, for the Whitted tracer), in the local
// shading frame.

#include <optional>
#include <variant>

#include "materials/diffuse_bsdf.h"
#include "materials/layered_bsdf.h"
#include "materials/pbr_bsdf.h"

namespace prism {

template <int N>
using Bsdf = std::variant<DiffuseBsdf<N>, ConductorBsdf<N>, DielectricBsdf<N>, PbrBsdf<N>, LayeredBsdf<N>>;

template <int N>
SampledSpectrum<N> bsdf_f(const Bsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return std::visit([&](const auto& lobe) { return lobe.f(wo, wi); }, b);
}

template <int N>
float bsdf_pdf(const Bsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return std::visit([&](const auto& lobe) { return lobe.pdf(wo, wi); }, b);
}

// f and pdf together: one pass where a lobe shares their work (eval), else the two calls.
template <int N>
BsdfEval<N> bsdf_eval(const Bsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return std::visit([&](const auto& lobe) { return lobe_eval<N>(lobe, wo, wi); }, b);
}

template <int N>
std::optional<BsdfSample<N>> bsdf_sample_f(const Bsdf<N>& b, const Vec3f& wo, float uc, Vec2f u) {
  return std::visit([&](const auto& lobe) { return lobe.sample_f(wo, uc, u); }, b);
}

template <int N>
bool bsdf_is_specular(const Bsdf<N>& b) {
  return std::visit([](const auto& lobe) { return lobe.is_specular(); }, b);
}

template <int N>
DeltaLobes<N> bsdf_delta_lobes(const Bsdf<N>& b, const Vec3f& wo) {
  return std::visit([&](const auto& lobe) { return lobe.delta_lobes(wo); }, b);
}

}  // namespace prism
