#!/usr/bin/env python3
"""Why the clear-coated and sheen assets render darker in Prism than in Cycles, on the smallest
scene that shows it: a Lambertian plane (glTF base colour ρ, specularFactor 0) under a uniform
white environment, seen straight on by an orthographic camera, bare, under a smooth clear coat
(factor 1, index 1.5), under a sheen (colour 1, roughness 0.5) and under the base's own specular
layer (specularFactor 1; the others have 0), each with ρ = 0.5 and ρ = 0. Renders them with Prism
and with Blender 3.4 Cycles (the harness in tools/cycles of the shared assets, PRISM_SHARED_DIR,
which scales Principled v1's clearcoat by 4 to undo its 0.25) and separates each layer into:

  the layer's own reflection        L(layer, ρ = 0)
  what the base keeps under it      (L(layer, ρ) − L(layer, 0)) / L(bare, ρ)

The model difference it shows: KHR_materials_clearcoat and _sheen layer the base under the top
lobe, which lets through only what it does not reflect. Prism scales the base by the coat's
transmittance on the way in and out, (1 − c E_c(μ_o))(1 − c E_c(μ_i)) (a smooth coat: E_c = F,
so the base keeps (1 − F(1))(1 − F_avg) = 0.872 of its light seen straight on, η = 1.5), and by
1 − s E_sheen under a sheen. Cycles 3.4's Principled v1 adds its clearcoat lobe on top of an
undimmed base, and Blender's importer adds a Velvet BSDF (Ashikhmin's, not the Charlie sheen) to the
Principled BSDF with an Add Shader: the base keeps 1.000 of its light under both. The layers' own
reflections agree for the coat (F(1) = 0.04 in both) and differ for the sheen (the two fibre
distributions). The same holds, smaller, for the base's own specular layer (specularFactor 1):
Prism's diffuse keeps 1 − E(μ_o) of its light under it (0.986), Cycles' all of it; that layer's own
reflection at roughness 1 is 0.014 in Prism and 0.013 in Cycles 3.4 (single scattering). The
plane has no volume, so it is a thin wall, which reflects as one interface over its base when
opaque (tools/specular_cycles.py checks this at normal incidence).
SpecularTest's difference is tools/specular_cycles.py's.

    tools/layering_cycles.py [--spp 64] [--size 32] [--out out/layering_cycles]

Skips (exit 0) without the shared assets or Blender.
"""
import argparse
import os
import sys

from cycles_pair import add_common_args, fresnel, harness, mean_y, plane_scene, render_pair
ETA = 1.5  # the clear coat's index (KHR_materials_clearcoat)


def scene(rho, layer):
    """A 2 m square at z = 0 facing +z, filling an orthographic camera's view from z = 1."""
    extensions = {"KHR_materials_specular": {"specularFactor": 1.0 if layer == "specular" else 0.0}}
    if layer == "coat":
        extensions["KHR_materials_clearcoat"] = {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.0}
    elif layer == "sheen":
        extensions["KHR_materials_sheen"] = {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5}
    material = {"name": "plane", "extensions": extensions,
                "pbrMetallicRoughness": {"baseColorFactor": [rho, rho, rho, 1], "metallicFactor": 0, "roughnessFactor": 1}}
    return plane_scene("tools/layering_cycles.py", material, view=0.5)


def fresnel_average(eta, n=100000):
    """F_avg = 2 ∫ F(μ) μ dμ, by the midpoint rule."""
    return sum(2 * fresnel((k + 0.5) / n, eta) * (k + 0.5) / n for k in range(n)) / n


def render(a, exrstats, rho, layer):
    common = ["--spp", str(a.spp), "--width", str(a.size), "--height", str(a.size), "--env", "1,1,1"]
    prism_exr, cycles_exr = render_pair("layering_cycles", a, os.path.join(a.out, "%s_%g" % (layer, rho)),
                                        scene(rho, layer), ["--max-depth", "4"] + common,
                                        ["--max-bounces", "3", "--filter", "box", "--filter-width", "1"] + common)
    return mean_y(exrstats, prism_exr), mean_y(exrstats, cycles_exr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--size", type=int, default=32, help="image width and height (default 32)")
    ap.add_argument("--rho", type=float, default=0.5, help="the base colour's grey (default 0.5)")
    add_common_args(ap, "layering_cycles")
    a = ap.parse_args()
    a.harness = harness("layering_cycles", a.shared)
    if a.harness is None:
        return 0
    import exrstats

    f0, f_avg = fresnel(1.0, ETA), fresnel_average(ETA)
    print("Lambertian plane ρ = %g under a white environment, seen straight on; %d spp, %dx%d; image means (Y)."
          % (a.rho, a.spp, a.size, a.size))
    bare = render(a, exrstats, a.rho, "bare")
    print("%-7s %-34s %9s %9s %s" % ("layer", "quantity", "Prism", "Cycles", "model"))
    print("%-7s %-34s %9.4f %9.4f ρ = %g (Cycles: Burley's diffuse)" % ("none", "L(bare, ρ)", *bare, a.rho))
    for layer in ("coat", "sheen", "specular"):
        alone, under = render(a, exrstats, 0.0, layer), render(a, exrstats, a.rho, layer)
        kept = [(u - o) / b for u, o, b in zip(under, alone, bare)]
        own = {"coat": "F(1) = %.4f in both" % f0, "sheen": "Charlie (Prism) vs Ashikhmin's velvet (Cycles)",
               "specular": "the base's own GGX layer (roughness 1)"}[layer]
        keeps = {"coat": "glTF layering (1 − F(1))(1 − F_avg) = %.4f; additive (Cycles v1) 1" % ((1 - f0) * (1 - f_avg)),
                 "sheen": "glTF layering 1 − s E_sheen < 1; additive (Add Shader) 1",
                 "specular": "coupled diffuse 1 − E(1) < 1; additive (Cycles v1) 1"}[layer]
        print("%-7s %-34s %9.4f %9.4f %s" % (layer, "own reflection L(layer, 0)", *alone, own))
        print("%-7s %-34s %9.4f %9.4f %s" % (layer, "base kept (L(layer,ρ) − L(layer,0))/L", *kept, keeps))
    return 0


if __name__ == "__main__":
    sys.exit(main())
