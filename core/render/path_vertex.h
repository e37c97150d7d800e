#pragma once
// A vertex of a light subpath, kept for the connections a camera subpath makes to it, and the
// partial sums that give every connection its MIS weight in O(1) (van Antwerpen 2011;
// Georgiev et al. 2012, "Light Transport Simulation with Vertex Connection and Merging",
// tech. report eqs. 31–37: dVCM, dVC and dVM).

#include "core/base/frame.h"
#include "core/render/interaction.h"
#include "materials/bsdf.h"

namespace prism {

// The power heuristic's weight term (β = 2): the MIS sums hold mis(p_other / p_this) ratios.
inline float mis(float x) { return x * x; }

// How merging weighs against connecting: with η = π r² · (light paths), vm = mis(η) and
// vc = mis(1 / η) (Georgiev et al. 2012 eq. 22); both 0 for bidirectional path tracing alone.
struct MisFactors {
  float vm = 0, vc = 0;
  static MisFactors vcm(float radius, float light_paths) {
    const float eta = kPi * radius * radius * light_paths;
    return {mis(eta), mis(1.f / eta)};
  }
};

// Partial sums of one subpath at its last vertex: vcm = mis of the reverse density ratio up to
// the previous vertex, vc and vm = the sums over the farther connection and merging strategies.
struct MisSums {
  float vcm = 0, vc = 0, vm = 0;

  // After arriving at a vertex over distance t (the light's first segment from an infinite light
  // has no distance) with |cos| cos_in of the geometric normal: eq. 31.
  void arrive(float t, float cos_in, bool with_distance) {
    if (with_distance) vcm *= mis(t * t);
    const float c = mis(cos_in);
    vcm /= c, vc /= c, vm /= c;
  }
  // After scattering: sampling density pdf_dir (solid angle) of the new direction, pdf_rev of
  // the reverse, |cos| cos_out of the new direction at the geometric normal (eqs. 34–36); a
  // specular (delta) sample can be made by no other strategy.
  void scatter(float pdf_dir, float pdf_rev, float cos_out, bool specular, const MisFactors& f) {
    if (specular) {
      vcm = 0, vc *= mis(cos_out), vm *= mis(cos_out);
      return;
    }
    const float g = mis(cos_out / pdf_dir), r = mis(pdf_rev);
    vc = g * (vc * r + vcm + f.vm);
    vm = g * (vm * r + vcm * f.vc + 1.f);
    vcm = mis(1.f / pdf_dir);
  }
  // The weight term of the farther strategies of a connection at this vertex, whose BSDF has
  // density pdf_rev of sampling the reverse direction.
  float connection(float pdf_rev, const MisFactors& f) const { return f.vm + vcm + vc * mis(pdf_rev); }
};

template <int N>
struct LightVertex {
  SurfaceInteraction si;
  Frame frame;
  Bsdf<N> bsdf;
  Vec3f wo;                 // local: towards the previous vertex, where the light came from
  SampledSpectrum<N> beta;  // Le · Π f·cos / pdf from the light to here (importance transport)
  MisSums mis;
  int length;      // segments from the light
  bool hero_only;  // a dispersive interface on the way here left only the hero wavelength valid

  // The factor of leaving towards w (world, unit) that makes the adjoint BSDF with shading
  // normals: f(w, wo) · |ns·wo| · |ng·w| / |ng·wo| (Veach 1997 §5.3, eq. 5.19). f takes the
  // camera-side direction first, as the path tracer's does, so that both estimate one integral.
  SampledSpectrum<N> adjoint_f(const Vec3f& w_local, const Vec3f& w) const {
    return bsdf_f(bsdf, w_local, wo) * (abs_cos_theta(wo) * abs_dot(si.n, w) / abs_dot(si.n, si.wo));
  }
};

}  // namespace prism
