#pragma once
// The recursive Fresnel-splitting ray tracer of Whitted 1980 ("An Improved Illumination Model
// for Shaded Display", CACM 23(6)): at a dielectric both the reflected and the refracted ray
// are traced, weighted by the Fresnel reflectance and transmittance; a metal traces its
// reflection weighted by its Fresnel reflectance; a diffuse surface takes direct light through
// shadow rays (every point, spot and directional light, plus one sample of the area lights and
// environment); misses see the environment. Per wavelength: a dispersive interface splits the
// path's wavelengths into one trace each. Noise-free for delta lights, and a reference for
// Fresnel scenes.

#include "core/base/sampler.h"
#include "core/render/path_integrator.h"
#include "core/render/ray_counters.h"
#include "core/render/world.h"

namespace prism {

template <int N>
SampledSpectrum<N> whitted_radiance(const World& world, const Ray& ray, const SampledWavelengths<N>& lambda,
                                    Sampler& sampler, const PathOptions& options, RayCounters& counters);

}  // namespace prism
