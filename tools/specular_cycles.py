#!/usr/bin/env python3
"""Why SpecularTest renders darker in Prism than in Cycles, on the smallest scene that shows it: a smooth black dielectric plane (glTF base colour 0, roughness 0) under a uniform white
environment, tilted by θ from an orthographic camera, so that every pixel is the Fresnel
reflectance at that one angle. Rendered with Prism and with Blender 3.4 Cycles (the harness in
tools/cycles of the shared assets, PRISM_SHARED_DIR, which sets Principled v1's Specular from KHR_materials_specular) for
specularFactor s = 0.2 and 1 and specularColorFactor c = 0.2, and compared with the two models:

  glTF (KHR_materials_specular)   R = s · F(θ, η_c),  η_c the index of F0 = min(F0(1.5) · c, 1)
                                  (the factor scales F0 and F90 alike: F90 = s)
  Principled v1 (Cycles 3.4)      R = F(θ, η'),  η' the index of F0' = s · min(F0(1.5) · c, 1)
                                  (Specular sets F0 alone; F90 stays 1)

Cycles equals its model at every angle to 4 digits, and so does Prism. The models agree at normal
incidence and for s = 1; for s < 1 glTF's reflection fades to s at grazing and Cycles' rises to 1
(s = 0.2 at 80°: 0.078 against 0.284): SpecularTest's first two rows (specularFactor and
specularTexture below 1) are darker in Prism by that model difference. The plane also checks the
thin wall: a glTF material without KHR_materials_volume is thin-walled, and an opaque thin wall
reflects as one interface over its base (0.040 at normal incidence), not with a sheet's two faces'
R + T²R/(1 − R²) (0.077).

    tools/specular_cycles.py [--spp 16] [--size 16] [--out out/specular_cycles]

Skips (exit 0) without the shared assets or Blender.
"""
import argparse
import math
import os
import sys

from cycles_pair import add_common_args, fresnel, harness, mean_y, plane_scene, render_pair
F0_15 = 0.04  # ((1.5 - 1) / (1.5 + 1))², the default index's normal reflectance


def scene(theta_deg, factor, color):
    """A 2 m square through the origin, tilted by θ about x, seen along −z from z = 1."""
    half = math.radians(theta_deg) / 2
    specular = {"specularFactor": factor, "specularColorFactor": [color] * 3}
    material = {"name": "plane", "extensions": {"KHR_materials_specular": specular},
                "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 0}}
    return plane_scene("tools/specular_cycles.py", material, view=0.1, rotation=[math.sin(half), 0, 0, math.cos(half)])


def ior_of_f0(f0):
    root = min(f0, 0.9999) ** 0.5
    return (1 + root) / (1 - root)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--size", type=int, default=16, help="image width and height (default 16)")
    add_common_args(ap, "specular_cycles")
    a = ap.parse_args()
    a.harness = harness("specular_cycles", a.shared)
    if a.harness is None:
        return 0
    import exrstats

    common = ["--spp", str(a.spp), "--width", str(a.size), "--height", str(a.size), "--env", "1,1,1"]
    print("Smooth black dielectric plane at θ from the view, white environment; %d spp, %dx%d; image means (Y)."
          % (a.spp, a.size, a.size))
    print("%-5s %-5s %4s %9s %9s %9s %9s" % ("s", "c", "θ", "Prism", "glTF", "Cycles", "Princ.v1"))
    for factor, color in ((1.0, 1.0), (0.2, 1.0), (1.0, 0.2)):
        for theta in (0, 60, 80):
            work = os.path.join(a.out, "s%g_c%g_t%d" % (factor, color, theta))
            prism_exr, cycles_exr = render_pair("specular_cycles", a, work, scene(theta, factor, color),
                                                ["--max-depth", "4"] + common,
                                                ["--max-bounces", "3", "--filter", "box", "--filter-width", "1"] + common)
            mu = math.cos(math.radians(theta))
            f0 = min(F0_15 * color, 1.0)
            gltf_model = factor * fresnel(mu, ior_of_f0(f0))
            principled = fresnel(mu, ior_of_f0(factor * f0))
            print("%-5g %-5g %4d %9.4f %9.4f %9.4f %9.4f" % (factor, color, theta, mean_y(exrstats, prism_exr), gltf_model,
                                                            mean_y(exrstats, cycles_exr), principled))
    return 0


if __name__ == "__main__":
    sys.exit(main())
