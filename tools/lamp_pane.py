#!/usr/bin/env python3
"""Why LightsPunctualLamp differs from Cycles, on the smallest scenes that show it:
a point light 5 cm behind a rough pane with glTF's thin-walled transmission (the lamp's shade: an
open sheet, roughness 0.6, transmission 1, no KHR_materials_volume), and 5 cm in front of a
Lambertian plane, each seen straight on by an orthographic camera. Renders both with Prism
(--no-energy-compensation: the single-scattering lobes Cycles 3.4 has) and Blender 3.4 Cycles (the
harness in tools/cycles of the shared assets, PRISM_SHARED_DIR; COMPAT units), and compares them
with answers computed here:

  plane       ρ I cos θ / (π d²);
  thin wall   f_t(wo, wi) I |cos θ_i| / d², f_t the GGX reflection lobe mirrored through the sheet
              (glTF's thin wall; T = 1 − 2R/(1 + R) for its two faces, or 1 − R for one);
  solid       Walter et al. 2007's rough refraction into index 1.5, the light taken to be inside
              the glass, with and without the 1/η² that radiance takes on leaving it.

    tools/lamp_pane.py [--spp 256] [--size 128] [--out out/lamp_pane]

Skips (exit 0) without the shared assets or Blender. tests/render/test_punctual_lights.cpp checks Prism
against the same thin-wall answer in every test run.
"""
import argparse
import os
import sys

from cycles_pair import add_common_args, harness, plane_scene, render_pair
DEPTH, HALF, INTENSITY, ETA = 0.05, 0.1, 1.0, 1.5  # light 5 cm from a 20 cm square, 1 cd, index 1.5


def scene(kind, roughness):
    """A 2·HALF square at z = 0 facing +z, the point light DEPTH behind it (pane) or in front (plane)."""
    pbr = {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": roughness}
    if kind == "pane":
        material = {"name": "pane", "pbrMetallicRoughness": pbr, "doubleSided": True,
                    "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}
    else:
        material = {"name": "plane", "pbrMetallicRoughness": pbr,
                    "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    light = (-DEPTH if kind == "pane" else DEPTH, {"type": "point", "intensity": INTENSITY})
    return plane_scene("tools/lamp_pane.py", material, half=HALF, view=HALF, light=light)


# ----------------------------------------------------------------------------- the answers
def directions(np, n, sub=8):
    """Per sub-pixel: the unit direction to the light (pane's frame, normal +z) and d²."""
    t = (np.arange(n * sub) + 0.5) / (n * sub) * 2 * HALF - HALF
    x, y = np.meshgrid(t, -t)  # image row 0 is +y
    def at(z):
        d2 = x * x + y * y + z * z
        r = np.sqrt(d2)
        return np.stack([-x / r, -y / r, np.full_like(x, z) / r]), d2
    return at


def pixels(np, a, n, sub=8):
    return a.reshape(n, sub, n, sub).mean((1, 3))


def ggx(np, roughness):
    a2 = roughness ** 4
    D = lambda c: a2 / (np.pi * (c * c * (a2 - 1) + 1) ** 2)
    lam = lambda c: (np.sqrt(1 + a2 * (1 - c * c) / (c * c)) - 1) / 2
    return D, lam


def fresnel(np, c, eta):
    c = np.abs(c)
    s2 = (1 - c * c) / eta ** 2
    ct = np.sqrt(np.maximum(0, 1 - s2))
    rs, rp = (c - eta * ct) / (c + eta * ct), (eta * c - ct) / (eta * c + ct)
    return np.where(s2 >= 1, 1.0, (rs * rs + rp * rp) / 2)


def plane_answer(np, n):
    wi, d2 = directions(np, n)(DEPTH)
    return pixels(np, INTENSITY * wi[2] / d2 / np.pi, n)


def thin_wall_answer(np, n, roughness, two_faces=True):
    D, lam = ggx(np, roughness)
    wi, d2 = directions(np, n)(-DEPTH)
    m = wi * np.array([1, 1, -1.0])[:, None, None] + np.array([0, 0, 1.0])[:, None, None]
    m /= np.linalg.norm(m, axis=0)
    R = fresnel(np, m[2], ETA)
    T = 1 - 2 * R / (1 + R) if two_faces else 1 - R
    ci = np.abs(wi[2])
    f = T * D(m[2]) / (1 + lam(1.0) + lam(ci)) / (4 * ci)
    return pixels(np, f * INTENSITY * ci / d2, n)


def solid_answer(np, n, roughness, radiance_scaling):
    """The viewer in air over glass of index ETA that holds the light: m ∝ −(wo + η wi)."""
    D, lam = ggx(np, roughness)
    wi, d2 = directions(np, n)(-DEPTH)
    wo = np.array([0, 0, 1.0])[:, None, None] * np.ones_like(wi)
    m = -(wo + ETA * wi)
    m /= np.linalg.norm(m, axis=0)
    m = np.where(m[2] < 0, -m, m)
    om, im = (wo * m).sum(0), (wi * m).sum(0)
    ci = np.abs(wi[2])
    f = (1 - fresnel(np, om, ETA)) * D(m[2]) / (1 + lam(1.0) + lam(ci)) * np.abs(om * im) * ETA ** 2 / (ci * (om + ETA * im) ** 2)
    if radiance_scaling:
        f /= ETA ** 2
    return pixels(np, np.where((om > 0) & (im < 0), f, 0) * INTENSITY * ci / d2, n)


# ----------------------------------------------------------------------------- renders
def load(exrstats, np, path):
    img = exrstats.read_exr(path)
    names = exrstats.rgb_names(list(img["channels"]))
    g = np.asarray(img["channels"][names[1]], dtype=np.float64)
    return g.reshape(img["height"], img["width"])


def render(a, kind, roughness):
    common = ["--spp", str(a.spp), "--width", str(a.size), "--height", str(a.size)]
    return render_pair("lamp_pane", a, os.path.join(a.out, kind), scene(kind, roughness),
                       ["--no-energy-compensation"] + common,
                       ["--lighting-mode", "COMPAT", "--filter", "box", "--filter-width", "1"] + common)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--size", type=int, default=128, help="image width and height (default 128)")
    ap.add_argument("--roughness", type=float, default=0.6, help="the pane's glTF roughness (the shade's: 0.6)")
    add_common_args(ap, "lamp_pane")
    a = ap.parse_args()
    a.harness = harness("lamp_pane", a.shared)
    if a.harness is None:
        return 0
    try:
        import numpy as np
    except ImportError:
        print("lamp_pane: SKIPPED: numpy not importable (run it with /usr/bin/python3)")
        return 0
    import exrstats

    n, c = a.size, slice(a.size // 2 - 4, a.size // 2 + 4)
    print("Point light %.0f cm from a %.0f cm square, %d spp, %dx%d, Prism --no-energy-compensation, Cycles COMPAT."
          % (100 * DEPTH, 200 * HALF, a.spp, n, n))
    print("%-44s %12s %12s %14s %14s" % ("answer", "image mean", "centre 8x8", "Prism / it", "Cycles / it"))
    for kind, answers in (("plane", [("Lambert: I cos θ / (π d²)", lambda: plane_answer(np, n))]),
                          ("pane", [("thin wall, two faces (glTF thin wall)", lambda: thin_wall_answer(np, n, a.roughness)),
                                    ("thin wall, one face (the extension's sketch)",
                                     lambda: thin_wall_answer(np, n, a.roughness, False)),
                                    ("solid glass, no 1/η² (Cycles' reading)",
                                     lambda: solid_answer(np, n, a.roughness, False)),
                                    ("solid glass with 1/η²", lambda: solid_answer(np, n, a.roughness, True))])):
        prism_exr, cycles_exr = render(a, kind, a.roughness)
        p, cy = load(exrstats, np, prism_exr), load(exrstats, np, cycles_exr)
        print("%s (roughness %.2f): Prism mean %.4f centre %.3f, Cycles mean %.4f centre %.3f"
              % (kind, a.roughness, p.mean(), p[c, c].mean(), cy.mean(), cy[c, c].mean()))
        for name, answer in answers:
            e = answer()
            print("  %-42s %12.4f %12.3f %7.4f %6.4f %7.4f %6.4f"
                  % (name, e.mean(), e[c, c].mean(), p.mean() / e.mean(), p[c, c].mean() / e[c, c].mean(),
                     cy.mean() / e.mean(), cy[c, c].mean() / e[c, c].mean()))
    print("(ratios: image mean, then centre)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
